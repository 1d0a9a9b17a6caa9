/// @file seanet_protocol.cpp
/// SeaNet framing, the packet parser, the simple commands and the head's replies (see
/// seanet_protocol.hpp); mtHeadCommand is in seanet_head_command.cpp.

#include "sonarmap/formats/seanet_protocol.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <utility>

#include "frame_scanner.hpp"
#include "seanet_framing.hpp"
#include "seanet_head_data.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace detail {
namespace {

constexpr unsigned char kPacketEnd = 0x0A;  // LF
constexpr std::size_t kHexLengthAt = 1;
constexpr std::size_t kBinaryLengthAt = 5;

FrameProbe cutShort(std::size_t available, const std::string& what) {
  return {FrameProbe::Kind::kCutShort, 0,
          what + ", the capture ends " + std::to_string(available) + " bytes after its start"};
}

}  // namespace

FrameProbe probeSeaNetPacket(std::span<const unsigned char> bytes, std::size_t at) {
  const std::size_t available = bytes.size();
  std::size_t hex_length = 0;
  for (std::size_t i = kHexLengthAt; i < kHexLengthAt + 4; ++i) {
    if (i >= available) return cutShort(available, "header");
    const unsigned char digit = bytes[i];
    if (!std::isxdigit(digit)) return {FrameProbe::Kind::kNotAFrame, 0, "length is not 4 ASCII hex digits"};
    hex_length = 16 * hex_length + static_cast<std::size_t>(std::isdigit(digit) ? digit - '0' : std::tolower(digit) - 'a' + 10);
  }
  if (available < kBinaryLengthAt + 2) return cutShort(available, "header");
  const std::size_t length = bytes[kBinaryLengthAt] | (bytes[kBinaryLengthAt + 1] << 8);
  if (length != hex_length) {
    return {FrameProbe::Kind::kNotAFrame, 0,
            "hex length " + std::to_string(hex_length) + " and binary length " + std::to_string(length) + " differ"};
  }
  const std::size_t size = length + kSeaNetUncountedBytes;
  if (size < kSeaNetMinPacketBytes) {
    return {FrameProbe::Kind::kNotAFrame, 0,
            "length " + std::to_string(length) + ", expected at least " +
                std::to_string(kSeaNetMinPacketBytes - kSeaNetUncountedBytes)};
  }
  if (size > available) return cutShort(available, "declares " + std::to_string(size) + " bytes");
  if (bytes[size - 1] != kPacketEnd) {
    return {FrameProbe::Kind::kNotAFrame, 0, "no LF at its end (byte " + std::to_string(at + size - 1) + ")"};
  }
  return {FrameProbe::Kind::kFrame, size, {}};
}

}  // namespace detail

namespace seanet {
namespace {

void putU16(std::vector<std::uint8_t>& out, unsigned value) {
  out.push_back(static_cast<std::uint8_t>(value & 0xFF));
  out.push_back(static_cast<std::uint8_t>((value >> 8) & 0xFF));
}

void putU32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  putU16(out, value & 0xFFFF);
  putU16(out, value >> 16);
}

std::uint16_t u16(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  return static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8));
}

std::uint32_t u32(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  return static_cast<std::uint32_t>(u16(bytes, at)) | (static_cast<std::uint32_t>(u16(bytes, at + 2)) << 16);
}

bool isType(const Packet& packet, MessageType type) { return packet.type == static_cast<std::uint8_t>(type); }

constexpr std::size_t kAlivePayloadBytes = 8;
constexpr std::size_t kVersionPayloadBytes = 11;
constexpr std::size_t kBBUserLongPayloadBytes = 250;  // 264-byte packets
constexpr std::size_t kBBUserDuplexAt = 146 - kHeaderBytes;
constexpr std::size_t kMaxDataBytes = 65000;

/// libminiking's BBUserData offsets in the 264-byte layout (payload offsets).
namespace bbuser {
constexpr std::size_t kHasMotor = 46;
constexpr std::size_t kHasAux = 48;
constexpr std::size_t kHasRollSensor = 50;
constexpr std::size_t kDualAxis = 82;
constexpr std::size_t kRs485 = 86;
constexpr std::size_t kDualSynth = 176;
}  // namespace bbuser

}  // namespace

