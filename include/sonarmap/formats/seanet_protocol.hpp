#pragma once
/// @file seanet_protocol.hpp
/// Tritech SeaNet, the serial protocol of the Micron and SeaKing imaging heads: the packet framing
/// (one encoder, one incremental parser), the host's commands and the head's replies. The readers
/// of raw captures (seanet_capture.hpp), the capture encoder (wire_encoder.hpp), the live driver
/// (devices/seanet_driver.hpp) and the emulator (devices/seanet_emulator.hpp) all use this file.
///
/// Sources, read and cross-checked, not copied: rock-drivers `drivers-sonar_tritech` (commit
/// 8c33dca, `SeaNetTypesInternal.cpp`, `SeaNet.cpp`, `SeaNetMicron.cpp`, `SeaNetProfiling.cpp`),
/// mcgill-robotics `ros-tritech-micron` (commit 4722dd6, `sonar.py`, `commands.py`, `replies.py`),
/// RobDos `Tritech-Micron-Driver` (commit c55d747, `message_types.h`, `tritech_micron_driver.cpp`:
/// the driver that recorded ../shared/data/micron_pool_ros1.bag), Emilio Garcia-Fidalgo's
/// `libminiking` (`SonarDefs.h`, `MtVersionData.cpp`, `MtBBUserData.cpp`); ../shared/docs/formats.md.
///
/// Packet (little-endian): byte 0 '@'; 1–4 the length as 4 ASCII hex digits; 5–6 the same length
/// as uint16 (it counts bytes 7 … the byte before the LF: a packet is length + 6 bytes); 7 the
/// sender's node (the host is 255, an imaging head 2); 8 the receiver's node; 9 the byte count
/// (length − 5 in every message the drivers send and check, 0 in a single-packet mtHeadData);
/// 10 the message type; 11 the sequence (bit 7: last packet of a message, 0x80 for a whole one);
/// 12 the head's node (also in the host's commands); 13 … the payload; the last byte LF (0x0A).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap::seanet {

/// Message types (packet byte 10), numbered as every driver above numbers them.
enum class MessageType : std::uint8_t {
  kVersionData = 1,   ///< head → host: identity (mtVersionData)
  kHeadData = 2,      ///< head → host: one beam (mtHeadData)
  kAlive = 4,         ///< head → host: about once a second, its state (mtAlive)
  kBBUserData = 6,    ///< head → host: its configuration block (mtBBUserData)
  kAuxData = 8,       ///< head → host: an auxiliary port's bytes (mtAuxData)
  kReBoot = 16,       ///< host → head: restart, forgetting the parameters (mtReBoot)
  kHeadCommand = 19,  ///< host → head: the scan parameters (mtHeadCommand)
  kSendVersion = 23,  ///< host → head: ask for mtVersionData (mtSendVersion)
  kSendBBUser = 24,   ///< host → head: ask for mtBBUserData (mtSendBBUser)
  kSendData = 25,     ///< host → head: ask for the next beam (mtSendData)
  kStopAlive = 66,    ///< host → head: stop sending mtAlive (mtStopAlives)
};

/// "mtAlive" for 4, "message type 77" for a type this file does not name.
std::string messageTypeName(std::uint8_t type);

inline constexpr std::uint8_t kHostNode = 255;   ///< the host's node (every driver)
inline constexpr std::uint8_t kSonarNode = 2;    ///< an imaging head's default node
inline constexpr std::size_t kHeaderBytes = 13;  ///< '@' … node byte
inline constexpr std::size_t kMaxPayloadBytes = 0xFFFF - 8;  ///< the 4 hex digits' limit

/// One packet, its fields named by their bytes (see the file's comment).
struct Packet {
  std::uint8_t tx_node = kHostNode;   ///< byte 7: sender
  std::uint8_t rx_node = kSonarNode;  ///< byte 8: receiver
  std::uint8_t byte_count = 0;        ///< byte 9
  std::uint8_t type = 0;              ///< byte 10
  std::uint8_t sequence = 0x80;       ///< byte 11
  std::uint8_t node = kSonarNode;     ///< byte 12: the head's node
  std::vector<std::uint8_t> payload;  ///< bytes 13 … before the LF
  std::size_t offset = 0;             ///< PacketParser: stream offset of its '@'

