/// @file ping_protocol.cpp
/// ping-protocol messages: frame, payloads, the stream parser (see ping_protocol.hpp).

#include "sonarmap/formats/ping_protocol.hpp"

#include <numbers>
#include <utility>

#include "frame_scanner.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::ping_protocol {
namespace {

constexpr std::size_t kPayloadLengthAt = 2;
constexpr std::size_t kIdAt = 4;
constexpr std::size_t kSourceAt = 6;
constexpr std::size_t kDestinationAt = 7;
constexpr std::uint32_t kGradiansPerTurn = 400;
constexpr double kSamplePeriodTick_s = 25e-9;

std::uint16_t u16At(std::span<const std::uint8_t> bytes, std::size_t at) {
  return static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8));
}

void putU16(std::vector<std::uint8_t>& out, std::uint16_t value) {
  out.push_back(static_cast<std::uint8_t>(value & 0xFF));
  out.push_back(static_cast<std::uint8_t>(value >> 8));
}

/// Reads a payload field by field; a read past the end leaves the reader failed.
class PayloadReader {
 public:
  explicit PayloadReader(std::span<const std::uint8_t> payload) : payload_(payload) {}
  std::uint8_t u8() {
    if (at_ + 1 > payload_.size()) return fail();
    return payload_[at_++];
  }
  std::uint16_t u16() {
    if (at_ + 2 > payload_.size()) return fail();
    const std::uint16_t value = u16At(payload_, at_);
    at_ += 2;
    return value;
  }
  std::span<const std::uint8_t> rest() {
    const std::span<const std::uint8_t> bytes = payload_.subspan(std::min(at_, payload_.size()));
    at_ = payload_.size();
    return bytes;
  }
  std::size_t position() const { return at_; }
  std::size_t size() const { return payload_.size(); }
  bool failed() const { return failed_; }

 private:
  std::uint8_t fail() {
    failed_ = true;
    at_ = payload_.size() + 1;
    return 0;
  }
  std::span<const std::uint8_t> payload_;
  std::size_t at_ = 0;
  bool failed_ = false;
};

/// Whether `reader` read exactly its payload's fixed fields of `bytes` bytes; sets `why` if not.
bool exactly(const PayloadReader& reader, std::size_t bytes, std::string* why) {
  if (!reader.failed() && reader.position() == reader.size()) return true;
  if (why) *why = "payload of " + std::to_string(reader.size()) + " bytes, expected " + std::to_string(bytes);
  return false;
}

/// Reads a u16 length and that many bytes, the payload's last field; false (with `why`) when the
/// payload is shorter than `data_at` or the length does not match the bytes after it.
bool readVector(PayloadReader& reader, std::size_t data_at, std::vector<std::uint8_t>& data, std::string* why) {
  const std::uint16_t length = reader.u16();
  if (reader.failed()) {
    if (why) *why = "payload of " + std::to_string(reader.size()) + " bytes, expected at least " + std::to_string(data_at);
    return false;
  }
  const std::span<const std::uint8_t> bytes = reader.rest();
  if (bytes.size() != length) {
    if (why) {
      *why = "data length " + std::to_string(length) + " but the payload holds " + std::to_string(bytes.size()) +
             " bytes after its fields";
    }
    return false;
  }
  data.assign(bytes.begin(), bytes.end());
  return true;
}

std::string textOf(std::span<const std::uint8_t> bytes) { return {bytes.begin(), bytes.end()}; }

}  // namespace

std::string messageName(std::uint16_t id) {
  const char* name = nullptr;
  switch (id) {
    case kAck: name = "ack"; break;
    case kNack: name = "nack"; break;
    case kAsciiText: name = "ascii_text"; break;
    case kDeviceInformation: name = "device_information"; break;
    case kProtocolVersion: name = "protocol_version"; break;
    case kGeneralRequest: name = "general_request"; break;
    case kSetDeviceId: name = "set_device_id"; break;
    case kDeviceData: name = "device_data"; break;
    case kAutoDeviceData: name = "auto_device_data"; break;
    case kReset: name = "reset"; break;
    case kTransducer: name = "transducer"; break;
    case kAutoTransmit: name = "auto_transmit"; break;
    case kMotorOff: name = "motor_off"; break;
    default: return "message " + std::to_string(id);
  }
  return std::string(name) + " (" + std::to_string(id) + ")";
}

// ---- Frame ------------------------------------------------------------------------------------

std::uint16_t checksumOf(std::span<const std::uint8_t> bytes) {
  std::uint32_t sum = 0;
  for (const std::uint8_t byte : bytes) sum += byte;
  return static_cast<std::uint16_t>(sum & 0xFFFFU);
}

