#pragma once
/// @file ping_protocol.hpp
/// Blue Robotics ping-protocol, as a Ping360 and its host speak it: the message frame, the payload
/// of every message a Ping360 host or head sends, and a parser of a byte stream into whole, checked
/// messages. The one ping-protocol framing and checksum of the library: the Ping360 readers
/// (ping360_reader.hpp, wire_stream.hpp), the capture encoder (wire_encoder.hpp), the Ping360
/// driver and its emulator (devices/) all use it.
///
/// Sources, read and written from, not copied: Blue Robotics `ping-protocol` (`docs/index.md`
/// "Message Format"; `src/definitions/common.json` and `ping360.json` for the ids, fields, units
/// and ranges quoted below), `ping-python` (`brping/pingmessage.py`: header "<BBHHBB", checksum =
/// sum of the bytes before it & 0xFFFF; a vector field with a `sizetype` is preceded by its u16
/// length) and Ping Viewer (`pingparserext.h`: messages shorter than 10,240 bytes).
///
/// Message (all numbers little-endian): 'B' 'R'; u16 payload length; u16 message id; u8 source
/// device id; u8 destination device id; the payload; u16 checksum = the sum of every byte before
/// it, modulo 65536. A host sends with source and destination 0 (ping-python, the protocol's
/// example); the Ping360 of the shared logs sends with source 2, destination 0.
///
/// Payload structs hold the fields in the protocol's order and units; each field's name is the
/// json name with its unit appended (`angle` → `angle_grad`). `payload()` writes the payload,
/// `parse()` reads it back and checks its length (exactly the fixed fields; a vector field's u16
/// length must match the bytes that follow). Nothing here checks a field's range: the head (or its
/// emulator) does.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap::ping_protocol {

// ---- Message ids: common.json (0–999 are the common set), ping360.json ---------------------------
inline constexpr std::uint16_t kAck = 1;
inline constexpr std::uint16_t kNack = 2;
inline constexpr std::uint16_t kAsciiText = 3;
inline constexpr std::uint16_t kDeviceInformation = 4;
inline constexpr std::uint16_t kProtocolVersion = 5;
inline constexpr std::uint16_t kGeneralRequest = 6;
inline constexpr std::uint16_t kSetDeviceId = 2000;  ///< the Ping360's own (common.json's is 100)
inline constexpr std::uint16_t kDeviceData = 2300;
inline constexpr std::uint16_t kAutoDeviceData = 2301;
inline constexpr std::uint16_t kReset = 2600;
inline constexpr std::uint16_t kTransducer = 2601;
inline constexpr std::uint16_t kAutoTransmit = 2602;
inline constexpr std::uint16_t kMotorOff = 2903;

/// "device_data (2300)", or "message 1234" for an id this file does not define.
std::string messageName(std::uint16_t id);

// ---- Frame ------------------------------------------------------------------------------------
inline constexpr std::size_t kHeaderBytes = 8;     ///< 'B' 'R', payload length, id, source, destination
inline constexpr std::size_t kChecksumBytes = 2;
/// Messages are shorter than this (Ping Viewer's parser buffer, pingparserext.h); a Ping360's
/// largest, an auto_device_data of 1,200 samples, is 1,230 bytes.
inline constexpr std::size_t kMaxMessageBytes = 10240;

/// One message: its header fields and payload (the frame and checksum are implied).
struct Message {
  std::uint16_t id = 0;
  std::uint8_t source_id = 0;       ///< src_device_id
  std::uint8_t destination_id = 0;  ///< dst_device_id
  std::vector<std::uint8_t> payload;
};

/// The checksum of `bytes`: their sum modulo 65536.
std::uint16_t checksumOf(std::span<const std::uint8_t> bytes);

