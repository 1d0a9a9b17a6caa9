/// @file ping360_settings.cpp
/// A Ping360's settings by Ping Viewer's rules (see ping360_settings.hpp).

#include "sonarmap/devices/ping360_settings.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kRadiansPerGradian = std::numbers::pi / 200.0;
constexpr double kDegreesPerGradian = 0.9;
constexpr double kDefaultRange_m = 20.0;
constexpr int kDefaultGain = 1;
constexpr double kDefaultFrequency_khz = 750.0;

/// `value` with up to 6 significant digits ("19.98", "0.9", "22200").
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string degrees(double radians) { return number(radians * 180.0 / std::numbers::pi); }

/// `value` wrapped into 0–399.
int wrapGradians(long value) {
  const long turn = kPing360GradiansPerTurn;
  return static_cast<int>((value % turn + turn) % turn);
}

/// The step in whole gradians: `step_rad` rounded to the nearest, at least 1 (the head's finest);
/// a step that is not whole adds a note of its rounding to `notes`.
int stepGradians(const std::optional<double>& step_rad, std::vector<std::string>& notes) {
  if (!step_rad) return 1;
  const double steps = *step_rad / kRadiansPerGradian;
  const double whole = std::max(1.0, std::round(steps));
  if (!std::isfinite(steps) || !(steps > 0.0) || whole > kPing360MaxStepGradians) {
    throw ValueError("--step " + degrees(*step_rad) +
                     " degrees is not a step of the Ping360: expected above 0 and up to 9 degrees (10 gradians; "
                     "the head steps in whole gradians of 0.9 degrees)");
  }
  if (std::abs(steps - whole) > 1e-6) {
    notes.push_back("--step " + degrees(*step_rad) + " degrees rounded to " + number(whole) + " gradian" +
                    (whole == 1.0 ? "" : "s") + " = " + number(whole * kDegreesPerGradian) +
                    " degrees (the Ping360 steps in whole gradians of 0.9 degrees)");
  }
  return static_cast<int>(whole);
}

}  // namespace

double Ping360Sampling::range_m(double sound_speed_m_s) const {
  return samples * (sample_period_ticks * kPing360Tick_s) * sound_speed_m_s / 2.0;
}

Ping360Sampling ping360Sampling(double range_m, double sound_speed_m_s) {
  // As Ping Viewer computes it: the distance in single precision, the quotient in double, stored
  // in a float, truncated to whole ticks.
  const float distance = static_cast<float>(range_m);
  const auto ticks = [&](int samples) {
    const double denominator = static_cast<double>(samples) * sound_speed_m_s * kPing360Tick_s;
    const auto period = static_cast<float>(static_cast<double>(2.0f * distance) / denominator);
    return static_cast<int>(period);
  };
  Ping360Sampling sampling;
  int samples = kPing360MaxSamples;
  int period = ticks(samples);
  while (period < kPing360MinSamplePeriodTicks && samples > 1) {
    --samples;
    period = ticks(samples);
  }
  sampling.samples = static_cast<std::uint16_t>(samples);
  sampling.sample_period_ticks = static_cast<std::uint16_t>(std::min(period, 0xFFFF));
  return sampling;
}

int ping360MaxTransmitDuration_us(int sample_period_ticks) {
  const int periods_64 = static_cast<int>(sample_period_ticks * kPing360Tick_s * 64e6);
  return std::min(kPing360MaxTransmitDuration_us, periods_64);
}

int ping360TransmitDuration_us(const Ping360Sampling& sampling, double sound_speed_m_s) {
  int duration = static_cast<int>(std::lround(8000.0 * sampling.range_m(sound_speed_m_s) / sound_speed_m_s));
  const double period_us = sampling.sample_period_ticks * kPing360Tick_s * 1e6;
  duration = std::max(static_cast<int>(2.5 * period_us), duration);
  return std::max(kPing360MinTransmitDuration_us,
                  std::min(ping360MaxTransmitDuration_us(sampling.sample_period_ticks), duration));
}

int ping360GainSetting(const std::string& gain) {
  std::string word;
  for (const char c : gain) word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (word == "low" || word == "0") return 0;
  if (word == "normal" || word == "medium" || word == "1") return 1;
  if (word == "high" || word == "2") return 2;
  throw ValueError("--gain '" + gain + "' is not a Ping360 gain setting: expected low, normal, high (or 0, 1, 2)");
}

std::string ping360GainWord(int gain_setting) {
  switch (gain_setting) {
    case 0: return "low";
    case 1: return "normal";
    case 2: return "high";
    default: return std::to_string(gain_setting);
  }
}