std::string messageTypeName(std::uint8_t type) {
  switch (static_cast<MessageType>(type)) {
    case MessageType::kVersionData: return "mtVersionData";
    case MessageType::kHeadData: return "mtHeadData";
    case MessageType::kAlive: return "mtAlive";
    case MessageType::kBBUserData: return "mtBBUserData";
    case MessageType::kAuxData: return "mtAuxData";
    case MessageType::kReBoot: return "mtReBoot";
    case MessageType::kHeadCommand: return "mtHeadCommand";
    case MessageType::kSendVersion: return "mtSendVersion";
    case MessageType::kSendBBUser: return "mtSendBBUser";
    case MessageType::kSendData: return "mtSendData";
    case MessageType::kStopAlive: return "mtStopAlive";
  }
  return "message type " + std::to_string(type);
}

std::vector<std::uint8_t> encodePacket(const Packet& packet) {
  if (packet.payload.size() > kMaxPayloadBytes) {
    throw ValueError("SeaNet packet: a payload of " + std::to_string(packet.payload.size()) +
                     " bytes does not fit one packet (at most " + std::to_string(kMaxPayloadBytes) + ")");
  }
  const std::size_t length = packet.payload.size() + 8;  // bytes 5 … before the LF
  std::vector<std::uint8_t> out;
  out.reserve(length + 6);
  char hex[8];
  std::snprintf(hex, sizeof hex, "%04zX", length);
  out.push_back('@');
  out.insert(out.end(), hex, hex + 4);
  putU16(out, static_cast<unsigned>(length));
  out.insert(out.end(), {packet.tx_node, packet.rx_node, packet.byte_count, packet.type, packet.sequence, packet.node});
  out.insert(out.end(), packet.payload.begin(), packet.payload.end());
  out.push_back('\n');
  return out;
}

Packet makePacket(MessageType type, std::vector<std::uint8_t> payload, bool from_head, std::uint8_t head_node) {
  Packet packet;
  packet.tx_node = from_head ? head_node : kHostNode;
  packet.rx_node = from_head ? kHostNode : head_node;
  const std::size_t count = payload.size() + 3;
  packet.byte_count = count <= 255 ? static_cast<std::uint8_t>(count) : 0;
  packet.type = static_cast<std::uint8_t>(type);
  packet.sequence = 0x80;
  packet.node = head_node;
  packet.payload = std::move(payload);
  return packet;
}

// ---- the parser ----------------------------------------------------------------------------------

struct PacketParser::State {
  SonarLog skips;  // FrameStream's skipped items (skip_reasons, skipped_beams)
  std::vector<Packet> ready;
  detail::FrameStream stream;

  State() : stream(scan(), "SeaNet stream", skips) {}

  detail::FrameScan scan() {
    detail::FrameScan frames;
    frames.start = "@";
    frames.noun = "packet";
    frames.probe = detail::probeSeaNetPacket;
    frames.on_frame = [this](std::span<const unsigned char> bytes, std::size_t at) {
      Packet packet;
      packet.tx_node = bytes[7];
      packet.rx_node = bytes[8];
      packet.byte_count = bytes[9];
      packet.type = bytes[10];
      packet.sequence = bytes[11];
      packet.node = bytes[12];
      packet.payload.assign(bytes.begin() + static_cast<std::ptrdiff_t>(kHeaderBytes), bytes.end() - 1);
      packet.offset = at;
      ready.push_back(std::move(packet));
    };
    return frames;
  }
};

PacketParser::PacketParser() : state_(std::make_unique<State>()) {}
PacketParser::~PacketParser() = default;
PacketParser::PacketParser(PacketParser&&) noexcept = default;
PacketParser& PacketParser::operator=(PacketParser&&) noexcept = default;

std::vector<Packet> PacketParser::feed(std::span<const std::uint8_t> bytes) {
  state_->stream.feed(bytes);
  return std::exchange(state_->ready, {});
}

std::vector<std::string> PacketParser::takeSkipped() {
  // Handed over and forgotten: a long dive must not grow the list (skippedRuns() keeps the count).
  return std::exchange(state_->skips.skip_reasons, {});
}

std::size_t PacketParser::skippedRuns() const { return state_->skips.skipped_beams; }
std::size_t PacketParser::bytesFed() const { return state_->stream.bytesFed(); }

// ---- commands --------------------------------------------------------------------------------------

std::vector<std::uint8_t> encodeSimpleCommand(MessageType type, std::uint8_t head_node) {
  return encodePacket(makePacket(type, {}, false, head_node));
}

std::vector<std::uint8_t> encodeSendData(std::uint32_t time_of_day_ms, std::uint8_t head_node) {
  std::vector<std::uint8_t> payload;
  putU32(payload, time_of_day_ms);
  return encodePacket(makePacket(MessageType::kSendData, std::move(payload), false, head_node));
}