/// Appends the message framed: header, payload, checksum.
/// @throws ValueError for a payload of more than 65,535 bytes (its u16 length). Messages of
///         kMaxMessageBytes or more are written but no parser here (nor Ping Viewer's) takes them.
void appendMessage(std::vector<std::uint8_t>& out, std::uint16_t id, std::span<const std::uint8_t> payload,
                   std::uint8_t source_id = 0, std::uint8_t destination_id = 0);

/// `message` framed (appendMessage). @throws ValueError as appendMessage.
std::vector<std::uint8_t> encode(const Message& message);

/// The verdict on the bytes at a candidate message start.
struct Framing {
  enum class Kind {
    kNotAMessage,  ///< no 'B' 'R', a declared size of kMaxMessageBytes or more, or a bad checksum
    kCutShort,     ///< consistent so far; the message runs past the end of the bytes
    kMessage,      ///< a whole, checked message of `size` bytes
  };
  Kind kind = Kind::kNotAMessage;
  std::size_t size = 0;  ///< bytes of the message (kMessage)
  /// Why it is not a message, or what is cut short: "checksum 0 but its bytes sum to 1039 (mod
  /// 65536)", "declares 27 bytes, the capture ends 20 bytes after its start".
  std::string reason;
};

/// Frames the message starting at bytes[0] (bytes: from there to the last byte received). The
/// verdict on a prefix is kCutShort or the verdict on all the bytes. Reads at most one message's
/// bytes.
Framing frameAt(std::span<const std::uint8_t> bytes);

/// The message of `frame` (a kMessage frame's bytes, as frameAt framed them).
Message messageOf(std::span<const std::uint8_t> frame);