void appendMessage(std::vector<std::uint8_t>& out, std::uint16_t id, std::span<const std::uint8_t> payload,
                   std::uint8_t source_id, std::uint8_t destination_id) {
  if (payload.size() > 0xFFFF) {
    throw ValueError("ping-protocol " + messageName(id) + ": a payload of " + std::to_string(payload.size()) +
                     " bytes does not fit its u16 length (at most 65535)");
  }
  const std::size_t start = out.size();
  out.insert(out.end(), {'B', 'R'});
  putU16(out, static_cast<std::uint16_t>(payload.size()));
  putU16(out, id);
  out.push_back(source_id);
  out.push_back(destination_id);
  out.insert(out.end(), payload.begin(), payload.end());
  putU16(out, checksumOf(std::span(out).subspan(start)));
}

std::vector<std::uint8_t> encode(const Message& message) {
  std::vector<std::uint8_t> out;
  appendMessage(out, message.id, message.payload, message.source_id, message.destination_id);
  return out;
}

Framing frameAt(std::span<const std::uint8_t> bytes) {
  const std::size_t available = bytes.size();
  const auto cut = [&](const std::string& what) {
    return Framing{Framing::Kind::kCutShort, 0,
                   what + ", the capture ends " + std::to_string(available) + " bytes after its start"};
  };
  if ((available >= 1 && bytes[0] != 'B') || (available >= 2 && bytes[1] != 'R')) {
    return {Framing::Kind::kNotAMessage, 0, "no 'B' 'R' at its start"};
  }
  if (available < kHeaderBytes) return cut("header");
  const std::size_t size = kHeaderBytes + u16At(bytes, kPayloadLengthAt) + kChecksumBytes;
  if (size >= kMaxMessageBytes) {
    return {Framing::Kind::kNotAMessage, 0,
            "declares " + std::to_string(size) + " bytes, expected fewer than " + std::to_string(kMaxMessageBytes)};
  }
  if (size > available) return cut("declares " + std::to_string(size) + " bytes");
  const std::uint16_t sum = checksumOf(bytes.first(size - kChecksumBytes));
  const std::uint16_t checksum = u16At(bytes, size - kChecksumBytes);
  if (checksum != sum) {
    return {Framing::Kind::kNotAMessage, 0,
            "checksum " + std::to_string(checksum) + " but its bytes sum to " + std::to_string(sum) + " (mod 65536)"};
  }
  return {Framing::Kind::kMessage, size, {}};
}

Message messageOf(std::span<const std::uint8_t> frame) {
  Message message;
  message.id = u16At(frame, kIdAt);
  message.source_id = frame[kSourceAt];
  message.destination_id = frame[kDestinationAt];
  const std::span<const std::uint8_t> payload = frame.subspan(kHeaderBytes, frame.size() - kHeaderBytes - kChecksumBytes);
  message.payload.assign(payload.begin(), payload.end());
  return message;
}

// ---- Common payloads --------------------------------------------------------------------------------

std::vector<std::uint8_t> Ack::payload() const {
  std::vector<std::uint8_t> out;
  putU16(out, acked_id);
  return out;
}

std::optional<Ack> Ack::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  Ack ack;
  ack.acked_id = reader.u16();
  if (!exactly(reader, 2, why)) return std::nullopt;
  return ack;
}

std::vector<std::uint8_t> Nack::payload() const {
  std::vector<std::uint8_t> out;
  putU16(out, nacked_id);
  out.insert(out.end(), text.begin(), text.end());
  return out;
}

std::optional<Nack> Nack::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  Nack nack;
  nack.nacked_id = reader.u16();
  if (reader.failed()) {
    if (why) *why = "payload of " + std::to_string(payload.size()) + " bytes, expected at least 2";
    return std::nullopt;
  }
  nack.text = textOf(reader.rest());
  return nack;
}

std::vector<std::uint8_t> AsciiText::payload() const { return {text.begin(), text.end()}; }

std::optional<AsciiText> AsciiText::parse(std::span<const std::uint8_t> payload, std::string*) {
  return AsciiText{textOf(payload)};
}

std::vector<std::uint8_t> DeviceInformation::payload() const {
  return {device_type, device_revision, firmware_version_major, firmware_version_minor, firmware_version_patch,
          reserved};
}

std::optional<DeviceInformation> DeviceInformation::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  DeviceInformation info;
  info.device_type = reader.u8();
  info.device_revision = reader.u8();
  info.firmware_version_major = reader.u8();
  info.firmware_version_minor = reader.u8();
  info.firmware_version_patch = reader.u8();
  info.reserved = reader.u8();
  if (!exactly(reader, 6, why)) return std::nullopt;
  return info;
}

std::string DeviceInformation::text() const {
  const std::string type = device_type == 2   ? "Ping360"
                           : device_type == 1 ? "Ping echosounder"
                                              : "ping-protocol device type " + std::to_string(device_type);
  return type + " (firmware " + std::to_string(firmware_version_major) + "." + std::to_string(firmware_version_minor) +
         "." + std::to_string(firmware_version_patch) + ")";
}

