/// @file ping360_messages.cpp
/// readPing360Messages: ping-protocol messages → Ping360 beams (see ping360_messages.hpp).

#include "ping360_messages.hpp"

#include <cstdint>
#include <numbers>
#include <optional>

#include "../io/byte_io.hpp"
#include "frame_scanner.hpp"
#include "wire_protocols.hpp"

namespace sonarmap::detail {
namespace {

constexpr std::size_t kHeaderBytes = 8;    // 'B' 'R', payload length, message id, source, destination
constexpr std::size_t kChecksumBytes = 2;
/// Ping Viewer's parser takes messages shorter than its 10,240-byte buffer (pingparserext.h); an
/// auto_device_data of 1,200 samples is 1,230 bytes. The cap also bounds the checksum work per candidate.
constexpr std::size_t kMaxMessageBytes = 10240;
constexpr std::size_t kPayloadLengthAt = 2;
constexpr std::size_t kMessageIdAt = 4;
constexpr std::uint16_t kDeviceInformation = 4;
constexpr std::uint16_t kDeviceData = 2300;
constexpr std::uint16_t kAutoDeviceData = 2301;
constexpr std::uint32_t kGradiansPerTurn = 400;
constexpr double kSamplePeriodUnit_s = 25e-9;

// Payload offsets shared by both messages, and where each one's sample count and data begin.
constexpr std::size_t kGainSettingAt = 1;
constexpr std::size_t kAngleAt = 2;
constexpr std::size_t kTransmitDurationAt = 4;  ///< µs
constexpr std::size_t kSamplePeriodAt = 6;
constexpr std::size_t kDeviceDataLengthAt = 12;      // device_data: after number_of_samples
constexpr std::size_t kAutoDeviceDataLengthAt = 18;  // auto_device_data: after the sector fields

/// Ping-protocol framing of `stream` (from a 'B' 'R' to the last byte received).
FrameProbe probeMessage(std::span<const unsigned char> stream, std::size_t /*at*/) {
  const std::size_t available = stream.size();
  const auto cut = [&](const std::string& what) {
    return FrameProbe{FrameProbe::Kind::kCutShort, 0,
                      what + ", the capture ends " + std::to_string(available) + " bytes after its start"};
  };
  if (available < kHeaderBytes) return cut("header");
  const std::size_t size = kHeaderBytes + u16At(stream, kPayloadLengthAt) + kChecksumBytes;
  if (size >= kMaxMessageBytes) {
    return {FrameProbe::Kind::kNotAFrame, 0,
            "declares " + std::to_string(size) + " bytes, expected fewer than " + std::to_string(kMaxMessageBytes)};
  }
  if (size > available) return cut("declares " + std::to_string(size) + " bytes");
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i < size - kChecksumBytes; ++i) sum += stream[i];
  const std::uint16_t checksum = u16At(stream, size - kChecksumBytes);
  if (checksum != (sum & 0xFFFFU)) {
    return {FrameProbe::Kind::kNotAFrame, 0,
            "checksum " + std::to_string(checksum) + " but its bytes sum to " + std::to_string(sum & 0xFFFFU) +
                " (mod 65536)"};
  }
  return {FrameProbe::Kind::kFrame, size, {}};
}

/// The beam of a device_data / auto_device_data payload (time unset), or why there is none.
std::optional<Beam> decodeDeviceData(std::span<const unsigned char> payload, std::size_t length_at,
                                     double sound_speed_m_s, std::string& why) {
  const std::size_t data_at = length_at + 2;
  if (payload.size() < data_at) {
    why = "payload of " + std::to_string(payload.size()) + " bytes, expected at least " + std::to_string(data_at);
    return std::nullopt;
  }
  const std::uint16_t angle = u16At(payload, kAngleAt);
  const std::uint16_t sample_period = u16At(payload, kSamplePeriodAt);
  const std::size_t samples = u16At(payload, length_at);
  if (data_at + samples != payload.size()) {
    why = "data length " + std::to_string(samples) + " but the payload holds " +
          std::to_string(payload.size() - data_at) + " bytes after its fields";
  } else if (angle >= kGradiansPerTurn) {
    why = "angle " + std::to_string(angle) + ", expected 0…399 gradians";
  } else if (sample_period == 0) {
    why = "sample period 0, expected > 0 (units of 25 ns)";
  } else if (samples == 0) {
    why = "no samples";
  } else {
    Beam beam;
    beam.bearing_rad = 2.0 * std::numbers::pi * static_cast<double>(angle) / kGradiansPerTurn;  // clockwise, 0 ahead
    beam.bin_length_m = sample_period * kSamplePeriodUnit_s * sound_speed_m_s / 2.0;
    beam.intensities.assign(payload.begin() + static_cast<std::ptrdiff_t>(data_at), payload.end());
    beam.gain_setting = payload[kGainSettingAt];
    const std::uint16_t transmit_duration_us = u16At(payload, kTransmitDurationAt);
    if (transmit_duration_us > 0) beam.pulse_length_m = transmit_duration_us * 1e-6 * sound_speed_m_s / 2.0;
    return beam;
  }
  return std::nullopt;
}

/// device_information (common message 4): u8 device_type (1 Ping echosounder, 2 Ping360), u8
/// device_revision, u8 firmware major, minor, patch, u8 reserved.
std::string deviceName(std::span<const unsigned char> payload) {
  const std::string type = payload[0] == 2 ? "Ping360" : (payload[0] == 1 ? "Ping echosounder" : "ping-protocol device type " + std::to_string(payload[0]));
  return type + " (firmware " + std::to_string(payload[2]) + "." + std::to_string(payload[3]) + "." + std::to_string(payload[4]) + ")";
}

}  // namespace

