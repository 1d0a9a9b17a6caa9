/// @file mavlink_fixes.cpp
/// MavlinkFixMaker: an autopilot's frames → fixes on its boot clock (see mavlink_fixes.hpp and, for
/// the rules, mavlink_navigation.hpp).

#include "mavlink_fixes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/mavlink_messages.hpp"
#include "vehicle_track.hpp"

namespace sonarmap::detail {
namespace {

/// A boot time this far behind the latest one is a new boot (the autopilot rebooted), as the
/// `.tlog` reader has always told reboots.
constexpr double kRebootBack_s = 10.0;
constexpr std::size_t kEarlyFrames = 64;
constexpr std::size_t kNotesPerBoot = 20;

constexpr std::array<NavSource, 2> kHorizontalChain{NavSource::kLocalPosition, NavSource::kVisionDelta};
constexpr std::size_t kIntervalsKept = 15;
/// How long a source that has sent one sample is followed while its second tells its rhythm:
/// 3 intervals of a 0.5 Hz stream.
constexpr double kFirstSilence_s = 6.0;

std::span<const NavSource> chainSources(int chain) {
  if (chain == 0) return kHorizontalChain;
  return kDepthChain;
}

/// The messages of the vehicle that carry time_boot_ms (its first field) and are read.
bool isVehicleMessage(std::uint32_t id) { return id == 29 || id == 30 || id == 32 || id == 33 || id == 137 || id == 143; }

std::uint32_t bootTimeMs(const MavlinkFrame& frame) {
  return static_cast<std::uint32_t>(frame.payload[0] | (frame.payload[1] << 8) | (frame.payload[2] << 16) |
                                    (static_cast<std::uint32_t>(frame.payload[3]) << 24));
}

bool sameSender(const MavlinkFrame& frame, const MavlinkSender& sender) {
  return frame.system == sender.system && frame.component == sender.component;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : " and ") + n;
  return out;
}

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", s);
  return text;
}

}  // namespace

const char* navSourceName(NavSource s) {
  switch (s) {
    case NavSource::kLocalPosition: return "LOCAL_POSITION_NED";
    case NavSource::kVisionDelta: return "VISION_POSITION_DELTA";
    case NavSource::kGlobalPosition: return "GLOBAL_POSITION_INT.relative_alt";
    case NavSource::kPressure2: return "SCALED_PRESSURE2";
    case NavSource::kPressure3: return "SCALED_PRESSURE3";
    case NavSource::kPressure1: return "SCALED_PRESSURE";
  }
  return "?";
}

bool SourceSeries::add(double time_s, const Eigen::Vector3d& value) {
  if (!std::isfinite(time_s) || !value.allFinite()) return false;
  if (!samples_.empty() && time_s <= samples_.back().time_s) return false;
  if (samples_.empty()) {
    run_start_s_ = time_s;
  } else {
    const double interval_s = time_s - samples_.back().time_s;
    if (interval_s > silence_s()) run_start_s_ = time_s;  // judged by the rhythm before this sample
    intervals_s_.push_back(interval_s);
    if (intervals_s_.size() > kIntervalsKept) intervals_s_.pop_front();
  }
  samples_.push_back({time_s, value});
  return true;
}

double SourceSeries::silence_s() const {
  if (intervals_s_.empty()) return std::max(min_silence_s_, kFirstSilence_s);
  std::vector<double> sorted(intervals_s_.begin(), intervals_s_.end());
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  return std::max(min_silence_s_, 3.0 * *middle);
}

std::optional<double> SourceSeries::lastTimeAtOrBefore(double time_s) const {
  const auto after = std::upper_bound(samples_.begin(), samples_.end(), time_s,
                                      [](double t, const Sample& s) { return t < s.time_s; });
  if (after == samples_.begin()) return std::nullopt;
  return (after - 1)->time_s;
}

std::optional<Eigen::Vector3d> SourceSeries::at(double time_s) const {
  if (samples_.empty() || time_s < samples_.front().time_s || time_s > samples_.back().time_s) return std::nullopt;
  const auto after = std::lower_bound(samples_.begin(), samples_.end(), time_s,
                                      [](const Sample& s, double t) { return s.time_s < t; });
  if (after->time_s == time_s) return after->value;
  const Sample& before = *(after - 1);
  const double w = (time_s - before.time_s) / (after->time_s - before.time_s);
  return ((1.0 - w) * before.value + w * after->value).eval();
}