  /// Bytes of the whole packet (payload + 14).
  std::size_t size() const { return payload.size() + kHeaderBytes + 1; }
};

/// The whole packet: '@', the length (hex and binary), bytes 7–12 from `packet`, its payload, LF.
/// @throws ValueError when the payload exceeds kMaxPayloadBytes.
std::vector<std::uint8_t> encodePacket(const Packet& packet);

/// A packet between host and head with the byte count the drivers write (payload + 3, the length
/// − 5; 0 when that exceeds 255), sequence 0x80 and node `head_node`. From the host (255) to the
/// head when `from_head` is false, else the other way.
Packet makePacket(MessageType type, std::vector<std::uint8_t> payload, bool from_head = false,
                  std::uint8_t head_node = kSonarNode);

/// Whole packets out of bytes fed in any chunks. A packet is taken when its '@' is followed by 4
/// hex digits equal to the binary length, the packet holds at least 14 bytes and its last byte is
/// LF; a candidate whose header is consistent but whose end has not arrived is held until it has
/// (at most one packet's bytes, 65,541). Anything else (line noise, a packet broken by a bad byte)
/// is skipped byte by byte and counted, with a reason, in skipped(). Never throws on any bytes
/// (only std::bad_alloc).
class PacketParser {
 public:
  PacketParser();
  ~PacketParser();
  PacketParser(PacketParser&&) noexcept;
  PacketParser& operator=(PacketParser&&) noexcept;

  /// The packets completed by `bytes`, in stream order.
  std::vector<Packet> feed(std::span<const std::uint8_t> bytes);
  /// Lines on the bytes skipped since the last call ("byte 3 to byte 9: 7 bytes outside any
  /// packet (at byte 3: length is not 4 ASCII hex digits)"), then forgotten.
  std::vector<std::string> takeSkipped();
  /// Runs of skipped bytes so far.
  std::size_t skippedRuns() const;
  /// Bytes fed so far.
  std::size_t bytesFed() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// ---- the host's commands -----------------------------------------------------------------------

/// mtReBoot, mtSendVersion, mtSendBBUser or mtStopAlive with no payload (14 bytes, as the drivers
/// send them: "@0008", 8, 0, 255, 2, 3, type, 0x80, 2, LF).
std::vector<std::uint8_t> encodeSimpleCommand(MessageType type, std::uint8_t head_node = kSonarNode);

/// mtSendData (18 bytes) with its 4-byte time: milliseconds since midnight as mcgill's driver
/// sends it (rock's and RobDos's send 0).
std::vector<std::uint8_t> encodeSendData(std::uint32_t time_of_day_ms, std::uint8_t head_node = kSonarNode);

/// The time field of an mtSendData packet, or nothing when `packet` is not one with ≥ 4 bytes.
std::optional<std::uint32_t> decodeSendData(const Packet& packet);

// ---- the head's replies ------------------------------------------------------------------------

/// mtAlive: 22 bytes; payload byte 0 (packet byte 13) is read by none of the drivers, 1–4 the
/// head's clock (ms), 5–6 the motor's position (1/16 gradian), 7 HeadInf (bits below).
struct AliveInfo {
  std::uint8_t node = kSonarNode;
  std::uint8_t spare = 0;
  std::uint32_t head_time_ms = 0;
  std::uint16_t motor_position = 0;  ///< 1/16 gradian, the head's own count
  std::uint8_t head_info = 0;

