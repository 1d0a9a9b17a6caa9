/// @file mavlink_depth_choice.cpp
/// MavlinkFixMaker's depth: one source at a time with hysteresis, and the pressures made depths in
/// the autopilot's own calibration (the rules: mavlink_navigation.hpp, "Depth").

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mavlink_fixes.hpp"
#include "sonarmap/formats/mavlink_messages.hpp"

namespace sonarmap::detail {
namespace {

constexpr double kGravity_m_s2 = 9.80665;
/// ArduSub's water barometer: (ground pressure − pressure) / 9800 / BARO_SPEC_GRAV metres up
/// (ArduPilot's AP_Baro::update: "9800 Pascal/ m depth in water").
constexpr double kArduSubPascalsPerMetre = 9800.0;
constexpr std::size_t kPairsKept = 15;
/// An autopilot depth waits this long (boot clock) for a pressure sample after its time.
constexpr double kPairWait_s = 2.0;

bool isPressure(NavSource s) {
  return s == NavSource::kPressure1 || s == NavSource::kPressure2 || s == NavSource::kPressure3;
}

/// The barometer of a pressure source: SCALED_PRESSURE 0, SCALED_PRESSURE2 1, SCALED_PRESSURE3 2.
std::size_t barometer(NavSource s) { return s == NavSource::kPressure1 ? 0 : s == NavSource::kPressure2 ? 1 : 2; }

std::size_t rank(NavSource s) {
  return static_cast<std::size_t>(std::find(kDepthChain.begin(), kDepthChain.end(), s) - kDepthChain.begin());
}

std::string number(const char* format, double value) {
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace

void MavlinkFixMaker::takeParameter(const MavlinkFrame& frame) {
  const MavlinkParamValue p = *decodeMavlink<MavlinkParamValue>(frame);
  const double value = p.param_value;
  if (!std::isfinite(value) || !(value > 0.0)) return;
  // ArduPilot 4's names, then ArduSub 3.5's (the GND_ group before it became BARO_).
  static constexpr std::array<std::pair<const char*, int>, 8> kNames{{{"BARO1_GND_PRESS", 0},
                                                                        {"BARO2_GND_PRESS", 1},
                                                                        {"BARO3_GND_PRESS", 2},
                                                                        {"GND_ABS_PRESS", 0},
                                                                        {"GND_ABS_PRESS2", 1},
                                                                        {"GND_ABS_PRESS3", 2},
                                                                        {"BARO_SPEC_GRAV", -1},
                                                                        {"GND_SPEC_GRAV", -1}}};
  for (const auto& [name, index] : kNames) {
    if (p.param_id != name) continue;
    if (index < 0) {
      specific_gravity_ = value;
    } else {
      ground_pressure_pa_[static_cast<std::size_t>(index)] = value;
    }
    if (std::find(parameters_said_.begin(), parameters_said_.end(), p.param_id) == parameters_said_.end()) {
      parameters_said_.push_back(p.param_id);
      notes_.push_back("the autopilot's " + p.param_id + " is " + number("%.6g", value) +
                       " (its calibration of the pressures' depths)");
    }
    return;
  }
}

void MavlinkFixMaker::addAutopilotDepth(NavSource source, double time_s, double depth_m) {
  if (!std::isfinite(depth_m)) return;
  unpaired_.push_back({source, time_s, depth_m});
  pairDepths();
}

void MavlinkFixMaker::addPressure(NavSource source, double time_s, double pressure_pa) {
  if (series(source).add(time_s, Eigen::Vector3d(0.0, 0.0, pressure_pa))) pairDepths();
}

void MavlinkFixMaker::pairDepths() {
  while (!unpaired_.empty()) {
    const AutopilotDepth& d = unpaired_.front();
    bool reached = false;  // a barometer has a sample at or after the depth's time
    for (const NavSource p : {NavSource::kPressure1, NavSource::kPressure2, NavSource::kPressure3}) {
      const SourceSeries& pressures = series(p);
      if (!pressures.seen() || pressures.lastTime_s() < d.time_s) continue;
      reached = true;
      if (const std::optional<Eigen::Vector3d> at = pressures.at(d.time_s)) {
        std::deque<DepthPair>& pairs = depth_pairs_[barometer(p)];
        pairs.push_back({d.source, d.depth_m, at->z()});
        if (pairs.size() > kPairsKept) pairs.pop_front();
      }
    }
    if (!reached && d.time_s >= boot_now_s_ - kPairWait_s) return;
    unpaired_.pop_front();
  }
}

MavlinkFixMaker::PressureCalibration MavlinkFixMaker::pressureCalibration(NavSource source) const {
  PressureCalibration c;
  const std::optional<double>& ground_pa = ground_pressure_pa_[barometer(source)];
  c.surface_pa = ground_pa.value_or(options_.pressure.surface_pressure_pa);
  c.pascals_per_metre = specific_gravity_ ? kArduSubPascalsPerMetre * *specific_gravity_
                                          : options_.pressure.water_density_kg_m3 * kGravity_m_s2;
  const std::string gnd = "BARO" + std::to_string(barometer(source) + 1) + "_GND_PRESS";
  const std::string conversion =
      (ground_pa ? "the autopilot's " + gnd + " " + number("%.0f", *ground_pa) + " Pa"
                 : number("%.0f", c.surface_pa) + " Pa at the surface") +
      (specific_gravity_ ? " and BARO_SPEC_GRAV " + number("%.4g", *specific_gravity_) + " (9800 Pa/m each)"
                         : " and " + number("%.0f", options_.pressure.water_density_kg_m3) + " kg/m3");
  const std::deque<DepthPair>& pairs = depth_pairs_[barometer(source)];
  if (pairs.empty()) {
    c.words = conversion + (ground_pa || specific_gravity_ ? "" : ": no calibration from the autopilot");
    return c;
  }
  // The autopilot's depth beside this pressure while both came: the median offset between them.
  std::vector<double> offsets_m;
  for (const DepthPair& pair : pairs) offsets_m.push_back(pair.depth_m - (pair.pressure_pa - c.surface_pa) / c.pascals_per_metre);
  const auto middle = offsets_m.begin() + static_cast<std::ptrdiff_t>(offsets_m.size() / 2);
  std::nth_element(offsets_m.begin(), middle, offsets_m.end());
  c.offset_m = *middle;
  c.words = "in " + std::string(navSourceName(pairs.back().autopilot)) + "'s calibration: offset " +
            number("%+.3f", c.offset_m) + " m while both came, on " + conversion;
  return c;
}

bool MavlinkFixMaker::depthAlive(NavSource source, double time_s) const {
  const SourceSeries& samples = series(source);
  if (!samples.seen() || samples.firstTime_s() > time_s) return false;
  const std::optional<double> before_s = samples.lastTimeAtOrBefore(time_s);
  return before_s && time_s - *before_s <= samples.silence_s();
}

MavlinkFixMaker::Choice MavlinkFixMaker::chooseDepth(double time_s, bool final) {
  const double hold_s = options_.max_hold_s;
  const bool starting = !final && boot_now_s_ < boot_first_s_ + hold_s;  // sources still being learnt
  bool any_seen = false;
  std::optional<NavSource> best;  // the most preferred source coming at this time
  for (const NavSource s : kDepthChain) {
    if (!series(s).seen()) {
      if (starting) return Choice::wait();
      continue;
    }
    any_seen = true;
    if (depthAlive(s, time_s)) {
      best = s;
      break;
    }
  }
  std::optional<NavSource> chosen = depth_source_;
  if (chosen && depthAlive(*chosen, time_s)) {
    // A preferred source is taken back only once it has come for a silence's length again.
    if (best && rank(*best) < rank(*chosen) && series(*best).runStart_s() + series(*best).silence_s() <= time_s) {
      chosen = best;
    }
  } else {
    if (!chosen) {  // the boot's first choice: no fallback just before a preferred source begins
      for (const NavSource s : kDepthChain) {
        if (best && rank(s) >= rank(*best)) break;
        const SourceSeries& later = series(s);
        if (later.seen() && later.firstTime_s() > time_s && later.firstTime_s() - time_s <= hold_s) return Choice::drop();
      }
    }
    chosen = best;
  }
  if (!chosen) {
    if (final && any_seen) return Choice::drop();
    depth_source_.reset();
    return Choice::of(chain_value_[kDepth], std::nullopt);
  }
  const SourceSeries& samples = series(*chosen);
  std::optional<Eigen::Vector3d> value = samples.at(time_s);
  if (!value) {  // after the source's last sample, within its silence: its next one, else its last
    if (final) return Choice::drop();
    if (boot_now_s_ <= time_s + hold_s) return Choice::wait();
    value = samples.lastValue();
  }
  if (chosen != depth_source_) {
    depth_source_ = chosen;
    depth_calibration_ = isPressure(*chosen) ? pressureCalibration(*chosen) : PressureCalibration{};
  }
  if (!isPressure(*chosen)) return Choice::of(Eigen::Vector3d(0.0, 0.0, value->z()), chosen);
  const PressureCalibration& c = depth_calibration_;
  const double depth_m = (value->z() - c.surface_pa) / c.pascals_per_metre + c.offset_m;
  return Choice::of(Eigen::Vector3d(0.0, 0.0, depth_m), chosen, false, c.words);
}

}  // namespace sonarmap::detail
