/// @file sweeps.cpp
/// bearingStep_rad, splitSweeps, SweepSplitter, SweepGrouper, mergeShortSweeps (see sweeps.hpp).

#include "sonarmap/sonar/sweeps.hpp"

#include <cmath>
#include <numbers>
#include <utility>

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Slack when comparing the accumulated turn with 2π: bearings read from single-precision
/// degrees carry ~1e-6 rad of rounding, far below any head step (≥ 0.05625° ≈ 1e-3 rad).
constexpr double kFullTurnSlack_rad = 1e-5;

}  // namespace

double bearingStep_rad(double from_rad, double to_rad) {
  const double step = std::remainder(to_rad - from_rad, kTwoPi);
  return step <= -std::numbers::pi ? step + kTwoPi : step;
}

bool SweepSplitter::startsSweep(const Beam& beam) {
  const HeadSetting setting = headSettingOf(beam);
  if (!previous_) {
    previous_ = Previous{beam.bearing_rad, setting};
    return false;
  }
  const double step = bearingStep_rad(previous_->bearing_rad, beam.bearing_rad);
  const int sign = step > 0.0 ? 1 : (step < 0.0 ? -1 : 0);
  const bool starts = setting != previous_->setting ||
                      (sign != 0 && direction_ != 0 && sign != direction_) ||
                      turned_rad_ + std::abs(step) >= kTwoPi - kFullTurnSlack_rad;
  previous_ = Previous{beam.bearing_rad, setting};
  if (starts) {
    direction_ = 0;
    turned_rad_ = 0.0;
    return true;
  }
  if (direction_ == 0 && sign != 0) direction_ = sign;
  turned_rad_ += std::abs(step);
  return false;
}

std::vector<SweepRange> splitSweeps(const std::vector<Beam>& beams) {
  std::vector<SweepRange> sweeps;
  SweepSplitter splitter;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    if (splitter.startsSweep(beams[i]) || sweeps.empty()) sweeps.push_back(SweepRange{i, i});
    sweeps.back().last_exclusive = i + 1;
  }
  return sweeps;
}

namespace {

int signOf(double step) { return step > 0.0 ? 1 : (step < 0.0 ? -1 : 0); }

/// The direction the head turned in `sweep`: the sign of its first non-zero step, else (one beam,
/// or repeated bearings) of the step into it; 0 when neither says.
int directionOf(const std::vector<Beam>& beams, const SweepRange& sweep) {
  for (std::size_t i = sweep.first + 1; i < sweep.last_exclusive; ++i) {
    if (const int sign = signOf(bearingStep_rad(beams[i - 1].bearing_rad, beams[i].bearing_rad)); sign != 0) return sign;
  }
  if (sweep.first == 0) return 0;
  return signOf(bearingStep_rad(beams[sweep.first - 1].bearing_rad, beams[sweep.first].bearing_rad));
}

/// Whether the head reversed between the beam before `first` and beam `first` (same head setting):
/// the step into it turns against `before_direction`, the direction of the sweep before.
bool reversesAt(const std::vector<Beam>& beams, std::size_t first, int before_direction) {
  if (first == 0 || first >= beams.size() || before_direction == 0) return false;
  if (headSettingOf(beams[first - 1]) != headSettingOf(beams[first])) return false;
  return signOf(bearingStep_rad(beams[first - 1].bearing_rad, beams[first].bearing_rad)) == -before_direction;
}

}  // namespace

std::vector<bool> wholeSweepFlags(const std::vector<Beam>& beams, const std::vector<SweepRange>& sweeps) {
  std::vector<bool> whole(sweeps.size(), false);
  std::vector<int> directions(sweeps.size());
  for (std::size_t k = 0; k < sweeps.size(); ++k) directions[k] = directionOf(beams, sweeps[k]);
  for (std::size_t k = 0; k < sweeps.size(); ++k) {
    const SweepRange& sweep = sweeps[k];
    double turned_rad = 0.0;
    double last_step_rad = 0.0;
    for (std::size_t i = sweep.first + 1; i < sweep.last_exclusive; ++i) {
      last_step_rad = std::abs(bearingStep_rad(beams[i - 1].bearing_rad, beams[i].bearing_rad));
      turned_rad += last_step_rad;
    }
    const bool full_turn = turned_rad + last_step_rad >= kTwoPi - kFullTurnSlack_rad;
    const bool begins_reversed = k > 0 && reversesAt(beams, sweep.first, directions[k - 1]);
    const bool ends_reversed = k + 1 < sweeps.size() && reversesAt(beams, sweep.last_exclusive, directions[k]);
    whole[k] = full_turn || (begins_reversed && ends_reversed);
  }
  return whole;
}

std::vector<SweepRange> wholeSweeps(const std::vector<Beam>& beams) {
  const std::vector<SweepRange> sweeps = splitSweeps(beams);
  const std::vector<bool> whole = wholeSweepFlags(beams, sweeps);
  std::vector<SweepRange> out;
  for (std::size_t k = 0; k < sweeps.size(); ++k) {
    if (whole[k]) out.push_back(sweeps[k]);
  }
  return out;
}

SweepGrouper::SweepGrouper(std::size_t min_beams) : min_beams_(min_beams) {}

std::size_t SweepGrouper::add(bool starts_sweep, const HeadSetting& setting) {
  const bool new_setting = setting_ && setting != *setting_;
  setting_ = setting;
  if (starts_sweep || new_setting) closeCurrent();
  if (new_setting) {  // nothing of another setting joins the group: it is final, however short
    ++current_;
    pending_sweeps_ = 0;
    return std::exchange(pending_, 0);
  }
  // Sweeps joined until they hold min_beams beams are a whole group: a short sweep after them
  // joins the next group (a narrow sector's passes commit a group every few passes).
  if (starts_sweep && pending_sweeps_ >= 2 && pending_ >= min_beams_) {
    ++current_;
    pending_sweeps_ = 0;
    return std::exchange(pending_, 0);
  }
  ++current_;
  if (pending_ >= min_beams_ && current_ >= min_beams_) {  // current will not join pending: it is final
    pending_sweeps_ = 0;
    return std::exchange(pending_, 0);
  }
  return 0;
}

std::size_t SweepGrouper::finish() {
  closeCurrent();
  pending_sweeps_ = 0;
  return std::exchange(pending_, 0);
}

void SweepGrouper::closeCurrent() {
  // A sweep joins the group before it when either is short (both long: the group left in add()).
  if (current_ == 0) return;
  pending_ += std::exchange(current_, 0);
  ++pending_sweeps_;
}

std::vector<SweepRange> mergeShortSweeps(const std::vector<Beam>& beams, const std::vector<SweepRange>& sweeps,
                                         std::size_t min_beams) {
  std::vector<SweepRange> merged;
  SweepGrouper grouper(min_beams);
  std::size_t next = sweeps.empty() ? 0 : sweeps.front().first;
  const auto take = [&](std::size_t beams) {
    if (beams == 0) return;
    merged.push_back(SweepRange{next, next + beams});
    next += beams;
  };
  for (const SweepRange& sweep : sweeps) {
    for (std::size_t i = sweep.first; i < sweep.last_exclusive; ++i) {
      take(grouper.add(i == sweep.first, headSettingOf(beams[i])));
    }
  }
  take(grouper.finish());
  return merged;
}

std::vector<SweepRange> groupSweeps(const std::vector<Beam>& beams, std::size_t min_beams) {
  return mergeShortSweeps(beams, splitSweeps(beams), min_beams);
}

}  // namespace sonarmap
