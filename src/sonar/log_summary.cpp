/// @file log_summary.cpp
/// summarizeLog (see log_summary.hpp).

#include "sonarmap/sonar/log_summary.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <numbers>

#include "sonarmap/core/statistics.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;
/// A gap between neighbouring bearings wider than this many head steps breaks a full circle.
constexpr double kCircleGapSteps = 1.5;

/// `bearing_rad` in degrees within [0, 360).
double degrees0To360(double bearing_rad) {
  const double deg = std::fmod(bearing_rad * kDegPerRad, 360.0);
  const double wrapped = deg < 0.0 ? deg + 360.0 : deg;
  return wrapped >= 360.0 ? 0.0 : wrapped;
}

int signOf(double value) { return value > 0.0 ? 1 : (value < 0.0 ? -1 : 0); }

/// The non-zero |bearing steps| between consecutive beams of [first, last_exclusive), radians.
std::vector<double> movingSteps(const std::vector<Beam>& beams, std::size_t first, std::size_t last_exclusive) {
  std::vector<double> steps;
  for (std::size_t i = first + 1; i < last_exclusive; ++i) {
    const double step = std::abs(bearingStep_rad(beams[i - 1].bearing_rad, beams[i].bearing_rad));
    if (step > 0.0) steps.push_back(step);
  }
  return steps;
}

/// The smallest arc holding every bearing of `bearings_rad` (see BearingArc); `step_rad` the head's step.
BearingArc arcOf(const std::vector<double>& bearings_rad, double step_rad) {
  BearingArc arc;
  if (bearings_rad.empty()) return arc;
  std::vector<double> deg;
  deg.reserve(bearings_rad.size());
  for (const double bearing : bearings_rad) {
    if (std::isfinite(bearing)) deg.push_back(degrees0To360(bearing));
  }
  if (deg.empty()) return arc;
  std::sort(deg.begin(), deg.end());
  deg.erase(std::unique(deg.begin(), deg.end()), deg.end());
  // The widest gap between neighbours around the circle; the arc is the rest.
  std::size_t after_gap = 0;
  double widest = deg.front() + 360.0 - deg.back();
  for (std::size_t i = 1; i < deg.size(); ++i) {
    if (deg[i] - deg[i - 1] > widest) {
      widest = deg[i] - deg[i - 1];
      after_gap = i;
    }
  }
  if (deg.size() > 1 && step_rad > 0.0 && widest <= kCircleGapSteps * step_rad * kDegPerRad) {
    return BearingArc{0.0, 0.0, 360.0, true};
  }
  arc.from_deg = deg[after_gap];
  arc.to_deg = deg[(after_gap + deg.size() - 1) % deg.size()];
  arc.span_deg = deg.size() == 1 ? 0.0 : 360.0 - widest;
  return arc;
}

/// The first non-zero step's sign in [first, last_exclusive), 0 when the head did not move.
int directionOf(const std::vector<Beam>& beams, std::size_t first, std::size_t last_exclusive) {
  for (std::size_t i = first + 1; i < last_exclusive; ++i) {
    const int sign = signOf(bearingStep_rad(beams[i - 1].bearing_rad, beams[i].bearing_rad));
    if (sign != 0) return sign;
  }
  return 0;
}

/// Summaries of the sweeps without their kind's sector test (full turn or partial for now).
std::vector<SweepSummary> describeSweeps(const std::vector<Beam>& beams, double log_step_rad) {
  std::vector<SweepSummary> sweeps;
  for (const SweepRange& range : splitSweeps(beams)) {
    SweepSummary sweep;
    sweep.first_beam = range.first;
    sweep.beams = range.size();
    sweep.direction = directionOf(beams, range.first, range.last_exclusive);
    std::vector<double> steps = movingSteps(beams, range.first, range.last_exclusive);
    double turned_rad = 0.0;
    for (const double step : steps) turned_rad += step;
    const double step_rad = steps.empty() ? log_step_rad : percentile(steps, 0.5);
    sweep.span_deg = turned_rad * kDegPerRad;
    sweep.first_bearing_deg = degrees0To360(beams[range.first].bearing_rad);
    sweep.last_bearing_deg = degrees0To360(beams[range.last_exclusive - 1].bearing_rad);
    const double duration = beams[range.last_exclusive - 1].time_s - beams[range.first].time_s;
    sweep.duration_s = std::isfinite(duration) ? duration : 0.0;
    const bool full = step_rad > 0.0 && turned_rad + step_rad >= kTwoPi - 0.5 * step_rad;
    sweep.kind = full ? SweepKind::kFullTurn : SweepKind::kPartialTurn;
    sweeps.push_back(sweep);
  }
  return sweeps;
}