void SourceSeries::forgetBefore(double time_s) {
  while (samples_.size() > 1 && samples_[1].time_s <= time_s) samples_.pop_front();
}

MavlinkFixMaker::MavlinkFixMaker(const MavlinkNavigationOptions& options) : options_(options) {
  for (SourceSeries& s : series_) s.setMinSilence_s(options.max_hold_s);
}

void MavlinkFixMaker::take(const MavlinkFrame& frame, double arrival_s, std::vector<BootFix>& out) {
  if (!frame.checked) return;
  if (frame.message_id == MavlinkVisionPositionDelta::kId) {
    takeVisionDelta(frame, arrival_s);
    makeFixes(out, false);
    return;
  }
  const bool parameter = frame.message_id == MavlinkParamValue::kId;
  if (!parameter && !isVehicleMessage(frame.message_id)) return;
  if (!vehicle_) {
    if (frame.message_id != MavlinkAttitude::kId) {
      early_.emplace_back(frame, arrival_s);
      if (early_.size() > kEarlyFrames) early_.pop_front();
      return;
    }
    vehicle_ = MavlinkSender{frame.system, frame.component};
    for (const auto& [early, early_arrival_s] : std::exchange(early_, {})) {
      if (!sameSender(early, *vehicle_)) continue;
      if (early.message_id == MavlinkParamValue::kId) {
        takeParameter(early);
      } else {
        takeVehicleFrame(early, early_arrival_s, out);
      }
    }
  }
  if (!sameSender(frame, *vehicle_)) return;
  if (parameter) {
    takeParameter(frame);
  } else {
    takeVehicleFrame(frame, arrival_s, out);
  }
}

void MavlinkFixMaker::startBoot(double time_s) {
  if (in_boot_) {
    notes_.push_back("the autopilot rebooted (boot time " + seconds(time_s) + " s after " + seconds(boot_now_s_) +
                     " s): its clock is found anew");
  }
  in_boot_ = true;
  offsets_s_.push_back(std::numeric_limits<double>::infinity());
  boot_first_s_ = boot_now_s_ = time_s;
  last_attitude_s_ = -std::numeric_limits<double>::infinity();
  for (SourceSeries& s : series_) s.clear();
  chain_value_ = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  chain_words_ = {};
  sourced_ = {};
  last_horizontal_.reset();
  depth_source_.reset();
  unpaired_.clear();
  for (auto& pairs : depth_pairs_) pairs.clear();
  boot_notes_ = 0;
}