std::optional<std::uint32_t> decodeSendData(const Packet& packet) {
  if (!isType(packet, MessageType::kSendData) || packet.payload.size() < 4) return std::nullopt;
  return u32(packet.payload, 0);
}

// ---- mtAlive ---------------------------------------------------------------------------------------

std::string AliveInfo::describe() const {
  static constexpr std::pair<std::uint8_t, const char*> kBits[] = {
      {kInCentre, "in centre"}, {kCentred, "centred"},     {kMotoring, "motoring"},  {kMotorOn, "motor on"},
      {kDirection, "clockwise"}, {kInScan, "in scan"}, {kNoParams, "no params"}, {kSentConfig, "sent config"}};
  std::string text;
  for (const auto& [bit, name] : kBits) {
    if (has(bit)) text += (text.empty() ? "" : ", ") + std::string(name);
  }
  return text.empty() ? "no flags" : text;
}

std::optional<AliveInfo> decodeAlive(const Packet& packet) {
  if (!isType(packet, MessageType::kAlive) || packet.payload.size() < kAlivePayloadBytes) return std::nullopt;
  AliveInfo alive;
  alive.node = packet.node;
  alive.spare = packet.payload[0];
  alive.head_time_ms = u32(packet.payload, 1);
  alive.motor_position = u16(packet.payload, 5);
  alive.head_info = packet.payload[7];
  return alive;
}

std::vector<std::uint8_t> encodeAlive(const AliveInfo& alive) {
  std::vector<std::uint8_t> payload{alive.spare};
  putU32(payload, alive.head_time_ms);
  putU16(payload, alive.motor_position);
  payload.push_back(alive.head_info);
  return encodePacket(makePacket(MessageType::kAlive, std::move(payload), true, alive.node));
}

// ---- mtVersionData ---------------------------------------------------------------------------------

std::optional<double> VersionInfo::frequencyKhz() const {
  static constexpr double kKhz[] = {325, 580, 675, 795, 935, 1210, 200, 1700, 2000, 500, 1500, 295};
  if (frequency_code < 1 || frequency_code > std::size(kKhz)) return std::nullopt;
  return kKhz[frequency_code - 1];
}

std::string VersionInfo::describe() const {
  char code[8];
  std::snprintf(code, sizeof code, "0x%02X", frequency_code);
  const std::optional<double> khz = frequencyKhz();
  return "Tritech SeaNet head, node " + std::to_string(node) + ", serial " + std::to_string(serial_number) +
         ", CPU code " + code + (khz ? " (" + std::to_string(static_cast<int>(*khz)) + " kHz)" : std::string()) +
         ", program " + std::to_string(program_length) + " bytes";
}

std::optional<VersionInfo> decodeVersionData(const Packet& packet) {
  if (!isType(packet, MessageType::kVersionData) || packet.payload.size() < kVersionPayloadBytes) return std::nullopt;
  VersionInfo version;
  version.node = packet.node;
  version.frequency_code = packet.payload[0];
  version.info_bits = packet.payload[1];
  version.serial_number = u16(packet.payload, 2);
  version.program_length = u32(packet.payload, 4);
  version.checksum = u16(packet.payload, 8);
  version.node_id = packet.payload[10];
  return version;
}

std::vector<std::uint8_t> encodeVersionData(const VersionInfo& version) {
  std::vector<std::uint8_t> payload{version.frequency_code, version.info_bits};
  putU16(payload, version.serial_number);
  putU32(payload, version.program_length);
  putU16(payload, version.checksum);
  payload.push_back(version.node_id);
  return encodePacket(makePacket(MessageType::kVersionData, std::move(payload), true, version.node));
}

// ---- mtBBUserData ----------------------------------------------------------------------------------

std::optional<BBUserInfo> decodeBBUserData(const Packet& packet) {
  if (!isType(packet, MessageType::kBBUserData)) return std::nullopt;
  BBUserInfo info;
  info.packet_bytes = packet.size();
  const std::vector<std::uint8_t>& p = packet.payload;
  if (p.size() > kBBUserDuplexAt) info.full_duplex = p[kBBUserDuplexAt] == 0;
  if (p.size() >= kBBUserLongPayloadBytes) {
    info.long_layout = true;
    info.has_motor = p[bbuser::kHasMotor] != 0;
    info.has_aux = p[bbuser::kHasAux] != 0;
    info.has_roll_sensor = p[bbuser::kHasRollSensor] != 0;
    info.dual_axis = p[bbuser::kDualAxis] != 0;
    info.rs485 = p[bbuser::kRs485] != 0;
    info.dual_synth = p[bbuser::kDualSynth] != 0;
  }
  return info;
}