/// True when the head reverses from sweep `sweep` into the beam that follows it (same setting,
/// a step against the sweep's direction).
bool reversesAfter(const std::vector<Beam>& beams, const SweepSummary& sweep) {
  const std::size_t next = sweep.first_beam + sweep.beams;
  if (next >= beams.size() || sweep.direction == 0) return false;
  const Beam& last = beams[next - 1];
  return headSettingOf(last) == headSettingOf(beams[next]) &&
         signOf(bearingStep_rad(last.bearing_rad, beams[next].bearing_rad)) == -sweep.direction;
}

/// Marks the sector passes among the sweeps that are not full turns; counts each kind.
void classifySweeps(const std::vector<Beam>& beams, LogSummary& summary) {
  std::vector<double> sector_bearings_rad, between_reversals_rad;  // bearings of all passes, of whole ones
  std::vector<double> turn_beams, turn_times_s;
  for (std::size_t k = 0; k < summary.sweeps.size(); ++k) {
    SweepSummary& sweep = summary.sweeps[k];
    if (sweep.kind == SweepKind::kFullTurn) {
      ++summary.full_turns;
      turn_beams.push_back(static_cast<double>(sweep.beams));
      if (sweep.beams > 1 && sweep.duration_s > 0.0) {
        turn_times_s.push_back(sweep.duration_s * static_cast<double>(sweep.beams) / static_cast<double>(sweep.beams - 1));
      }
      continue;
    }
    const bool after_reversal = k > 0 && reversesAfter(beams, summary.sweeps[k - 1]);
    const bool before_reversal = reversesAfter(beams, sweep);
    if (after_reversal || before_reversal) {
      sweep.kind = SweepKind::kSectorPass;
      ++summary.sector_passes;
      for (std::size_t i = sweep.first_beam; i < sweep.first_beam + sweep.beams; ++i) {
        sector_bearings_rad.push_back(beams[i].bearing_rad);
        if (after_reversal && before_reversal) between_reversals_rad.push_back(beams[i].bearing_rad);
      }
    } else {
      ++summary.partial_turns;
    }
  }
  if (!turn_beams.empty()) summary.beams_per_turn = static_cast<std::size_t>(std::lround(percentile(turn_beams, 0.5)));
  if (!turn_times_s.empty()) summary.full_turn_s = percentile(turn_times_s, 0.5);
  // The sector is what the head sweeps between its turning points: a pass that leads into the sector
  // scan from a turn, or is cut by a setting change, would widen or shift it.
  summary.sector_arc = arcOf(between_reversals_rad.empty() ? sector_bearings_rad : between_reversals_rad,
                             summary.step_deg / kDegPerRad);
}

/// Each head setting in order of first use, with its beams.
std::vector<HeadSettingUse> settingUses(const std::vector<Beam>& beams) {
  std::vector<HeadSettingUse> uses;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    const Beam& beam = beams[i];
    const HeadSetting setting = headSettingOf(beam);
    auto use = std::find_if(uses.begin(), uses.end(), [&](const HeadSettingUse& u) { return u.setting == setting; });
    const std::size_t bins = beam.intensities.size();
    if (use == uses.end()) {
      HeadSettingUse fresh;
      fresh.setting = setting;
      fresh.first_beam = i;
      fresh.min_bins = bins;
      fresh.first_time_s = std::numeric_limits<double>::infinity();
      fresh.last_time_s = -std::numeric_limits<double>::infinity();
      use = uses.insert(uses.end(), fresh);
    }
    ++use->beams;
    if (i == 0 || headSettingOf(beams[i - 1]) != setting) ++use->stretches;
    use->bins = std::max(use->bins, bins);
    use->min_bins = std::min(use->min_bins, bins);
    use->reach_m = std::max(use->reach_m, static_cast<double>(bins) * beam.bin_length_m);
    if (beam.pulse_length_m && (!use->pulse_length_m || *beam.pulse_length_m < *use->pulse_length_m)) {
      use->pulse_length_m = beam.pulse_length_m;
    }
    if (std::isfinite(beam.time_s)) {
      use->first_time_s = std::min(use->first_time_s, beam.time_s);
      use->last_time_s = std::max(use->last_time_s, beam.time_s);
    }
  }
  for (HeadSettingUse& use : uses) {
    if (!std::isfinite(use.first_time_s)) use.first_time_s = use.last_time_s = 0.0;  // no finite time
  }
  return uses;
}