std::vector<std::uint8_t> ProtocolVersion::payload() const {
  return {version_major, version_minor, version_patch, reserved};
}

std::optional<ProtocolVersion> ProtocolVersion::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  ProtocolVersion version;
  version.version_major = reader.u8();
  version.version_minor = reader.u8();
  version.version_patch = reader.u8();
  version.reserved = reader.u8();
  if (!exactly(reader, 4, why)) return std::nullopt;
  return version;
}

std::vector<std::uint8_t> GeneralRequest::payload() const {
  std::vector<std::uint8_t> out;
  putU16(out, requested_id);
  return out;
}

std::optional<GeneralRequest> GeneralRequest::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  GeneralRequest request;
  request.requested_id = reader.u16();
  if (!exactly(reader, 2, why)) return std::nullopt;
  return request;
}

// ---- Ping360 payloads --------------------------------------------------------------------------------

std::vector<std::uint8_t> SetDeviceId::payload() const { return {id, reserved}; }

std::optional<SetDeviceId> SetDeviceId::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  SetDeviceId set;
  set.id = reader.u8();
  set.reserved = reader.u8();
  if (!exactly(reader, 2, why)) return std::nullopt;
  return set;
}

std::vector<std::uint8_t> DeviceData::payload() const {
  std::vector<std::uint8_t> out = {mode, gain_setting};
  for (const std::uint16_t field : {angle_grad, transmit_duration_us, sample_period_ticks, transmit_frequency_khz,
                                    number_of_samples, static_cast<std::uint16_t>(data.size())}) {
    putU16(out, field);
  }
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

std::optional<DeviceData> DeviceData::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  DeviceData ping;
  ping.mode = reader.u8();
  ping.gain_setting = reader.u8();
  ping.angle_grad = reader.u16();
  ping.transmit_duration_us = reader.u16();
  ping.sample_period_ticks = reader.u16();
  ping.transmit_frequency_khz = reader.u16();
  ping.number_of_samples = reader.u16();
  if (!readVector(reader, 14, ping.data, why)) return std::nullopt;
  return ping;
}

std::vector<std::uint8_t> AutoDeviceData::payload() const {
  std::vector<std::uint8_t> out = {mode, gain_setting};
  for (const std::uint16_t field :
       {angle_grad, transmit_duration_us, sample_period_ticks, transmit_frequency_khz, start_angle_grad, stop_angle_grad}) {
    putU16(out, field);
  }
  out.push_back(num_steps);
  out.push_back(delay_ms);
  putU16(out, number_of_samples);
  putU16(out, static_cast<std::uint16_t>(data.size()));
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

std::optional<AutoDeviceData> AutoDeviceData::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  AutoDeviceData ping;
  ping.mode = reader.u8();
  ping.gain_setting = reader.u8();
  ping.angle_grad = reader.u16();
  ping.transmit_duration_us = reader.u16();
  ping.sample_period_ticks = reader.u16();
  ping.transmit_frequency_khz = reader.u16();
  ping.start_angle_grad = reader.u16();
  ping.stop_angle_grad = reader.u16();
  ping.num_steps = reader.u8();
  ping.delay_ms = reader.u8();
  ping.number_of_samples = reader.u16();
  if (!readVector(reader, 20, ping.data, why)) return std::nullopt;
  return ping;
}

DeviceData AutoDeviceData::deviceData() const {
  return {mode, gain_setting, angle_grad, transmit_duration_us, sample_period_ticks, transmit_frequency_khz,
          number_of_samples, data};
}

std::vector<std::uint8_t> Reset::payload() const { return {bootloader, reserved}; }

std::optional<Reset> Reset::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  Reset reset;
  reset.bootloader = reader.u8();
  reset.reserved = reader.u8();
  if (!exactly(reader, 2, why)) return std::nullopt;
  return reset;
}

std::vector<std::uint8_t> Transducer::payload() const {
  std::vector<std::uint8_t> out = {mode, gain_setting};
  for (const std::uint16_t field :
       {angle_grad, transmit_duration_us, sample_period_ticks, transmit_frequency_khz, number_of_samples}) {
    putU16(out, field);
  }
  out.push_back(transmit);
  out.push_back(reserved);
  return out;
}

std::optional<Transducer> Transducer::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  Transducer command;
  command.mode = reader.u8();
  command.gain_setting = reader.u8();
  command.angle_grad = reader.u16();
  command.transmit_duration_us = reader.u16();
  command.sample_period_ticks = reader.u16();
  command.transmit_frequency_khz = reader.u16();
  command.number_of_samples = reader.u16();
  command.transmit = reader.u8();
  command.reserved = reader.u8();
  if (!exactly(reader, 14, why)) return std::nullopt;
  return command;
}

