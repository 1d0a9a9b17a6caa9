/// @file ping360_echo_model.cpp
/// ping360EchoModel: the simulated head and echo model of a Ping360 ping at its commanded settings
/// (see ping360_emulator.hpp for each choice and its source).

#include <algorithm>
#include <cmath>

#include "sonarmap/devices/ping360_emulator.hpp"
#include "sonarmap/devices/ping360_settings.hpp"

namespace sonarmap {
namespace {

constexpr double kGainStep_db = 4.0;           ///< per gain setting (ping360_emulator.hpp) [L, A]
constexpr double kPresetFrequency_khz = 750.0;  ///< the presets' beam widths are at 750 kHz
constexpr int kMaxSpeckleLooks = 64;

/// The preset nearest to `range_m` on a log scale, and the gain setting its levels describe.
SonarPreset presetFor(double range_m, int& preset_gain) {
  if (range_m < std::sqrt(2.0 * 5.0)) {
    preset_gain = 0;
    return sonarPreset("ping360-2m");
  }
  if (range_m < std::sqrt(5.0 * 50.0)) {
    preset_gain = 0;
    return sonarPreset("ping360-5m");
  }
  preset_gain = 2;
  return sonarPreset("ping360");
}

}  // namespace

SonarPreset ping360EchoModel(const ping_protocol::DeviceData& settings, double sound_speed_m_s) {
  const int samples = std::max<int>(1, settings.number_of_samples);
  const int period = std::max<int>(1, settings.sample_period_ticks);
  const double range_m = samples * (period * kPing360Tick_s) * sound_speed_m_s / 2.0;
  int preset_gain = 0;
  SonarPreset model = presetFor(range_m, preset_gain);
  MsisHeadOptions& head = model.head;
  EchoModelOptions& echo = model.echo;
  head.range_m = range_m;
  head.bins = samples;
  head.logs_pulse_length = true;

  const double pulse_m = std::max(1, static_cast<int>(settings.transmit_duration_us)) * 1e-6 * sound_speed_m_s / 2.0;
  echo.noise_level_db -= 10.0 * std::log10(pulse_m / echo.pulse_length_m);
  echo.pulse_length_m = pulse_m;
  const double looks = std::round(pulse_m / head.binLength_m());
  echo.speckle_looks = static_cast<int>(std::clamp(looks, 2.0, static_cast<double>(kMaxSpeckleLooks)));
  echo.ad_low_db -= kGainStep_db * (static_cast<int>(settings.gain_setting) - preset_gain);

  const double frequency_khz = std::max<int>(1, settings.transmit_frequency_khz);
  const double widening = kPresetFrequency_khz / frequency_khz;
  head.horizontal_beam_width_rad *= widening;
  head.vertical_beam_width_rad *= widening;
  return model;
}

}  // namespace sonarmap
