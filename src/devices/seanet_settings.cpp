/// @file seanet_settings.cpp
/// planSeaNetCommand: HeadSettings → mtHeadCommand (see seanet_settings.hpp, seanet_driver.hpp).

#include "seanet_settings.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kUnitsPerTurn = 6400.0;  // 1/16 gradian
constexpr int kAheadUnits = 3200;
constexpr double kAdIntervalUnit_s = 640e-9;
constexpr double kDefaultRange_m = 10.0;
constexpr double kMaxRange_m = 1638.3;  // RangeScale's 14 bits of decimetres
constexpr double kDefaultGainPercent = 40.0;
constexpr int kDefaultBins = 400;
constexpr int kMaxBins = 1500;
constexpr int kMinAdInterval = 5;
constexpr int kDefaultStepUnits = 32;
constexpr std::uint8_t kAdSpan = 149;  // SeaNet Pro, the shared V4LOG
constexpr std::uint8_t kAdLow = 14;
constexpr double kIGainPerPercent = 2.1;  // 0…100% → 0…210

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

/// "40", "40%", " 40.5 % " → 40.5; anything else throws.
double parseGainPercent(const std::string& text) {
  std::string digits = text;
  while (!digits.empty() && std::isspace(static_cast<unsigned char>(digits.back()))) digits.pop_back();
  if (!digits.empty() && digits.back() == '%') digits.pop_back();
  std::size_t used = 0;
  double value = 0.0;
  bool parsed = false;
  try {
    value = std::stod(digits, &used);
    parsed = true;
  } catch (const std::exception&) {
  }
  while (parsed && used < digits.size() && std::isspace(static_cast<unsigned char>(digits[used]))) ++used;
  if (!parsed || used != digits.size() || !std::isfinite(value) || value < 0.0 || value > 100.0) {
    throw ValueError("SeaNet head: gain '" + text + "' is not a percentage; expected 0 to 100, e.g. \"40\" or \"40%\"");
  }
  return value;
}

/// Radians clockwise from ahead → the head's units, ahead at 3200, wrapped to 0…6399.
std::uint16_t headUnits(double bearing_rad) {
  const long units = std::lround(bearing_rad * kUnitsPerTurn / kTwoPi) + kAheadUnits;
  return static_cast<std::uint16_t>(((units % 6400) + 6400) % 6400);
}

double unitsToDeg(double units) { return units * 360.0 / kUnitsPerTurn; }

}  // namespace