std::vector<std::uint8_t> AutoTransmit::payload() const {
  std::vector<std::uint8_t> out = {mode, gain_setting};
  for (const std::uint16_t field : {transmit_duration_us, sample_period_ticks, transmit_frequency_khz,
                                    number_of_samples, start_angle_grad, stop_angle_grad}) {
    putU16(out, field);
  }
  out.push_back(num_steps);
  out.push_back(delay_ms);
  return out;
}

std::optional<AutoTransmit> AutoTransmit::parse(std::span<const std::uint8_t> payload, std::string* why) {
  PayloadReader reader(payload);
  AutoTransmit command;
  command.mode = reader.u8();
  command.gain_setting = reader.u8();
  command.transmit_duration_us = reader.u16();
  command.sample_period_ticks = reader.u16();
  command.transmit_frequency_khz = reader.u16();
  command.number_of_samples = reader.u16();
  command.start_angle_grad = reader.u16();
  command.stop_angle_grad = reader.u16();
  command.num_steps = reader.u8();
  command.delay_ms = reader.u8();
  if (!exactly(reader, 16, why)) return std::nullopt;
  return command;
}

std::optional<MotorOff> MotorOff::parse(std::span<const std::uint8_t> payload, std::string* why) {
  if (!payload.empty()) {
    if (why) *why = "payload of " + std::to_string(payload.size()) + " bytes, expected 0";
    return std::nullopt;
  }
  return MotorOff{};
}

// ---- Beams ------------------------------------------------------------------------------------------

std::optional<Beam> ping360Beam(const DeviceData& ping, double sound_speed_m_s, std::string* why) {
  const auto refuse = [&](std::string reason) -> std::optional<Beam> {
    if (why) *why = std::move(reason);
    return std::nullopt;
  };
  if (ping.angle_grad >= kGradiansPerTurn) {
    return refuse("angle " + std::to_string(ping.angle_grad) + ", expected 0…399 gradians");
  }
  if (ping.sample_period_ticks == 0) return refuse("sample period 0, expected > 0 (units of 25 ns)");
  if (ping.data.empty()) return refuse("no samples");
  Beam beam;
  beam.bearing_rad = 2.0 * std::numbers::pi * static_cast<double>(ping.angle_grad) / kGradiansPerTurn;
  beam.bin_length_m = ping.sample_period_ticks * kSamplePeriodTick_s * sound_speed_m_s / 2.0;
  beam.intensities = ping.data;
  beam.gain_setting = ping.gain_setting;
  if (ping.transmit_duration_us > 0) beam.pulse_length_m = ping.transmit_duration_us * 1e-6 * sound_speed_m_s / 2.0;
  return beam;
}

// ---- MessageParser ------------------------------------------------------------------------------------

struct MessageParser::State {
  State() : stream(scan(), "stream", log) {}

  detail::FrameScan scan() {
    detail::FrameScan frames;
    frames.start = "BR";
    frames.noun = "message";
    frames.probe = [](std::span<const unsigned char> bytes, std::size_t) {
      const Framing framing = frameAt(bytes);
      const auto kind = framing.kind == Framing::Kind::kMessage    ? detail::FrameProbe::Kind::kFrame
                        : framing.kind == Framing::Kind::kCutShort ? detail::FrameProbe::Kind::kCutShort
                                                                   : detail::FrameProbe::Kind::kNotAFrame;
      return detail::FrameProbe{kind, framing.size, framing.reason};
    };
    frames.on_frame = [this](std::span<const unsigned char> frame, std::size_t) { messages.push_back(messageOf(frame)); };
    return frames;
  }

  SonarLog log;  ///< skip lines and counts (FrameStream's sink); never holds beams
  std::vector<Message> messages;
  std::size_t parsed = 0;
  detail::FrameStream stream;
};

MessageParser::MessageParser() : state_(std::make_unique<State>()) {}
MessageParser::~MessageParser() = default;
MessageParser::MessageParser(MessageParser&&) noexcept = default;
MessageParser& MessageParser::operator=(MessageParser&&) noexcept = default;

std::vector<Message> MessageParser::feed(std::span<const std::uint8_t> bytes) {
  state_->stream.feed(bytes);
  std::vector<Message> out = std::move(state_->messages);
  state_->messages.clear();
  state_->parsed += out.size();
  return out;
}

std::size_t MessageParser::bytesFed() const { return state_->stream.bytesFed(); }
std::size_t MessageParser::messagesParsed() const { return state_->parsed; }
std::size_t MessageParser::skippedItems() const { return state_->log.skipped_beams; }

std::vector<std::string> MessageParser::takeSkipReasons() {
  std::vector<std::string> reasons = std::move(state_->log.skip_reasons);
  state_->log.skip_reasons.clear();
  return reasons;
}

}  // namespace sonarmap::ping_protocol
