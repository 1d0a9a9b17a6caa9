#pragma once
/// @file mavlink.hpp
/// MAVLink frames: the checksum, the messages sonarmap knows, a frame read at a given place (a
/// `.tlog` record), an incremental parser of a byte stream (UDP datagrams, a TCP or serial stream
/// with line noise) and an encoder. The payloads' fields are in mavlink_messages.hpp.
///
/// Source: MAVLink's serialization spec (mavlink.io/en/guide/serialization.html). A MAVLink 1
/// frame is 0xFE, length, sequence, system, component, message id (1 byte), payload, checksum; a
/// MAVLink 2 frame is 0xFD, length, incompat flags, compat flags, sequence, system, component,
/// message id (3 bytes, little-endian), payload, checksum, and a 13-byte signature when incompat
/// flag 0x01 is set. The checksum is CRC-16/MCRF4XX over every byte after the magic up to the
/// payload's end, then the message's CRC_EXTRA byte (a digest of its definition), sent
/// little-endian. A MAVLink 2 sender drops the payload's trailing zero bytes; the receiver restores
/// them. Multi-byte fields are little-endian, as on every machine this project builds for.
///
/// Nothing here throws for any received bytes; the encoder throws ValueError for a message it
/// cannot send (see MavlinkEncoder).

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace sonarmap {

inline constexpr std::uint8_t kMavlinkMagicV1 = 0xFE;
inline constexpr std::uint8_t kMavlinkMagicV2 = 0xFD;
/// MAVLink 2 incompat flag: the frame carries a 13-byte signature after its checksum.
inline constexpr std::uint8_t kMavlinkFlagSigned = 0x01;
inline constexpr std::size_t kMavlinkSignatureBytes = 13;
/// The longest frame: a MAVLink 2 header (10 bytes), 255 payload bytes, checksum, signature.
inline constexpr std::size_t kMavlinkMaxFrameBytes = 10 + 255 + 2 + kMavlinkSignatureBytes;

/// CRC-16/MCRF4XX (poly 0x1021 reflected, initial 0xFFFF, no final xor; MAVLink's checksum.h calls
/// it X.25) of `bytes` continued from `crc`. Catalogue check: "123456789" → 0x6F91.
std::uint16_t mavlinkCrc(std::span<const std::uint8_t> bytes, std::uint16_t crc = 0xFFFF);

/// The CRC_EXTRA of a message definition: CRC-16/MCRF4XX of "NAME " then, for each field of the
/// MAVLink 1 payload in wire order (by type size, largest first; extensions excluded), "TYPE NAME "
/// and, for an array, its length as one byte; the low byte xor the high byte (serialization spec,
/// "CRC_EXTRA Calculation"). `fields` holds "TYPE NAME" or "TYPE[N] NAME" in wire order;
/// uint8_t_mavlink_version counts as uint8_t.
std::uint8_t mavlinkCrcExtra(std::string_view message_name, std::span<const std::string_view> fields);

/// A message sonarmap decodes or encodes, from its XML definition: common.xml (HEARTBEAT is in
/// minimal.xml, GLOBAL_POSITION_INT in standard.xml, both included by common.xml) and
/// ardupilotmega.xml (VISION_POSITION_DELTA).
struct MavlinkMessageInfo {
  std::uint32_t id = 0;
  std::string_view name;
  std::uint8_t crc_extra = 0;
  std::uint8_t min_length = 0;  ///< payload bytes without the extension fields (a MAVLink 1 payload)
  std::uint8_t max_length = 0;  ///< payload bytes with them (a MAVLink 2 payload before truncation)
};

/// HEARTBEAT 0, SCALED_PRESSURE 29, ATTITUDE 30, LOCAL_POSITION_NED 32, GLOBAL_POSITION_INT 33,
/// SCALED_PRESSURE2 137, SCALED_PRESSURE3 143, VISION_POSITION_DELTA 11011, by id.
std::span<const MavlinkMessageInfo> mavlinkMessages();
/// The message with `id`, or nullptr when sonarmap does not know it.
const MavlinkMessageInfo* findMavlinkMessage(std::uint32_t id);

/// One frame as received (or encoded).
struct MavlinkFrame {
  std::uint8_t version = 2;  ///< 1 (magic 0xFE) or 2 (0xFD)
  std::uint8_t incompat_flags = 0;  ///< MAVLink 2 only
  std::uint8_t compat_flags = 0;    ///< MAVLink 2 only
  std::uint8_t sequence = 0;
  std::uint8_t system = 0;     ///< the sender's system id (vehicle; a ground station is often 255)
  std::uint8_t component = 0;  ///< the sender's component id (the autopilot is 1)
  std::uint32_t message_id = 0;
  std::uint8_t payload_length = 0;  ///< as sent (MAVLink 2 truncates trailing zeros)
  std::array<std::uint8_t, 255> payload{};  ///< the payload, zero-extended to 255 bytes
  bool checked = false;    ///< a known message whose checksum matched; false: an unknown message, unchecked
  bool is_signed = false;  ///< MAVLink 2 with a signature (not verified: sonarmap holds no key)
};

/// What readMavlinkFrame found at the start of its bytes.
enum class MavlinkFrameStatus {
  kFrame,           ///< a known message with a matching checksum
  kUnknownMessage,  ///< a well-formed header of a message sonarmap does not know (checksum unchecked)
  kBadChecksum,     ///< a known message whose checksum does not match
  kBadLength,       ///< a known message longer than its definition
  kBadFlags,        ///< MAVLink 2 incompat flags other than "signed": a frame no one may parse
  kCutShort,        ///< the bytes end before the frame does
  kNoMagic,         ///< the first byte is neither 0xFE nor 0xFD
};

struct MavlinkFrameRead {
  MavlinkFrameStatus status = MavlinkFrameStatus::kNoMagic;
  /// The frame's bytes as its header declares them; for kCutShort, 0 when even the header is cut.
  std::size_t size = 0;
  /// The header's fields when the header is whole; the payload for kFrame and kUnknownMessage.
  MavlinkFrame frame;
};

/// Reads the frame that starts at bytes[0] (a `.tlog` record's frame; the stream parser's probe).
MavlinkFrameRead readMavlinkFrame(std::span<const std::uint8_t> bytes);

/// What a MavlinkFrameParser has seen so far.
struct MavlinkStreamCounts {
  std::size_t bytes = 0;           ///< fed
  std::size_t frames = 0;          ///< known messages with a matching checksum, passed on
  std::size_t unknown_frames = 0;  ///< other messages, passed on unchecked
  std::size_t bad_frames = 0;      ///< candidates refused (checksum, length, flags); each false start counts
  std::size_t noise_bytes = 0;     ///< bytes outside any frame, refused candidates' magic bytes included
};

/// Frames out of a byte stream fed in chunks of any size: any way of cutting the same bytes gives
/// the same frames and counts. Bytes before a magic byte are noise. A candidate frame of a known
/// message is passed on when its checksum matches; otherwise its magic byte counts as noise and
/// the search resumes at the next byte, so a frame hidden behind a false start is found. A
/// candidate of an unknown message (its checksum cannot be checked) is passed on when the byte
/// after it starts another frame (a magic byte), and is otherwise taken for noise likewise: a
/// datagram's last unknown frame is held until the next bytes arrive. Holds at most one frame's
/// bytes (kMavlinkMaxFrameBytes) plus one between calls. Never throws (only std::bad_alloc).
class MavlinkFrameParser {
 public:
  /// The frames `bytes` complete, in stream order.
  std::vector<MavlinkFrame> feed(std::span<const std::uint8_t> bytes);
  /// As feed(bytes), appending to `out`.
  void feed(std::span<const std::uint8_t> bytes, std::vector<MavlinkFrame>& out);
  const MavlinkStreamCounts& counts() const { return counts_; }
  /// Bytes held for the next call (a frame not yet complete).
  std::size_t heldBytes() const { return held_.size(); }

 private:
  std::vector<std::uint8_t> held_;
  MavlinkStreamCounts counts_;
};

/// Frames of one sender (system, component) with its sequence numbers, MAVLink 2 by default.
class MavlinkEncoder {
 public:
  /// @param version  1 or 2.
  /// @throws ValueError for another version.
  MavlinkEncoder(std::uint8_t system, std::uint8_t component, int version = 2);

  /// One frame of message `message_id` with `payload` (all its fields, max_length bytes; a
  /// shorter payload is zero-extended). MAVLink 2 drops the trailing zero bytes (keeping the
  /// first byte, as the spec asks); MAVLink 1 sends the fields without the extensions
  /// (min_length bytes). The sequence number then advances (wrapping at 256).
  /// @throws ValueError for a message sonarmap does not know, a payload longer than the message's,
  ///   or, in MAVLink 1, a message id above 255.
  std::vector<std::uint8_t> encode(std::uint32_t message_id, std::span<const std::uint8_t> payload);

  std::uint8_t nextSequence() const { return sequence_; }
  int version() const { return version_; }

 private:
  std::uint8_t system_;
  std::uint8_t component_;
  int version_;
  std::uint8_t sequence_ = 0;
};

}  // namespace sonarmap
