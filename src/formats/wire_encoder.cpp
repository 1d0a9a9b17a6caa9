/// @file wire_encoder.cpp
/// encodeSeaNetCapture, encodePing360Stream (see wire_encoder.hpp).

#include "sonarmap/formats/wire_encoder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "reader_support.hpp"
#include "sonarmap/formats/ping_protocol.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kMaxBins = 65000;
/// The source device id of a Ping360's messages (the head of the shared logs sends 2).
constexpr std::uint8_t kPing360SourceId = 2;

void putU16(std::vector<std::uint8_t>& out, unsigned value) {
  out.push_back(static_cast<std::uint8_t>(value & 0xFF));
  out.push_back(static_cast<std::uint8_t>((value >> 8) & 0xFF));
}

/// The beam's bin length as a whole number of `tick_s` of two-way travel, 1…65535.
unsigned sampleTicks(const Beam& beam, double tick_s, double sound_speed_m_s, const char* function) {
  const double ticks = std::round(2.0 * beam.bin_length_m / (sound_speed_m_s * tick_s));
  if (!(std::isfinite(beam.bin_length_m) && beam.bin_length_m > 0.0 && ticks >= 1.0 && ticks <= 65535.0)) {
    throw ValueError(std::string(function) + ": a bin length of " + std::to_string(beam.bin_length_m) +
                     " m is no sample interval of 1 to 65535 ticks");
  }
  return static_cast<unsigned>(ticks);
}

void checkBins(const Beam& beam, const char* function) {
  if (beam.intensities.size() > kMaxBins) {
    throw ValueError(std::string(function) + ": a beam of " + std::to_string(beam.intensities.size()) +
                     " bins does not fit one message (at most 65000)");
  }
}

/// `bearing_rad` (clockwise from ahead, beam.hpp) as `steps` per turn clockwise seen from above,
/// with ahead at `ahead_step` (the head's own count: SeaNet 3200 of 6400, Ping360 0 of 400).
unsigned clockwiseSteps(double bearing_rad, unsigned steps, unsigned ahead_step) {
  const long step = std::lround(bearing_rad * steps / (2.0 * std::numbers::pi)) + ahead_step;
  return static_cast<unsigned>((step % steps + steps) % steps);
}

/// A Ping360's transmit duration for the beam's pulse, µs (1…65535); 32 µs when the beam has none.
std::uint16_t transmitDurationUs(const Beam& beam, double sound_speed_m_s) {
  if (!beam.pulse_length_m) return 32;
  const double us = std::round(*beam.pulse_length_m * 2.0 / sound_speed_m_s * 1e6);
  return static_cast<std::uint16_t>(std::clamp(us, 1.0, 65535.0));
}

/// The beam's gain setting as the wire's byte (0 when unknown).
std::uint8_t gainByte(const Beam& beam) { return static_cast<std::uint8_t>(std::clamp(beam.gain_setting.value_or(0), 0, 255)); }

}  // namespace

std::vector<std::uint8_t> encodeSeaNetCapture(const std::vector<Beam>& beams, const CaptureOptions& options) {
  detail::checkSoundSpeed(options.sound_speed_m_s);
  std::vector<std::uint8_t> out;
  for (const Beam& beam : beams) {
    checkBins(beam, "encodeSeaNetCapture");
    const unsigned ad_interval = sampleTicks(beam, 640e-9, options.sound_speed_m_s, "encodeSeaNetCapture");
    const auto bins = static_cast<unsigned>(beam.intensities.size());
    const double span_db = beam.intensity_span_db.value_or(0.0);
    const auto ad_span = static_cast<unsigned>(std::clamp(std::lround(span_db * 255.0 / 80.0), 0L, 255L));
    seanet::HeadDataFields fields;  // head 2 to the host: device type 2, head status 0x10, sweep 0
    fields.hd_ctrl = seanet::hdctrl::kAdc8On;
    fields.range_scale_dm = static_cast<std::uint16_t>(std::lround(std::min(6553.5, bins * beam.bin_length_m * 10.0)));
    fields.gain = gainByte(beam);
    fields.ad_span = static_cast<std::uint8_t>(ad_span);
    fields.ad_interval = static_cast<std::uint16_t>(ad_interval);
    fields.left_limit = 0;
    fields.right_limit = 6399;
    fields.step = 32;  // 1.8°
    fields.bearing = static_cast<std::uint16_t>(clockwiseSteps(beam.bearing_rad, 6400, 3200));
    const std::vector<std::uint8_t> packet = seanet::encodeHeadData(fields, beam.intensities);
    out.insert(out.end(), packet.begin(), packet.end());
  }
  return out;
}

std::vector<std::uint8_t> encodePing360Stream(const std::vector<Beam>& beams, const CaptureOptions& options) {
  detail::checkSoundSpeed(options.sound_speed_m_s);
  std::vector<std::uint8_t> out;
  for (const Beam& beam : beams) {
    checkBins(beam, "encodePing360Stream");
    ping_protocol::DeviceData ping;
    ping.mode = 1;
    ping.gain_setting = gainByte(beam);
    ping.angle_grad = static_cast<std::uint16_t>(clockwiseSteps(beam.bearing_rad, 400, 0));
    ping.transmit_duration_us = transmitDurationUs(beam, options.sound_speed_m_s);
    ping.sample_period_ticks =
        static_cast<std::uint16_t>(sampleTicks(beam, 25e-9, options.sound_speed_m_s, "encodePing360Stream"));
    ping.transmit_frequency_khz = 750;
    ping.number_of_samples = static_cast<std::uint16_t>(beam.intensities.size());
    ping.data = beam.intensities;
    ping_protocol::appendMessage(out, ping_protocol::kDeviceData, ping.payload(), kPing360SourceId, 0);
  }
  return out;
}

}  // namespace sonarmap