  // HeadInf bits (RobDos mtAliveMsg, mcgill __update_state, ENSTA iSonar).
  static constexpr std::uint8_t kInCentre = 1U << 0;    ///< the motor is moving to the centre
  static constexpr std::uint8_t kCentred = 1U << 1;     ///< the motor is at the centre
  static constexpr std::uint8_t kMotoring = 1U << 2;    ///< the motor is moving
  static constexpr std::uint8_t kMotorOn = 1U << 3;     ///< the motor is powered
  static constexpr std::uint8_t kDirection = 1U << 4;   ///< scanning clockwise (right)
  static constexpr std::uint8_t kInScan = 1U << 5;      ///< scanning
  static constexpr std::uint8_t kNoParams = 1U << 6;    ///< the head has no parameters: send mtHeadCommand
  static constexpr std::uint8_t kSentConfig = 1U << 7;  ///< the head has its configuration (SentCfg)

  bool has(std::uint8_t bit) const { return (head_info & bit) != 0; }
  /// "no params, centred, motor on" …: the set bits, for notes.
  std::string describe() const;
};

/// nothing when `packet` is not an mtAlive with ≥ 8 payload bytes.
std::optional<AliveInfo> decodeAlive(const Packet& packet);
std::vector<std::uint8_t> encodeAlive(const AliveInfo& alive);

/// mtVersionData: 25 bytes; payload 0 the CPU ID's frequency code (rock: "software version";
/// libminiking: 1 325 kHz, 2 580, 3 675, 4 795, 5 935, 6 1210, 7 200, 8 1700, 9 2000, 10 500,
/// 11 1500, 12 295 kHz), 1 info bits (libminiking: low nibble the board, 1 a sonar), 2–3 serial
/// number, 4–7 program length, 8–9 program checksum, 10 node id.
struct VersionInfo {
  std::uint8_t node = kSonarNode;
  std::uint8_t frequency_code = 0;
  std::uint8_t info_bits = 0;
  std::uint16_t serial_number = 0;
  std::uint32_t program_length = 0;
  std::uint16_t checksum = 0;
  std::uint8_t node_id = kSonarNode;