// ---- Payloads of the common set (common.json) ------------------------------------------------------
struct Ack {
  static constexpr std::uint16_t kId = kAck;
  std::uint16_t acked_id = 0;  ///< the message id acknowledged
  std::vector<std::uint8_t> payload() const;
  static std::optional<Ack> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

struct Nack {
  static constexpr std::uint16_t kId = kNack;
  std::uint16_t nacked_id = 0;
  std::string text;  ///< nack_message: ASCII, the rest of the payload (not necessarily NUL-terminated)
  std::vector<std::uint8_t> payload() const;
  static std::optional<Nack> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

struct AsciiText {
  static constexpr std::uint16_t kId = kAsciiText;
  std::string text;  ///< ascii_message: the whole payload
  std::vector<std::uint8_t> payload() const;
  static std::optional<AsciiText> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

struct DeviceInformation {
  static constexpr std::uint16_t kId = kDeviceInformation;
  std::uint8_t device_type = 0;  ///< 0 unknown, 1 Ping echosounder, 2 Ping360
  std::uint8_t device_revision = 0;
  std::uint8_t firmware_version_major = 0;
  std::uint8_t firmware_version_minor = 0;
  std::uint8_t firmware_version_patch = 0;
  std::uint8_t reserved = 0;
  std::vector<std::uint8_t> payload() const;
  static std::optional<DeviceInformation> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
  /// "Ping360 (firmware 3.1.1)", "Ping echosounder (...)", "ping-protocol device type 7 (...)".
  std::string text() const;
};

struct ProtocolVersion {
  static constexpr std::uint16_t kId = kProtocolVersion;
  std::uint8_t version_major = 0;
  std::uint8_t version_minor = 0;
  std::uint8_t version_patch = 0;
  std::uint8_t reserved = 0;
  std::vector<std::uint8_t> payload() const;
  static std::optional<ProtocolVersion> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

/// Asks the device to send the message `requested_id` (a "get" message; ping-python also asks a
/// Ping360 for device_data this way). Timeout 50 ms (common.json).
struct GeneralRequest {
  static constexpr std::uint16_t kId = kGeneralRequest;
  std::uint16_t requested_id = 0;
  std::vector<std::uint8_t> payload() const;
  static std::optional<GeneralRequest> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

// ---- Payloads of the Ping360 (ping360.json) --------------------------------------------------------
struct SetDeviceId {
  static constexpr std::uint16_t kId = kSetDeviceId;
  std::uint8_t id = 0;  ///< device id 1–254 (0 and 255 reserved)
  std::uint8_t reserved = 0;
  std::vector<std::uint8_t> payload() const;
  static std::optional<SetDeviceId> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

/// The sonar's state, with the samples of one ping when `data` is not empty: the reply to a
/// transducer command (and to general_request(2300)). Replies may take up to 4000 ms.
struct DeviceData {
  static constexpr std::uint16_t kId = kDeviceData;
  std::uint8_t mode = 1;                      ///< operating mode (1 for a Ping360)
  std::uint8_t gain_setting = 0;              ///< analog gain: 0 low, 1 normal, 2 high
  std::uint16_t angle_grad = 0;               ///< head angle, gradians 0–399
  std::uint16_t transmit_duration_us = 0;     ///< acoustic transmission, 1–1000 µs
  std::uint16_t sample_period_ticks = 0;      ///< between samples, 25 ns ticks (80–40000: 2–1000 µs)
  std::uint16_t transmit_frequency_khz = 0;   ///< 500–1000 kHz
  std::uint16_t number_of_samples = 0;        ///< samples per ping (200–1200)
  std::vector<std::uint8_t> data;             ///< u16 length, then the samples, nearest first
  std::vector<std::uint8_t> payload() const;
  static std::optional<DeviceData> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

/// A ping the head sends by itself in auto-transmit mode: device_data's fields, the sector's.
struct AutoDeviceData {
  static constexpr std::uint16_t kId = kAutoDeviceData;
  std::uint8_t mode = 1;
  std::uint8_t gain_setting = 0;
  std::uint16_t angle_grad = 0;
  std::uint16_t transmit_duration_us = 0;
  std::uint16_t sample_period_ticks = 0;
  std::uint16_t transmit_frequency_khz = 0;
  std::uint16_t start_angle_grad = 0;  ///< the auto scan's sector, gradians 0–399
  std::uint16_t stop_angle_grad = 0;
  std::uint8_t num_steps = 1;          ///< motor steps (gradians) between pings, 1–10
  std::uint8_t delay_ms = 0;           ///< added between pings, 0–100 ms
  std::uint16_t number_of_samples = 0;
  std::vector<std::uint8_t> data;
  std::vector<std::uint8_t> payload() const;
  static std::optional<AutoDeviceData> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
  /// The fields device_data shares (the sector's dropped).
  DeviceData deviceData() const;
};

/// Resets the sonar (1: into its bootloader). The head answers nothing; the host must find it again.
struct Reset {
  static constexpr std::uint16_t kId = kReset;
  std::uint8_t bootloader = 0;
  std::uint8_t reserved = 0;
  std::vector<std::uint8_t> payload() const;
  static std::optional<Reset> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

/// Moves the transducer to `angle_grad` with these settings and, when `transmit` is 1, pings; the
/// head answers with one device_data (its data empty when transmit is 0). Timeout 4000 ms.
struct Transducer {
  static constexpr std::uint16_t kId = kTransducer;
  std::uint8_t mode = 1;  ///< 1 for a Ping360 (ping-python's transmitAngle sends 0)
  std::uint8_t gain_setting = 0;
  std::uint16_t angle_grad = 0;
  std::uint16_t transmit_duration_us = 0;
  std::uint16_t sample_period_ticks = 0;
  std::uint16_t transmit_frequency_khz = 0;
  std::uint16_t number_of_samples = 0;
  std::uint8_t transmit = 1;  ///< 0: do not transmit; 1: transmit once at the angle
  std::uint8_t reserved = 0;
  std::vector<std::uint8_t> payload() const;
  static std::optional<Transducer> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

/// Starts the auto scan: the head pings across start..stop by itself, an auto_device_data a ping,
/// until a motor_off (or a line break) stops it.
struct AutoTransmit {
  static constexpr std::uint16_t kId = kAutoTransmit;
  std::uint8_t mode = 1;
  std::uint8_t gain_setting = 0;
  std::uint16_t transmit_duration_us = 0;
  std::uint16_t sample_period_ticks = 0;
  std::uint16_t transmit_frequency_khz = 0;
  std::uint16_t number_of_samples = 0;
  std::uint16_t start_angle_grad = 0;
  std::uint16_t stop_angle_grad = 0;
  std::uint8_t num_steps = 1;
  std::uint8_t delay_ms = 0;
  std::vector<std::uint8_t> payload() const;
  static std::optional<AutoTransmit> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

/// Switches the stepper motor's current off (and ends an auto scan); the head answers with an ack.
/// Timeout 50 ms.
struct MotorOff {
  static constexpr std::uint16_t kId = kMotorOff;
  std::vector<std::uint8_t> payload() const { return {}; }
  static std::optional<MotorOff> parse(std::span<const std::uint8_t> payload, std::string* why = nullptr);
};

/// `body` as a framed message of its id. @throws ValueError as appendMessage.
template <class Body>
std::vector<std::uint8_t> encode(const Body& body, std::uint8_t source_id = 0, std::uint8_t destination_id = 0) {
  std::vector<std::uint8_t> out;
  const std::vector<std::uint8_t> payload = body.payload();
  appendMessage(out, Body::kId, payload, source_id, destination_id);
  return out;
}

/// The payload of `message` as `Body`: empty when the id is another's or the payload does not
/// parse (`why` then says why, when given).
template <class Body>
std::optional<Body> decode(const Message& message, std::string* why = nullptr) {
  if (message.id != Body::kId) {
    if (why) *why = messageName(message.id) + ", not " + messageName(Body::kId);
    return std::nullopt;
  }
  return Body::parse(message.payload, why);
}

// ---- Beams ------------------------------------------------------------------------------------------
/// The beam of a ping (time unset): `bearing_rad` = 2π · angle / 400 (the Ping360 counts gradians
/// clockwise seen from above; beam.hpp's bearing the same, 0 ahead), `bin_length_m` =
/// sample_period × 25 ns × sound_speed_m_s / 2, `intensities` = data (bin 0 nearest),
/// `gain_setting` = gain_setting, `pulse_length_m` = transmit_duration × sound_speed_m_s / 2 (unset
/// for a duration of 0), no `intensity_span_db` (the protocol gives none). None, with `why`, for
/// an angle ≥ 400, a sample period of 0, or no samples.
std::optional<Beam> ping360Beam(const DeviceData& ping, double sound_speed_m_s, std::string* why = nullptr);

// ---- A stream of messages ---------------------------------------------------------------------------
/// Whole, checked messages of any id from a byte stream fed in chunks of any size (a serial line,
/// UDP datagrams): the frames frameAt finds, across chunk boundaries; bytes outside every message
/// (line noise, a break, the autobaud 'U', a bad checksum) are skipped and described. Never
/// throws for any bytes (only std::bad_alloc); holds at most one message's bytes it has not decided.
class MessageParser {
 public:
  MessageParser();
  ~MessageParser();
  MessageParser(MessageParser&&) noexcept;
  MessageParser& operator=(MessageParser&&) noexcept;

  /// The messages completed by `bytes`, the stream's next bytes, in order.
  std::vector<Message> feed(std::span<const std::uint8_t> bytes);
  std::size_t bytesFed() const;
  std::size_t messagesParsed() const;
  /// Runs of skipped bytes so far.
  std::size_t skippedItems() const;
  /// One line per run of skipped bytes since the last call ("stream: byte 0 to byte 3: 4 bytes
  /// outside any message (at byte 0: checksum ...)"); a run is described once the next message
  /// ends it. Held until taken.
  std::vector<std::string> takeSkipReasons();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sonarmap::ping_protocol
