#pragma once
/// @file log_summary.hpp
/// What a sonar log holds, before mapping it (`sonarmap info`): its beams and clock, its
/// sweeps (full turns, sector passes), the bearings it covers, each head setting (range scale and
/// gain) with the beams that use it, what the reader skipped and why, and how a navigation track
/// covers it. Computed from the beams alone: no format, no detector, no map.
///
/// Units are in the names: seconds (the log's own clock, Beam::time_s), metres, degrees. Bearings
/// are in the sonar frame of beam.hpp (clockwise from the head's ahead, bearing 0, seen from
/// above), reported in degrees in [0, 360).

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/range_scales.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {

/// What one sweep of splitSweeps is.
enum class SweepKind {
  kFullTurn,     ///< the head turned 360° (its bearings' accumulated |step| reaches 2π less one step)
  kSectorPass,   ///< less than a turn, and it ends or begins where the head reverses (a sector scan)
  kPartialTurn,  ///< less than a turn without a reversal: cut by a head-setting change or the log's ends
};

/// "full turn", "sector pass" or "partial turn".
const char* sweepKindName(SweepKind kind);

/// One sweep of splitSweeps(log.beams).
struct SweepSummary {
  std::size_t first_beam = 0;  ///< index of its first beam in SonarLog::beams
  std::size_t beams = 0;       ///< its beam count (≥ 1)
  SweepKind kind = SweepKind::kPartialTurn;
  int direction = 0;           ///< +1 clockwise (bearings increase), −1 counter-clockwise, 0 the head did not move
  double span_deg = 0.0;       ///< accumulated |bearing step| from its first beam to its last, degrees
  double first_bearing_deg = 0.0;  ///< bearing of its first beam, degrees in [0, 360)
  double last_bearing_deg = 0.0;   ///< bearing of its last beam, degrees in [0, 360)
  double duration_s = 0.0;     ///< time of its last beam − time of its first, seconds
};

/// The smallest arc of bearings that holds every bearing of a set: clockwise from
/// `from_deg` to `to_deg` (to_deg < from_deg when it crosses bearing 0).
struct BearingArc {
  double from_deg = 0.0;   ///< degrees in [0, 360)
  double to_deg = 0.0;     ///< degrees in [0, 360)
  double span_deg = 0.0;   ///< degrees in [0, 360]; 360 for a full circle
  bool full_circle = false;  ///< no gap between the bearings wider than 1.5 head steps
};

/// One head setting (HeadSetting: a range scale and a gain) and the beams that use it.
struct HeadSettingUse {
  HeadSetting setting;          ///< bin length (metres) and gain setting (head's units; unset: none recorded)
  std::size_t bins = 0;         ///< most bins of one of its beams
  std::size_t min_bins = 0;     ///< fewest bins of one of its beams (less than `bins` for a cut beam)
  double reach_m = 0.0;         ///< bins × bin length, metres: the range scale as the user set it
  /// The shortest Beam::pulse_length_m of its beams, metres; unset when none records one.
  std::optional<double> pulse_length_m;
  std::size_t beams = 0;        ///< beams of this setting in the log
  std::size_t first_beam = 0;   ///< index of its first beam
  std::size_t stretches = 0;    ///< runs of consecutive beams of this setting (> 1: the user came back to it)
  double first_time_s = 0.0;    ///< earliest time of its beams, seconds
  double last_time_s = 0.0;     ///< latest time of its beams, seconds
};

/// Skipped items whose reasons differ only in their numbers (byte offsets, counts, record numbers).
struct SkipReasonGroup {
  std::string pattern;       ///< the reason with each run of digits written as 'N'
  std::string first_reason;  ///< the first reason of the group, as the reader wrote it
  std::size_t count = 0;     ///< reasons in the group
};

/// Adds skip lines (SonarLog::skip_reasons) to `groups`: each joins the group of its pattern (its
/// digits written as 'N'), or starts one at the end. Groups are kept in order of first appearance,
/// so reasons handed over in batches (WireStreamDecoder::takeSkipReasons) group as if read at once.
void addSkipReasons(std::vector<SkipReasonGroup>& groups, const std::vector<std::string>& reasons);

/// How a navigation track covers the beams' times.
struct NavCoverage {
  std::size_t fixes = 0;
  double first_time_s = 0.0;      ///< first fix's time, seconds (the beams' clock)
  double last_time_s = 0.0;       ///< last fix's time, seconds
  double duration_s = 0.0;        ///< last − first, seconds
  double distance_m = 0.0;        ///< length of the straight segments joining the fixes' NED positions, metres
  std::size_t beams_before = 0;   ///< beams earlier than the first fix
  std::size_t beams_after = 0;    ///< beams later than the last fix
  std::size_t beams_outside = 0;  ///< beams a mapper skips for want of a pose: before, after, or a NaN time
  bool coversBeams() const { return beams_outside == 0; }
};

/// What a log holds (summarizeLog).
struct LogSummary {
  std::string sonar;                   ///< SonarLog::sonar (empty when the file names no sonar)
  std::size_t beams = 0;               ///< beams read
  std::size_t skipped_beams = 0;       ///< SonarLog::skipped_beams
  std::vector<SkipReasonGroup> skip_reasons;  ///< SonarLog::skip_reasons grouped, in order of first appearance
  std::vector<std::string> notes;      ///< SonarLog::notes
  double first_time_s = 0.0;           ///< earliest finite beam time, seconds (0 without beams)
  double last_time_s = 0.0;            ///< latest finite beam time, seconds
  double duration_s = 0.0;             ///< last − first, seconds
  /// Beams per second, (beams − 1) / duration_s; unset when the duration is 0 (one beam, or a raw
  /// capture without a clock, whose beams are all at 0 s).
  std::optional<double> beam_rate_hz;

  std::vector<SweepSummary> sweeps;    ///< splitSweeps(log.beams), in order
  std::size_t full_turns = 0;          ///< sweeps of kind kFullTurn
  std::size_t sector_passes = 0;       ///< sweeps of kind kSectorPass
  std::size_t partial_turns = 0;       ///< sweeps of kind kPartialTurn
  std::size_t beams_per_turn = 0;      ///< median beams of a full turn (0: no full turn)
  /// Median time of a full turn, seconds: a turn's last − first beam time × beams / (beams − 1)
  /// (the time until the next turn's first beam); unset without a full turn or a clock.
  std::optional<double> full_turn_s;
  /// The bearings of the sector passes that run from one reversal to the next (the sector the head
  /// sweeps), or of every sector pass when none does; span 0 without sector passes.
  BearingArc sector_arc;

  BearingArc bearings;                 ///< the bearings of all beams
  double step_deg = 0.0;               ///< median |bearing step| between consecutive beams that moved, degrees

  std::vector<HeadSettingUse> settings;  ///< each head setting, in order of first use
  std::vector<RangeScale> range_scales;  ///< rangeScales(log): the distinct bin lengths, in order of first use
  /// The range scale the automatic resolution follows (mostUsedRangeScale); unset without beams.
  std::optional<RangeScale> followed_scale;

  std::optional<NavCoverage> nav;      ///< set when a navigation track was given
};

/// Summarizes `log`: see LogSummary's fields. Sweeps are splitSweeps(log.beams), each classified
/// (SweepKind): a full turn when its accumulated |bearing step| (bearingStep_rad) plus one step
/// reaches 2π less half a step (the step: the sweep's median non-zero |step|); otherwise a sector
/// pass when the head reverses at its end or at its start (the step into the next sweep, or from
/// the previous one, has the same head setting and turns against that sweep's direction), else a
/// partial turn. A bearing arc is a full circle when no two neighbouring bearings (sorted around
/// the circle) are more than 1.5 median steps apart. Beams with a non-finite time are left out of
/// the times and durations (and counted outside the navigation).
///
/// Cost: O(beams · log beams) (sorting bearings) plus O(skip reasons · groups) plus O(fixes).
///
/// @param log  beams in recording order, as a reader returns them; may be empty (every count 0,
///             no sweeps, no settings, followed_scale unset).
/// @param nav  navigation fixes as readNavCsv returns them (times strictly increasing; not checked
///             here); empty: no navigation given, LogSummary::nav unset.
/// @return     the summary. Throws nothing but std::bad_alloc.
LogSummary summarizeLog(const SonarLog& log, const NavTrack& nav = {});

}  // namespace sonarmap