  /// The frequency libminiking's table gives the code, kHz; nothing for other codes.
  std::optional<double> frequencyKhz() const;
  /// "Tritech SeaNet head, node 2, serial 1234, CPU code 0x03 (675 kHz), program 65536 bytes".
  std::string describe() const;
};

std::optional<VersionInfo> decodeVersionData(const Packet& packet);
std::vector<std::uint8_t> encodeVersionData(const VersionInfo& version);

/// mtBBUserData, the head's configuration block: 175 or 264 bytes as rock accepts them (older
/// and DST heads). What the drivers read of it:
///  - rock (`decodeBBUserData`): full duplex when packet byte 146 is 0;
///  - libminiking (the 264-byte layout, payload offsets): 46 has a motor, 48 has an auxiliary
///    port, 50 has a roll sensor, 82 dual axis, 86 RS-485, 88–95 the Tx1, Tx2, Rx1, Rx2 words,
///    176 dual synthesiser (the two channels' frequencies, so a dual-frequency head).
struct BBUserInfo {
  std::size_t packet_bytes = 0;
  std::optional<bool> full_duplex;  ///< packet byte 146 == 0 (rock)
  bool long_layout = false;         ///< 264 bytes: the fields below were read
  bool has_motor = false;
  bool has_aux = false;
  bool has_roll_sensor = false;
  bool dual_axis = false;
  bool rs485 = false;
  bool dual_synth = false;  ///< two transmit channels (SeaKing): the driver may choose one
};

/// nothing when `packet` is not an mtBBUserData; fields it does not hold stay unset or false.
std::optional<BBUserInfo> decodeBBUserData(const Packet& packet);
/// A 264-byte mtBBUserData with the fields of `info` set (the rest 0: full duplex).
std::vector<std::uint8_t> encodeBBUserData(const BBUserInfo& info, std::uint8_t head_node = kSonarNode);

/// The fields of an imaging head's mtHeadData before its data bytes (seanet_capture.hpp; bearings
/// and limits in 1/16 gradian, the head's count: ahead at 3200 for an upright head).
struct HeadDataFields {
  std::uint8_t node = kSonarNode;
  std::uint8_t device_type = 2;      ///< 2 an imaging head; mcgill's Micron DST reports 0x11
  std::uint8_t head_status = 0x10;   ///< bit 0 power loss, bit 1 motor error, bit 4 8-bit 0…80 dB
  std::uint8_t sweep_code = 0;       ///< 0 scanning, 1 at the left limit, 2 at the right, 5 centre
  std::uint16_t hd_ctrl = 0x0001;    ///< as in mtHeadCommand (HdCtrl below)
  std::uint16_t range_scale_dm = 0;  ///< low 14 bits decimetres, high 2 bits units (0 metres)
  std::uint32_t tx_n = 0;
  std::uint8_t gain = 0;             ///< IGain, 0…210
  std::uint16_t slope = 0;
  std::uint8_t ad_span = 0;          ///< × 80/255 dB
  std::uint8_t ad_low = 0;           ///< × 80/255 dB
  std::uint16_t heading_offset = 0;
  std::uint16_t ad_interval = 1;     ///< 640 ns a bin
  std::uint16_t left_limit = 0;
  std::uint16_t right_limit = 6399;
  std::uint8_t step = 32;
  std::uint16_t bearing = 0;
};

/// One single-packet mtHeadData (byte count 0, sequence 0x80) from the head `fields.node` to the
/// host: the fields, the data byte count and `data` (8-bit bins, or two 4-bit bins a byte).
/// @throws ValueError when `data` holds more than 65,000 bytes.
std::vector<std::uint8_t> encodeHeadData(const HeadDataFields& fields, std::span<const std::uint8_t> data);

/// What an mtHeadData packet gives: a beam (bearing, bin length, bins, gain, span decoded as
/// seanet_capture.hpp says, its time unset), its fields, or why not.
struct HeadDataReply {
  std::optional<Beam> beam;
  std::optional<HeadDataFields> fields;  ///< set when the 33 field bytes are there
  std::string problem;                   ///< why there is no beam ("mtHeadData with no data bytes")
};

/// Decodes `packet` (an mtHeadData) with the one mtHeadData decoder of src/formats.
/// @param sound_speed_m_s  > 0 and finite (the caller's; not checked here).
HeadDataReply decodeHeadData(const Packet& packet, double sound_speed_m_s);

// ---- mtHeadCommand -------------------------------------------------------------------------------

/// HdCtrl, the head-control bits of mtHeadCommand (and echoed in mtHeadData), as rock's
/// `HeadConfigFlags` and mcgill's `set()` name them.
namespace hdctrl {
inline constexpr std::uint16_t kAdc8On = 1U << 0;         ///< 8-bit bins (else two 4-bit bins a byte)
inline constexpr std::uint16_t kContinuous = 1U << 1;     ///< continuous turns (else a sector between the limits)
inline constexpr std::uint16_t kScanRight = 1U << 2;      ///< clockwise
inline constexpr std::uint16_t kInvert = 1U << 3;         ///< the head mounted upside down
inline constexpr std::uint16_t kMotorOff = 1U << 4;       ///< motor off
inline constexpr std::uint16_t kTxOff = 1U << 5;          ///< transmitter off (testing)
inline constexpr std::uint16_t kSpare = 1U << 6;
inline constexpr std::uint16_t kChan2 = 1U << 7;          ///< use channel 2 (rock's profiler: select_channel 2)
inline constexpr std::uint16_t kRaw = 1U << 8;            ///< set by every driver
inline constexpr std::uint16_t kHasMotor = 1U << 9;       ///< set by every driver
inline constexpr std::uint16_t kApplyOffset = 1U << 10;   ///< apply the heading offset
inline constexpr std::uint16_t kPingPong = 1U << 11;      ///< side-scan heads
inline constexpr std::uint16_t kStareLeftLimit = 1U << 12;
inline constexpr std::uint16_t kReplyAsl = 1U << 13;      ///< set by every driver
inline constexpr std::uint16_t kReplyThreshold = 1U << 14;
inline constexpr std::uint16_t kIgnoreSensor = 1U << 15;
}  // namespace hdctrl

/// The V3B ("param") mtHeadCommand of an imaging head, its fields in packet order (payload offsets
/// from packet byte 13, little-endian): 0 V3BParams (0x1D: the 16-byte V3B block follows; 0x01:
/// none, mcgill's), 1–2 HdCtrl, 3 head type, 4–7 TxN ch1, 8–11 TxN ch2, 12–15 RxN ch1, 16–19 RxN
/// ch2, 20–21 TxPulseLen, 22–23 RangeScale, 24–25 LeftLim, 26–27 RightLim, 28 ADSpan, 29 ADLow,
/// 30 IGain ch1, 31 IGain ch2, 32–33 Slope ch1, 34–35 Slope ch2, 36 MoTime, 37 Step, 38–39
/// ADInterval, 40–41 NBins, 42–43 MaxADBuf, 44–45 Lockout, 46–47 MinorAxisDir, 48 MajorAxisPan,
/// 49 Ctl2, 50–51 ScanZ; V3B block: 52–53 ADSpan ch1/ch2, 54–55 ADLow ch1/ch2, 56–57 IGain
/// ch1/ch2, 58–59 ADCSetpoint ch1/ch2, 60–63 Slope ch1/ch2, 64–67 SlopeDelay ch1/ch2. So 82 bytes
/// with the block (rock, RobDos, SeaNet Pro as captured in RobDos's template), 66 without.
/// Units: TxN and RxN = frequency × 2³² / 32 MHz (rock's profiler; the receiver's RxN is the
/// transmit frequency + 455 kHz); TxPulseLen µs; RangeScale as in mtHeadData; limits 1/16 gradian;
/// ADSpan and ADLow × 80/255 dB; IGain 0…210 for 0…80 dB (perls' comment; rock and mcgill send
/// gain × 210); MoTime 10 µs; Step 1/16 gradian; ADInterval 640 ns; Lockout µs.
struct HeadCommand {
  bool v3b = true;
  std::uint16_t hd_ctrl = 0;
  std::uint8_t head_type = 2;
  std::uint32_t tx_n[2] = {0, 0};
  std::uint32_t rx_n[2] = {0, 0};
  std::uint16_t tx_pulse_length = 0;
  std::uint16_t range_scale_dm = 0;
  std::uint16_t left_limit = 0;
  std::uint16_t right_limit = 0;
  std::uint8_t ad_span = 0;
  std::uint8_t ad_low = 0;
  std::uint8_t igain[2] = {0, 0};
  std::uint16_t slope[2] = {0, 0};
  std::uint8_t mo_time = 0;
  std::uint8_t step = 0;
  std::uint16_t ad_interval = 0;
  std::uint16_t nbins = 0;
  std::uint16_t max_ad_buf = 0;
  std::uint16_t lockout = 0;
  std::uint16_t minor_axis_dir = 0;
  std::uint8_t major_axis_pan = 0;
  std::uint8_t ctl2 = 0;
  std::uint16_t scan_z = 0;
  // The V3B block (v3b true).
  std::uint8_t ad_span_ch[2] = {0, 0};
  std::uint8_t ad_low_ch[2] = {0, 0};
  std::uint8_t igain_ch[2] = {0, 0};
  std::uint8_t adc_set_point[2] = {0, 0};
  std::uint16_t slope_ch[2] = {0, 0};
  std::uint16_t slope_delay[2] = {0, 0};

  bool operator==(const HeadCommand&) const = default;
};

/// TxN (or RxN with `hz` + 455 kHz) of a frequency: floor(hz × 2³² / 32 MHz), as rock computes it.
std::uint32_t frequencyWord(double hz);
/// The frequency of a TxN word, Hz.
double frequencyOfWord(std::uint32_t word);

/// The whole mtHeadCommand packet (82 bytes, or 66 without the V3B block) to node `head_node`.
std::vector<std::uint8_t> encodeHeadCommand(const HeadCommand& command, std::uint8_t head_node = kSonarNode);
/// nothing when `packet` is not an mtHeadCommand holding the 52 bytes (68 with V3BParams 0x1D).
std::optional<HeadCommand> decodeHeadCommand(const Packet& packet);

}  // namespace sonarmap::seanet