std::vector<std::uint8_t> encodeBBUserData(const BBUserInfo& info, std::uint8_t head_node) {
  std::vector<std::uint8_t> payload(kBBUserLongPayloadBytes, 0);
  payload[bbuser::kHasMotor] = info.has_motor ? 1 : 0;
  payload[bbuser::kHasAux] = info.has_aux ? 1 : 0;
  payload[bbuser::kHasRollSensor] = info.has_roll_sensor ? 1 : 0;
  payload[bbuser::kDualAxis] = info.dual_axis ? 1 : 0;
  payload[bbuser::kRs485] = info.rs485 ? 1 : 0;
  payload[bbuser::kDualSynth] = info.dual_synth ? 1 : 0;
  payload[kBBUserDuplexAt] = info.full_duplex.value_or(true) ? 0 : 1;
  return encodePacket(makePacket(MessageType::kBBUserData, std::move(payload), true, head_node));
}

// ---- mtHeadData ------------------------------------------------------------------------------------

std::vector<std::uint8_t> encodeHeadData(const HeadDataFields& fields, std::span<const std::uint8_t> data) {
  if (data.size() > kMaxDataBytes) {
    throw ValueError("SeaNet mtHeadData: " + std::to_string(data.size()) +
                     " data bytes do not fit one packet (at most 65000)");
  }
  Packet packet = makePacket(MessageType::kHeadData, {}, true, fields.node);
  packet.byte_count = 0;  // a single-packet mtHeadData (mcgill replies.py)
  std::vector<std::uint8_t>& out = packet.payload;
  out.reserve(data.size() + 31);
  putU16(out, static_cast<unsigned>(data.size() + 31));  // packed size: the packet's bytes − 14 (rock)
  out.insert(out.end(), {fields.device_type, fields.head_status, fields.sweep_code});
  putU16(out, fields.hd_ctrl);
  putU16(out, fields.range_scale_dm);
  putU32(out, fields.tx_n);
  out.push_back(fields.gain);
  putU16(out, fields.slope);
  out.insert(out.end(), {fields.ad_span, fields.ad_low});
  putU16(out, fields.heading_offset);
  putU16(out, fields.ad_interval);
  putU16(out, fields.left_limit);
  putU16(out, fields.right_limit);
  out.push_back(fields.step);
  putU16(out, fields.bearing);
  putU16(out, static_cast<unsigned>(data.size()));
  out.insert(out.end(), data.begin(), data.end());
  return encodePacket(packet);
}

HeadDataReply decodeHeadData(const Packet& packet, double sound_speed_m_s) {
  HeadDataReply reply;
  if (!isType(packet, MessageType::kHeadData)) {
    reply.problem = messageTypeName(packet.type) + ", not mtHeadData";
    return reply;
  }
  // The decoder's body starts at the sequence byte (packet byte 11).
  std::vector<unsigned char> body{packet.sequence, packet.node};
  body.insert(body.end(), packet.payload.begin(), packet.payload.end());
  const std::string name = "packet at byte " + std::to_string(packet.offset);
  detail::SeaNetHeadData decoded = detail::decodeSeaNetHeadData(
      body, packet.offset + 11, {name, "packet", 11 + detail::kSeaNetHeadDataFieldBytes}, sound_speed_m_s);
  if (body.size() >= detail::kSeaNetHeadDataFieldBytes) {
    const std::vector<std::uint8_t>& p = packet.payload;
    HeadDataFields fields;
    fields.node = packet.node;
    fields.device_type = p[2];
    fields.head_status = p[3];
    fields.sweep_code = p[4];
    fields.hd_ctrl = u16(p, 5);
    fields.range_scale_dm = u16(p, 7);
    fields.tx_n = u32(p, 9);
    fields.gain = p[13];
    fields.slope = u16(p, 14);
    fields.ad_span = p[16];
    fields.ad_low = p[17];
    fields.heading_offset = u16(p, 18);
    fields.ad_interval = u16(p, 20);
    fields.left_limit = u16(p, 22);
    fields.right_limit = u16(p, 24);
    fields.step = p[26];
    fields.bearing = u16(p, 27);
    reply.fields = fields;
  }
  if (!decoded.defect.empty()) {
    reply.problem = decoded.defect;
  } else if (!decoded.beam) {
    reply.problem = decoded.skip_reason;
  } else {
    reply.beam = std::move(decoded.beam);
  }
  return reply;
}

}  // namespace seanet
}  // namespace sonarmap
