/// @file ping_protocol.cpp
/// ping-protocol messages: frame, payloads, the stream parser (see ping_protocol.hpp).

#include "sonarmap/formats/ping_protocol.hpp"

#include <concepts>
#include <numbers>
#include <tuple>
#include <type_traits>
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

/// Appends payload fields, each as its type says: u8; u16 little-endian; a byte vector as its u16
/// length then its bytes; a string as its bytes, the rest of the payload.
struct FieldWriter {
  std::vector<std::uint8_t>& out;
  void operator()(std::uint8_t field) const { out.push_back(field); }
  void operator()(std::uint16_t field) const { putU16(out, field); }
  void operator()(const std::vector<std::uint8_t>& data) const {
    putU16(out, static_cast<std::uint16_t>(data.size()));
    out.insert(out.end(), data.begin(), data.end());
  }
  void operator()(const std::string& text) const { out.insert(out.end(), text.begin(), text.end()); }
  template <class Field>
  void operator()(const Field&) const = delete;  // no other field type has a wire form here
};

/// Reads payload fields as FieldWriter writes them (a vector or string only as the last field),
/// then says whether they took exactly the payload: no fewer bytes than the fields want, no more
/// unless the last field takes the rest, a vector's u16 length equal to the bytes after it.
class FieldReader {
 public:
  explicit FieldReader(std::span<const std::uint8_t> payload) : payload_(payload) {}
  void operator()(std::uint8_t& field) {
    if (const std::span<const std::uint8_t> bytes = take(1); !bytes.empty()) field = bytes[0];
  }
  void operator()(std::uint16_t& field) {
    if (const std::span<const std::uint8_t> bytes = take(2); !bytes.empty()) field = u16At(bytes, 0);
  }
  void operator()(std::vector<std::uint8_t>& data) {
    std::uint16_t length = 0;
    (*this)(length);
    const std::span<const std::uint8_t> bytes = rest();
    if (!short_ && bytes.size() != length) {
      data_mismatch_ = "data length " + std::to_string(length) + " but the payload holds " +
                       std::to_string(bytes.size()) + " bytes after its fields";
    }
    data.assign(bytes.begin(), bytes.end());
  }
  void operator()(std::string& text) {
    const std::span<const std::uint8_t> bytes = rest();
    text.assign(bytes.begin(), bytes.end());
  }
  template <class Field>
  void operator()(Field&) = delete;

  /// Whether the fields read took exactly the payload; sets `why` if not.
  bool exact(std::string* why) const {
    std::string reason = data_mismatch_;
    if (short_ || at_ != payload_.size()) {
      reason = "payload of " + std::to_string(payload_.size()) + " bytes, expected " +
               (open_ended_ ? "at least " : "") + std::to_string(wanted_);
    }
    if (reason.empty()) return true;
    if (why) *why = std::move(reason);
    return false;
  }

 private:
  /// The next `count` bytes, or none (the reader then short) past the payload's end.
  std::span<const std::uint8_t> take(std::size_t count) {
    wanted_ += count;
    if (short_ || at_ + count > payload_.size()) {
      short_ = true;
      return {};
    }
    at_ += count;
    return payload_.subspan(at_ - count, count);
  }
  std::span<const std::uint8_t> rest() {
    open_ended_ = true;
    if (short_) return {};
    const std::span<const std::uint8_t> bytes = payload_.subspan(at_);
    at_ = payload_.size();
    return bytes;
  }

  std::span<const std::uint8_t> payload_;
  std::size_t at_ = 0;
  std::size_t wanted_ = 0;   ///< bytes the fields read so far want (a vector's length included)
  bool short_ = false;       ///< a field ran past the end
  bool open_ended_ = false;  ///< the last field took the rest
  std::string data_mismatch_;  ///< why a vector's length does not match the bytes after it
};

// ---- Each payload's fields in wire order: the one list payload() writes and parse() reads ----------
/// `Self` is `Body`, const (writing) or not (reading).
template <class Self, class Body>
concept PayloadOf = std::same_as<std::remove_const_t<Self>, Body>;