void MavlinkFixMaker::takeVehicleFrame(const MavlinkFrame& frame, double arrival_s, std::vector<BootFix>& out) {
  const double time_s = bootTimeMs(frame) / 1000.0;
  if (in_boot_ && time_s < boot_now_s_ - kRebootBack_s) {
    makeFixes(out, true);  // the previous boot's waiting attitudes, as at the end of a stream
    startBoot(time_s);
  } else if (!in_boot_) {
    startBoot(time_s);
  }
  boot_now_s_ = std::max(boot_now_s_, time_s);
  double& offset_s = offsets_s_.back();
  if (std::isfinite(arrival_s)) offset_s = std::min(offset_s, arrival_s - time_s);
  switch (frame.message_id) {
    case MavlinkAttitude::kId: {
      const MavlinkAttitude a = *decodeMavlink<MavlinkAttitude>(frame);
      const Attitude attitude{time_s, a.roll_rad, a.pitch_rad, a.yaw_rad};
      if (!std::isfinite(attitude.roll_rad) || !std::isfinite(attitude.pitch_rad) || !std::isfinite(attitude.yaw_rad) ||
          time_s <= last_attitude_s_) {
        ++without_fix_;
        break;
      }
      waiting_.push_back(attitude);
      latest_attitude_ = attitude;
      last_attitude_s_ = time_s;
      break;
    }
    case MavlinkLocalPositionNed::kId: {
      const MavlinkLocalPositionNed p = *decodeMavlink<MavlinkLocalPositionNed>(frame);
      if (series(NavSource::kLocalPosition).add(time_s, Eigen::Vector3d(p.x_m, p.y_m, p.z_m))) {
        addAutopilotDepth(NavSource::kLocalPosition, time_s, p.z_m);
      }
      break;
    }
    case MavlinkGlobalPositionInt::kId: {
      const MavlinkGlobalPositionInt g = *decodeMavlink<MavlinkGlobalPositionInt>(frame);
      if (series(NavSource::kGlobalPosition).add(time_s, Eigen::Vector3d(0.0, 0.0, -g.relative_alt_mm / 1000.0))) {
        addAutopilotDepth(NavSource::kGlobalPosition, time_s, -g.relative_alt_mm / 1000.0);
      }
      if (g.lat_degE7 == 0 && g.lon_degE7 == 0) break;  // no position
      const GeodeticFix fix{time_s, {g.lat_degE7 / 1e7, g.lon_degE7 / 1e7, g.alt_mm / 1000.0}};
      try {
        requireGeodetic(fix.point, "GLOBAL_POSITION_INT at boot time " + seconds(time_s) + " s");
        geodetic_.push_back({offsets_s_.size() - 1, fix});
      } catch (const ValueError& error) {
        if (geodetic_rejected_++ == 0) geodetic_reason_ = error.what();
      }
      break;
    }
    default: {  // the three SCALED_PRESSUREs
      const MavlinkScaledPressure p = *decodeMavlink<MavlinkScaledPressure>(frame);
      if (!(p.press_abs_hpa > 0.0f) || !std::isfinite(p.press_abs_hpa)) break;  // no barometer behind it
      const NavSource s = p.message_id == 137 ? NavSource::kPressure2
                          : p.message_id == 143 ? NavSource::kPressure3
                                                : NavSource::kPressure1;
      addPressure(s, time_s, p.press_abs_hpa * 100.0);
      break;
    }
  }
  makeFixes(out, false);
}

void MavlinkFixMaker::takeVisionDelta(const MavlinkFrame& frame, double arrival_s) {
  if (!vision_sender_) vision_sender_ = MavlinkSender{frame.system, frame.component};
  if (!sameSender(frame, *vision_sender_) || !in_boot_ || !latest_attitude_ || !std::isfinite(arrival_s)) return;
  const MavlinkVisionPositionDelta v = *decodeMavlink<MavlinkVisionPositionDelta>(frame);
  const Eigen::Vector3d delta_body(v.position_delta_m[0], v.position_delta_m[1], v.position_delta_m[2]);
  if (!delta_body.allFinite()) return;
  NavSample pose;
  pose.roll_rad = latest_attitude_->roll_rad;
  pose.pitch_rad = latest_attitude_->pitch_rad;
  pose.yaw_rad = latest_attitude_->yaw_rad;
  vision_ne_m_ += (bodyToNed(pose).linear() * delta_body).head<2>();
  // Timed by its arrival on the autopilot's clock: its own time_usec is unset (BlueOS) or another clock.
  const double time_s = arrival_s - offsets_s_.back();
  SourceSeries& vision = series(NavSource::kVisionDelta);
  const Eigen::Vector3d value(vision_ne_m_.x(), vision_ne_m_.y(), 0.0);
  if (!vision.add(time_s, value) && vision.seen() && std::isfinite(time_s) && time_s <= vision.lastTime_s()) {
    vision.setLast(value);
  }
}

MavlinkFixMaker::Choice MavlinkFixMaker::choose(Chain chain, double time_s, bool final) const {
  const double hold_s = options_.max_hold_s;
  const bool starting = !final && boot_now_s_ < boot_first_s_ + hold_s;  // sources still being learnt
  bool any_seen = false;
  for (const NavSource s : chainSources(chain)) {
    const SourceSeries& samples = series(s);
    if (!samples.seen()) {
      if (starting) return Choice::wait();
      continue;
    }
    any_seen = true;
    if (const std::optional<Eigen::Vector3d> value = samples.at(time_s)) return Choice::of(*value, s);
    if (samples.firstTime_s() > time_s) {  // the source began after this attitude
      if (samples.firstTime_s() - time_s <= hold_s) return Choice::drop();
      continue;
    }
    // The source's last sample is before this attitude.
    if (final || samples.lastTime_s() < time_s - hold_s) continue;
    if (boot_now_s_ <= time_s + hold_s) return Choice::wait();
    return Choice::of(samples.lastValue(), s, true);
  }
  if (final && any_seen) return Choice::drop();
  return Choice::of(chain_value_[chain], std::nullopt);
}