FrameScan ping360FrameScan(const std::string& source, double sound_speed_m_s,
                           const std::function<std::string(std::size_t)>& where, Ping360Messages& out) {
  FrameScan scan;
  scan.start = "BR";
  scan.noun = "message";
  scan.where = where;
  scan.probe = probeMessage;
  scan.on_frame = [source, sound_speed_m_s, &where, &out](std::span<const unsigned char> message, std::size_t at) {
    const std::uint16_t id = u16At(message, kMessageIdAt);
    const std::string name = "message at " + where(at);
    if (id == kDeviceInformation && message.size() >= kHeaderBytes + 5 + kChecksumBytes) {
      out.device = deviceName(message.subspan(kHeaderBytes, message.size() - kHeaderBytes - kChecksumBytes));
      return;
    }
    if (id != kDeviceData && id != kAutoDeviceData) {
      addSkip(out.log, source, name + ": id " + std::to_string(id) +
                                   ", not device_data (2300) or auto_device_data (2301)");
      return;
    }
    const std::span<const unsigned char> payload = message.subspan(kHeaderBytes, message.size() - kHeaderBytes - kChecksumBytes);
    std::string why;
    std::optional<Beam> beam = decodeDeviceData(payload, id == kDeviceData ? kDeviceDataLengthAt : kAutoDeviceDataLengthAt,
                                                sound_speed_m_s, why);
    if (!beam) {
      addSkip(out.log, source, name + " (" + (id == kDeviceData ? "device_data" : "auto_device_data") + "): " + why);
      return;
    }
    out.log.beams.push_back(std::move(*beam));
    out.beam_ends.push_back(at + message.size());
  };
  return scan;
}

Ping360Messages readPing360Messages(std::span<const unsigned char> stream, const std::string& source,
                                    double sound_speed_m_s, const std::function<std::string(std::size_t)>& where) {
  Ping360Messages result;
  scanFrames(stream, ping360FrameScan(source, sound_speed_m_s, where, result), source, result.log);
  return result;
}

}  // namespace sonarmap::detail