SeaNetPlan planSeaNetCommand(const SeaNetDriverOptions& options, const SeaNetHeadKnowledge& head) {
  const HeadSettings& s = options.settings;
  SeaNetPlan plan;
  seanet::HeadCommand& c = plan.command;

  if (!std::isfinite(s.sound_speed_m_s) || s.sound_speed_m_s < 1000.0 || s.sound_speed_m_s > 2000.0) {
    throw ValueError("SeaNet head: sound_speed_m_s " + number(s.sound_speed_m_s) + " is out of range; expected 1000 to 2000 m/s");
  }
  const double range_m = s.range_m.value_or(kDefaultRange_m);
  if (!std::isfinite(range_m) || range_m < 0.1 - 1e-9 || range_m > kMaxRange_m) {
    throw ValueError("SeaNet head: range " + number(range_m) + " m is out of range; expected 0.1 to 1638.3 m (RangeScale in decimetres)");
  }
  const double gain_percent = s.gain ? parseGainPercent(*s.gain) : kDefaultGainPercent;
  const int bins = options.bins.value_or(kDefaultBins);
  if (bins < 1 || bins > kMaxBins) {
    throw ValueError("SeaNet head: bins " + std::to_string(bins) + " is out of range; expected 1 to 1500");
  }
  const double step_units_exact = s.step_rad ? *s.step_rad * kUnitsPerTurn / kTwoPi : kDefaultStepUnits;
  const long step_units = std::lround(step_units_exact);
  if (!std::isfinite(step_units_exact) || step_units < 1 || step_units > 255) {
    throw ValueError("SeaNet head: step " + number(unitsToDeg(step_units_exact)) +
                     "° is out of range; expected 0.05625° to 14.34° (1 to 255 × 1/16 gradian; Low 1.8°, Medium 0.9°, "
                     "High 0.45°, Ultimate 0.225°)");
  }
  const bool continuous = s.fullTurns();
  if (!continuous && !(std::isfinite(s.sector_width_rad) && s.sector_width_rad > 0.0)) {
    throw ValueError("SeaNet head: sector width " + number(s.sector_width_rad * 180.0 / std::numbers::pi) +
                     "° is out of range; expected a step to 360°");
  }
  const long width_units = continuous ? 6400 : std::lround(s.sector_width_rad * kUnitsPerTurn / kTwoPi);
  if (!continuous && width_units < step_units) {
    throw ValueError("SeaNet head: sector width " + number(unitsToDeg(static_cast<double>(width_units))) +
                     "° holds no step of " + number(unitsToDeg(static_cast<double>(step_units))) +
                     "°; expected a width of at least one step, up to 360°");
  }
  if (!std::isfinite(s.sector_center_rad)) throw ValueError("SeaNet head: sector centre is not finite; expected degrees");
  if (s.frequency_khz && !(std::isfinite(*s.frequency_khz) && *s.frequency_khz > 0.0)) {
    throw ValueError("SeaNet head: frequency " + number(*s.frequency_khz) + " kHz is out of range; expected > 0 kHz");
  }
  const double ad_interval_exact = 2.0 * range_m / (s.sound_speed_m_s * bins) / kAdIntervalUnit_s;
  const long ad_interval = std::lround(ad_interval_exact);
  if (ad_interval < kMinAdInterval || ad_interval > 65535) {
    throw ValueError("SeaNet head: range " + number(range_m) + " m over " + std::to_string(bins) +
                     " bins gives ADInterval " + number(ad_interval_exact) +
                     " × 640 ns; expected 5 to 65535: use fewer bins or a longer range");
  }

  // The channel.
  int channel = 0;
  std::optional<double> frequency_khz;
  const bool dual = head.user && head.user->dual_synth;
  if (dual) {
    if (s.frequency_khz) {
      channel = std::abs(*s.frequency_khz - kSeaNetChannelKhz[1]) < std::abs(*s.frequency_khz - kSeaNetChannelKhz[0]) ? 1 : 0;
    }
    frequency_khz = kSeaNetChannelKhz[channel];
  } else {
    if (head.version) frequency_khz = head.version->frequencyKhz();
    if (s.frequency_khz && head.user) {
      if (!frequency_khz) {
        plan.notes.push_back("frequency " + number(*s.frequency_khz) +
                             " kHz ignored: the head has one channel and does not say its frequency");
      } else if (std::abs(*s.frequency_khz - *frequency_khz) > 0.05 * *frequency_khz) {
        plan.notes.push_back("frequency " + number(*s.frequency_khz) + " kHz ignored: the head has one channel, at " +
                             number(*frequency_khz) + " kHz");
      }
    }
  }

  c.v3b = true;
  c.hd_ctrl = seanet::hdctrl::kAdc8On | seanet::hdctrl::kScanRight | seanet::hdctrl::kRaw | seanet::hdctrl::kHasMotor |
              seanet::hdctrl::kReplyAsl | (continuous ? seanet::hdctrl::kContinuous : 0) |
              (channel == 1 ? seanet::hdctrl::kChan2 : 0);
  c.head_type = 2;
  for (int ch = 0; ch < 2; ++ch) {
    c.tx_n[ch] = seanet::frequencyWord(kSeaNetChannelKhz[ch] * 1e3);
    c.rx_n[ch] = seanet::frequencyWord((kSeaNetChannelKhz[ch] + 455.0) * 1e3);
  }
  c.tx_pulse_length = static_cast<std::uint16_t>(std::min(65535L, std::lround(25.0 + 2.5 * range_m)));
  c.range_scale_dm = static_cast<std::uint16_t>(std::lround(range_m * 10.0));
  if (continuous) {
    c.left_limit = 0;
    c.right_limit = 6399;
  } else {
    c.left_limit = headUnits(s.sector_center_rad - 0.5 * s.sector_width_rad);
    c.right_limit = static_cast<std::uint16_t>((c.left_limit + width_units) % 6400);
  }
  c.ad_span = kAdSpan;
  c.ad_low = kAdLow;
  const auto igain = static_cast<std::uint8_t>(std::lround(gain_percent * kIGainPerPercent));
  c.igain[0] = c.igain[1] = igain;
  c.slope[0] = 90;
  c.slope[1] = 125;
  c.mo_time = 25;
  c.step = static_cast<std::uint8_t>(step_units);
  c.ad_interval = static_cast<std::uint16_t>(ad_interval);
  c.nbins = static_cast<std::uint16_t>(bins);
  c.max_ad_buf = 1000;
  c.lockout = 100;
  c.minor_axis_dir = 1600;
  c.major_axis_pan = 1;
  for (int ch = 0; ch < 2; ++ch) {
    c.ad_span_ch[ch] = kAdSpan;
    c.ad_low_ch[ch] = kAdLow;
    c.igain_ch[ch] = igain;
    c.slope_ch[ch] = c.slope[ch];
  }

  const double bin_interval_s = ad_interval * kAdIntervalUnit_s;
  plan.listening_s = bins * bin_interval_s;
  AppliedSettings& a = plan.applied;
  a.head = "Tritech SeaNet head";
  auto add = [&a](const std::string& name, const std::string& value) { a.fields.emplace_back(name, value); };
  add("range_m", number(c.range_scale_dm / 10.0));
  add("bins", std::to_string(bins));
  add("ad_interval_ns", number(bin_interval_s * 1e9));
  add("bin_length_m", number(bin_interval_s * s.sound_speed_m_s / 2.0));
  add("gain", number(gain_percent) + "%");
  add("igain", std::to_string(igain) + "/210");
  add("ad_span_db", number(kAdSpan * 80.0 / 255.0));
  add("ad_low_db", number(kAdLow * 80.0 / 255.0));
  add("scan", continuous ? "continuous" : "sector");
  if (!continuous) {
    const double centre_units = c.left_limit + 0.5 * static_cast<double>(width_units);
    double centre_deg = unitsToDeg(centre_units - kAheadUnits);
    centre_deg = std::fmod(centre_deg + 540.0, 360.0) - 180.0;
    add("sector_width_deg", number(unitsToDeg(static_cast<double>(width_units))));
    add("sector_center_deg", number(centre_deg));
    add("left_limit_grad16", std::to_string(c.left_limit));
    add("right_limit_grad16", std::to_string(c.right_limit));
  }
  add("step_deg", number(unitsToDeg(static_cast<double>(step_units))));
  add("step_grad16", std::to_string(step_units));
  if (frequency_khz) add("frequency_khz", number(*frequency_khz));
  add("channel", std::to_string(channel + 1));
  add("sound_speed_m_s", number(s.sound_speed_m_s));
  if (s.step_rad && std::abs(step_units_exact - static_cast<double>(step_units)) > 1e-6) {
    plan.notes.push_back("step " + number(unitsToDeg(step_units_exact)) + "° rounded to " + std::to_string(step_units) +
                         " × 1/16 gradian = " + number(unitsToDeg(static_cast<double>(step_units))) + "°");
  }
  return plan;
}

}  // namespace sonarmap::detail