void MavlinkFixMaker::noteChoice(Chain chain, const Choice& choice, double time_s) {
  if (choice.source) {
    chain_value_[chain] = choice.value;
    const std::string name = navSourceName(*choice.source);
    if (std::find(used_[chain].begin(), used_[chain].end(), name) == used_[chain].end()) used_[chain].push_back(name);
  }
  std::string words;
  if (choice.source) {
    sourced_[chain] = true;
    words = std::string(navSourceName(*choice.source)) + (choice.stale ? " (its last sample: the message stopped)" : "") +
            (choice.calibration.empty() ? "" : " (" + choice.calibration + ")");
  } else {
    std::string names;
    for (const NavSource s : chainSources(chain)) names += (names.empty() ? "" : ", ") + std::string(navSourceName(s));
    words = sourced_[chain] ? "held at its last value (" + names + " silent)" : "held at 0 (no " + names + ")";
  }
  if (words == chain_words_[chain]) return;
  chain_words_[chain] = words;
  if (boot_notes_ > kNotesPerBoot) return;
  if (++boot_notes_ > kNotesPerBoot) {
    notes_.push_back("further changes of the navigation's sources are not listed");
    return;
  }
  notes_.push_back((chain == kHorizontal ? "north and east" : "depth") + std::string(" from boot time ") +
                   seconds(time_s) + " s: " + words);
}

void MavlinkFixMaker::makeFixes(std::vector<BootFix>& out, bool final) {
  while (!waiting_.empty()) {
    const Attitude& a = waiting_.front();
    const Choice horizontal = choose(kHorizontal, a.time_s, final);
    if (horizontal.kind == Choice::Kind::kWait) break;
    const Choice depth = chooseDepth(a.time_s, final);
    if (depth.kind == Choice::Kind::kWait) break;
    if (horizontal.kind == Choice::Kind::kDrop || depth.kind == Choice::Kind::kDrop) {
      ++without_fix_;
      waiting_.pop_front();
      continue;
    }
    // A sum of deltas is relative: it moves north and east on from the previous fix's, so
    // changing to it (at the start, or when LOCAL_POSITION_NED stops) makes no jump.
    Choice h = horizontal;
    if (h.source == NavSource::kVisionDelta) {
      if (last_horizontal_ != NavSource::kVisionDelta) vision_anchor_m_ = chain_value_[kHorizontal] - h.value;
      h.value += vision_anchor_m_;
    }
    last_horizontal_ = h.source;
    noteChoice(kHorizontal, h, a.time_s);
    noteChoice(kDepth, depth, a.time_s);
    BootFix made;
    made.boot = offsets_s_.size() - 1;
    made.fix.time_s = a.time_s;
    made.fix.roll_rad = a.roll_rad;
    made.fix.pitch_rad = a.pitch_rad;
    made.fix.yaw_rad = a.yaw_rad;
    made.fix.position_ned_m = Eigen::Vector3d(h.value.x(), h.value.y(), depth.value.z());
    out.push_back(made);
    waiting_.pop_front();
  }
  if (final) {
    without_fix_ += waiting_.size();
    waiting_.clear();
  }
  const double oldest_s = waiting_.empty() ? last_attitude_s_ : waiting_.front().time_s;
  for (SourceSeries& s : series_) s.forgetBefore(oldest_s);
}

void MavlinkFixMaker::finish(std::vector<BootFix>& out) { makeFixes(out, true); }

std::string MavlinkFixMaker::description() const {
  const std::string horizontal = joined(used_[kHorizontal]);
  const std::string depth = joined(used_[kDepth]);
  if (horizontal.empty() && depth.empty()) return vehicleTrackWords("ATTITUDE", "", "");
  if (horizontal == "LOCAL_POSITION_NED" && depth == "LOCAL_POSITION_NED") {
    return vehicleTrackWords("ATTITUDE", "LOCAL_POSITION_NED", "");
  }
  if (horizontal.empty()) return vehicleTrackWords("ATTITUDE", "", depth);
  return "attitude ATTITUDE, north and east from " + horizontal + ", depth from " + (depth.empty() ? "nothing (0)" : depth);
}

}  // namespace sonarmap::detail
