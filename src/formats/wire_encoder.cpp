/// @file wire_encoder.cpp
/// encodeSeaNetCapture, encodePing360Stream (see wire_encoder.hpp).

#include "sonarmap/formats/wire_encoder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "reader_support.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kMaxBins = 65000;

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

/// The beam's gain setting as the wire's byte (0 when unknown).
/// A Ping360's transmit duration for the beam's pulse, µs (1…65535); 32 µs when the beam has none.
std::uint16_t transmitDurationUs(const Beam& beam, double sound_speed_m_s) {
  if (!beam.pulse_length_m) return 32;
  const double us = std::round(*beam.pulse_length_m * 2.0 / sound_speed_m_s * 1e6);
  return static_cast<std::uint16_t>(std::clamp(us, 1.0, 65535.0));
}

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
    const unsigned sample_period = sampleTicks(beam, 25e-9, options.sound_speed_m_s, "encodePing360Stream");
    const auto bins = static_cast<unsigned>(beam.intensities.size());
    const std::size_t start = out.size();
    out.insert(out.end(), {'B', 'R'});
    putU16(out, 14 + bins);  // payload length
    putU16(out, 2300);       // device_data
    out.insert(out.end(), {0x02, 0x00});  // source device, destination
    out.insert(out.end(), {0x01, gainByte(beam)});  // mode 1, gain setting
    putU16(out, clockwiseSteps(beam.bearing_rad, 400, 0));
    putU16(out, transmitDurationUs(beam, options.sound_speed_m_s));
    putU16(out, sample_period);
    putU16(out, 750);  // transmit frequency, kHz
    putU16(out, bins);  // number of samples
    putU16(out, bins);  // data length
    out.insert(out.end(), beam.intensities.begin(), beam.intensities.end());
    unsigned sum = 0;
    for (std::size_t i = start; i < out.size(); ++i) sum += out[i];
    putU16(out, sum & 0xFFFF);
  }
  return out;
}

}  // namespace sonarmap