auto fields(PayloadOf<Ack> auto& m) { return std::tie(m.acked_id); }
auto fields(PayloadOf<Nack> auto& m) { return std::tie(m.nacked_id, m.text); }
auto fields(PayloadOf<AsciiText> auto& m) { return std::tie(m.text); }
auto fields(PayloadOf<DeviceInformation> auto& m) {
  return std::tie(m.device_type, m.device_revision, m.firmware_version_major, m.firmware_version_minor,
                  m.firmware_version_patch, m.reserved);
}
auto fields(PayloadOf<ProtocolVersion> auto& m) {
  return std::tie(m.version_major, m.version_minor, m.version_patch, m.reserved);
}
auto fields(PayloadOf<GeneralRequest> auto& m) { return std::tie(m.requested_id); }
auto fields(PayloadOf<SetDeviceId> auto& m) { return std::tie(m.id, m.reserved); }
auto fields(PayloadOf<DeviceData> auto& m) {
  return std::tie(m.mode, m.gain_setting, m.angle_grad, m.transmit_duration_us, m.sample_period_ticks,
                  m.transmit_frequency_khz, m.number_of_samples, m.data);
}
auto fields(PayloadOf<AutoDeviceData> auto& m) {
  return std::tie(m.mode, m.gain_setting, m.angle_grad, m.transmit_duration_us, m.sample_period_ticks,
                  m.transmit_frequency_khz, m.start_angle_grad, m.stop_angle_grad, m.num_steps, m.delay_ms,
                  m.number_of_samples, m.data);
}
auto fields(PayloadOf<Reset> auto& m) { return std::tie(m.bootloader, m.reserved); }
auto fields(PayloadOf<Transducer> auto& m) {
  return std::tie(m.mode, m.gain_setting, m.angle_grad, m.transmit_duration_us, m.sample_period_ticks,
                  m.transmit_frequency_khz, m.number_of_samples, m.transmit, m.reserved);
}
auto fields(PayloadOf<AutoTransmit> auto& m) {
  return std::tie(m.mode, m.gain_setting, m.transmit_duration_us, m.sample_period_ticks, m.transmit_frequency_khz,
                  m.number_of_samples, m.start_angle_grad, m.stop_angle_grad, m.num_steps, m.delay_ms);
}
auto fields(PayloadOf<MotorOff> auto&) { return std::tie(); }

/// The payload of `body`: its fields written in order.
template <class Body>
std::vector<std::uint8_t> writeFields(const Body& body) {
  std::vector<std::uint8_t> out;
  std::apply([&](const auto&... field) { (FieldWriter{out}(field), ...); }, fields(body));
  return out;
}

/// The `Body` of `payload`: its fields read in order; none (with `why`) unless they take it exactly.
template <class Body>
std::optional<Body> readFields(std::span<const std::uint8_t> payload, std::string* why) {
  Body body;
  FieldReader reader(payload);
  std::apply([&](auto&... field) { (reader(field), ...); }, fields(body));
  if (!reader.exact(why)) return std::nullopt;
  return body;
}

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

// ---- Payloads: written and read by their field lists above -----------------------------------------

std::vector<std::uint8_t> Ack::payload() const { return writeFields(*this); }
std::optional<Ack> Ack::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<Ack>(payload, why);
}

std::vector<std::uint8_t> Nack::payload() const { return writeFields(*this); }
std::optional<Nack> Nack::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<Nack>(payload, why);
}

std::vector<std::uint8_t> AsciiText::payload() const { return writeFields(*this); }
std::optional<AsciiText> AsciiText::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<AsciiText>(payload, why);
}

std::vector<std::uint8_t> DeviceInformation::payload() const { return writeFields(*this); }
std::optional<DeviceInformation> DeviceInformation::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<DeviceInformation>(payload, why);
}

std::string DeviceInformation::text() const {
  const std::string type = device_type == 2   ? "Ping360"
                           : device_type == 1 ? "Ping echosounder"
                                              : "ping-protocol device type " + std::to_string(device_type);
  return type + " (firmware " + std::to_string(firmware_version_major) + "." + std::to_string(firmware_version_minor) +
         "." + std::to_string(firmware_version_patch) + ")";
}

std::vector<std::uint8_t> ProtocolVersion::payload() const { return writeFields(*this); }
std::optional<ProtocolVersion> ProtocolVersion::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<ProtocolVersion>(payload, why);
}

std::vector<std::uint8_t> GeneralRequest::payload() const { return writeFields(*this); }
std::optional<GeneralRequest> GeneralRequest::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<GeneralRequest>(payload, why);
}

std::vector<std::uint8_t> SetDeviceId::payload() const { return writeFields(*this); }
std::optional<SetDeviceId> SetDeviceId::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<SetDeviceId>(payload, why);
}

std::vector<std::uint8_t> DeviceData::payload() const { return writeFields(*this); }
std::optional<DeviceData> DeviceData::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<DeviceData>(payload, why);
}

std::vector<std::uint8_t> AutoDeviceData::payload() const { return writeFields(*this); }
std::optional<AutoDeviceData> AutoDeviceData::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<AutoDeviceData>(payload, why);
}

DeviceData AutoDeviceData::deviceData() const {
  return {mode, gain_setting, angle_grad, transmit_duration_us, sample_period_ticks, transmit_frequency_khz,
          number_of_samples, data};
}

std::vector<std::uint8_t> Reset::payload() const { return writeFields(*this); }
std::optional<Reset> Reset::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<Reset>(payload, why);
}

std::vector<std::uint8_t> Transducer::payload() const { return writeFields(*this); }
std::optional<Transducer> Transducer::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<Transducer>(payload, why);
}

std::vector<std::uint8_t> AutoTransmit::payload() const { return writeFields(*this); }
std::optional<AutoTransmit> AutoTransmit::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<AutoTransmit>(payload, why);
}

std::optional<MotorOff> MotorOff::parse(std::span<const std::uint8_t> payload, std::string* why) {
  return readFields<MotorOff>(payload, why);
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