/// `reason` with each run of digits written as 'N'.
std::string digitPattern(const std::string& reason) {
  const auto digit = [&](std::size_t i) { return std::isdigit(static_cast<unsigned char>(reason[i])) != 0; };
  std::string pattern;
  for (std::size_t i = 0; i < reason.size(); ++i) {
    if (!digit(i)) {
      pattern += reason[i];
    } else if (i == 0 || !digit(i - 1)) {
      pattern += 'N';
    }
  }
  return pattern;
}


NavCoverage navCoverage(const NavTrack& nav, const std::vector<Beam>& beams) {
  NavCoverage coverage;
  coverage.fixes = nav.size();
  coverage.first_time_s = nav.front().time_s;
  coverage.last_time_s = nav.back().time_s;
  coverage.duration_s = coverage.last_time_s - coverage.first_time_s;
  for (std::size_t i = 1; i < nav.size(); ++i) {
    coverage.distance_m += (nav[i].position_ned_m - nav[i - 1].position_ned_m).norm();
  }
  for (const Beam& beam : beams) {
    if (beam.time_s < coverage.first_time_s) ++coverage.beams_before;
    if (beam.time_s > coverage.last_time_s) ++coverage.beams_after;
    if (!(beam.time_s >= coverage.first_time_s && beam.time_s <= coverage.last_time_s)) ++coverage.beams_outside;
  }
  return coverage;
}

}  // namespace

const char* sweepKindName(SweepKind kind) {
  switch (kind) {
    case SweepKind::kFullTurn:
      return "full turn";
    case SweepKind::kSectorPass:
      return "sector pass";
    case SweepKind::kPartialTurn:
      return "partial turn";
  }
  return "?";
}

LogSummary summarizeLog(const SonarLog& log, const NavTrack& nav) {
  LogSummary summary;
  const std::vector<Beam>& beams = log.beams;
  summary.sonar = log.sonar;
  summary.beams = beams.size();
  summary.skipped_beams = log.skipped_beams;
  addSkipReasons(summary.skip_reasons, log.skip_reasons);
  summary.notes = log.notes;
  if (!nav.empty()) summary.nav = navCoverage(nav, beams);
  if (beams.empty()) return summary;

  double first = std::numeric_limits<double>::infinity(), last = -first;
  for (const Beam& beam : beams) {
    if (!std::isfinite(beam.time_s)) continue;
    first = std::min(first, beam.time_s);
    last = std::max(last, beam.time_s);
  }
  if (std::isfinite(first)) {
    summary.first_time_s = first;
    summary.last_time_s = last;
    summary.duration_s = last - first;
  }
  if (summary.duration_s > 0.0) summary.beam_rate_hz = static_cast<double>(beams.size() - 1) / summary.duration_s;

  std::vector<double> steps = movingSteps(beams, 0, beams.size());
  const double step_rad = percentile(steps, 0.5);
  summary.step_deg = step_rad * kDegPerRad;
  std::vector<double> bearings_rad;
  bearings_rad.reserve(beams.size());
  for (const Beam& beam : beams) bearings_rad.push_back(beam.bearing_rad);
  summary.bearings = arcOf(bearings_rad, step_rad);

  summary.sweeps = describeSweeps(beams, step_rad);
  classifySweeps(beams, summary);

  summary.settings = settingUses(beams);
  summary.range_scales = rangeScales(log);
  if (const RangeScale* followed = mostUsedRangeScale(summary.range_scales)) summary.followed_scale = *followed;
  return summary;
}

void addSkipReasons(std::vector<SkipReasonGroup>& groups, const std::vector<std::string>& reasons) {
  for (const std::string& reason : reasons) {
    std::string pattern = digitPattern(reason);
    auto group = std::find_if(groups.begin(), groups.end(), [&](const SkipReasonGroup& g) { return g.pattern == pattern; });
    if (group == groups.end()) group = groups.insert(groups.end(), SkipReasonGroup{std::move(pattern), reason, 0});
    ++group->count;
  }
}

}  // namespace sonarmap