int ping360AngleDistance(int from_grad, int to_grad) {
  const int forward = wrapGradians(static_cast<long>(to_grad) - from_grad);
  return std::min(forward, kPing360GradiansPerTurn - forward);
}

int Ping360Settings::angleOf(std::size_t index) const {
  const int turn = kPing360GradiansPerTurn;
  if (full_turns) {
    return wrapGradians(first_grad + static_cast<long>(index % static_cast<std::size_t>(turn)) * step_grad);
  }
  const auto period = static_cast<std::size_t>(2 * sector_steps);
  const auto k = static_cast<long>(index % period);
  const long position = k <= sector_steps ? k : static_cast<long>(period) - k;
  return wrapGradians(first_grad + position * step_grad);
}

AppliedSettings Ping360Settings::applied() const {
  AppliedSettings settings;
  settings.head = "Ping360";
  settings.fields = {
      {"range_m", number(range_m())},
      {"gain", ping360GainWord(gain_setting)},
      {"sector_deg", full_turns ? "360" : number(sector_steps * step_grad * kDegreesPerGradian)},
      {"sector_center_deg", number(center_grad * kDegreesPerGradian)},
      {"step_deg", number(step_grad * kDegreesPerGradian)},
      {"frequency_khz", std::to_string(transmit_frequency_khz)},
      {"transmit_duration_us", std::to_string(transmit_duration_us)},
      {"sample_period_ns", std::to_string(sampling.sample_period_ticks * 25)},
      {"samples", std::to_string(sampling.samples)},
      {"sound_speed_m_s", number(sound_speed_m_s)},
  };
  return settings;
}

Ping360Settings ping360Settings(const HeadSettings& asked) {
  Ping360Settings settings;
  const double c = asked.sound_speed_m_s;
  if (!(c >= kPing360MinSoundSpeed_m_s && c <= kPing360MaxSoundSpeed_m_s)) {
    throw ValueError("--sound-speed " + number(c) + " m/s is outside 1400–1600 m/s (sea and fresh water)");
  }
  settings.sound_speed_m_s = c;
  const double range_m = asked.range_m.value_or(kDefaultRange_m);
  if (!(range_m >= kPing360MinRange_m && range_m <= kPing360MaxRange_m)) {
    throw ValueError("--range " + number(range_m) +
                     " m is outside the Ping360's 0.75–60 m (Blue Robotics' minimum to Ping Viewer's largest)");
  }
  settings.sampling = ping360Sampling(range_m, c);
  settings.transmit_duration_us = static_cast<std::uint16_t>(ping360TransmitDuration_us(settings.sampling, c));
  settings.gain_setting = static_cast<std::uint8_t>(asked.gain ? ping360GainSetting(*asked.gain) : kDefaultGain);
  const double frequency = asked.frequency_khz.value_or(kDefaultFrequency_khz);
  if (!(std::round(frequency) >= kPing360MinFrequency_khz && std::round(frequency) <= kPing360MaxFrequency_khz)) {
    throw ValueError("--frequency " + number(frequency) + " kHz is outside the Ping360's 500–1000 kHz");
  }
  settings.transmit_frequency_khz = static_cast<std::uint16_t>(std::lround(frequency));
  settings.step_grad = stepGradians(asked.step_rad, settings.notes);

  if (!std::isfinite(asked.sector_center_rad)) {
    throw ValueError("--sector-center " + degrees(asked.sector_center_rad) + " degrees is not a finite bearing");
  }
  settings.center_grad = wrapGradians(std::lround(asked.sector_center_rad / kRadiansPerGradian));
  const double width = asked.sector_width_rad;
  if (!(width > 0.0 && width <= 2.0 * std::numbers::pi + 1e-9)) {
    throw ValueError("--sector " + degrees(width) + " degrees is outside (0, 360]");
  }
  settings.full_turns = asked.fullTurns();
  if (settings.full_turns) {
    settings.first_grad = settings.center_grad;
    return settings;
  }
  settings.sector_steps = static_cast<int>(std::floor(width / kRadiansPerGradian / settings.step_grad + 1e-9));
  if (settings.sector_steps < 1) {
    throw ValueError("--sector " + degrees(width) + " degrees is narrower than one step (" +
                     number(settings.step_grad * kDegreesPerGradian) + " degrees)");
  }
  settings.first_grad = wrapGradians(settings.center_grad - settings.sector_steps * settings.step_grad / 2);
  return settings;
}

}  // namespace sonarmap
