#pragma once
/// @file sweeps.hpp
/// Splitting a beam log into sweeps (paper §2.1: "a scan has beams that span 360° around the AUV").

#include <cstddef>
#include <optional>
#include <vector>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// What a sweep's calibration depends on besides the scene: the head's range scale (its bin length:
/// a range change changes the sample interval, and with it the near field, the noise floor's growth
/// and every threshold in bins) and its receiver gain. Beams of different settings are never
/// calibrated together.
struct HeadSetting {
  double bin_length_m = 0.0;         ///< Beam::bin_length_m
  std::optional<int> gain_setting;   ///< Beam::gain_setting (unset when the format has none)
  bool operator==(const HeadSetting&) const = default;
};

/// The head setting of `beam`.
inline HeadSetting headSettingOf(const Beam& beam) { return HeadSetting{beam.bin_length_m, beam.gain_setting}; }

/// The head's step from bearing `from_rad` to bearing `to_rad`: their difference wrapped to (−π, π],
/// radians; positive clockwise seen from above (the sonar frame's direction of bearing, beam.hpp).
double bearingStep_rad(double from_rad, double to_rad);

/// Beams [first, last_exclusive) of a beam list form one sweep.
struct SweepRange {
  std::size_t first = 0;
  std::size_t last_exclusive = 0;
  std::size_t size() const { return last_exclusive - first; }
  bool operator==(const SweepRange&) const = default;
};

/// Splits consecutive beams into sweeps of the MSIS head.
///
/// The head's step between consecutive beams is the bearing difference wrapped to (−π, π]; its
/// sign is the direction of rotation. A new sweep starts at beam i when
///   - continuous (360°) scan: the head has turned a full turn since the sweep's first beam, i.e.
///     the accumulated |step| reaches 2π (the bearing wraps back to where the sweep began). This
///     is independent of where bearing 0 lies, so it also works when the first beam is not at 0;
///   - sector scan (SeaNet): the direction of rotation reverses (the step's sign differs
///     from the sweep's direction); the beam at the turning point ends the old sweep;
///   - the head setting changes (HeadSetting: the bin length with a range change, or the gain), so
///     each sweep can become one PolarImage and is calibrated on beams of one setting.
/// Zero steps (repeated bearings) neither set nor reverse the direction. Bearing jitter that
/// looks like a reversal would split a sweep; the MSIS logs we know step cleanly.
///
/// On the CRAS log (5,603 valid beams, 1.8° steps, first bearing 0) this gives 28 full sweeps of
/// 200 beams and a last partial sweep of 3 beams.
///
/// @param beams  beams in recording order; bearings in radians (any value; differences are wrapped).
/// @return       sweeps covering all beams in order, without gaps; empty when `beams` is empty.
std::vector<SweepRange> splitSweeps(const std::vector<Beam>& beams);

/// Whether each sweep of splitSweeps(beams) is whole: the head swept every bearing of its scan.
/// A sweep is whole when
///   - it covers a full turn: its accumulated |step| plus one more of its last step reaches 2π
///     (a continuous scan's turn, wherever it began), or
///   - it is a sector pass from one turning point to the other: it began where the head reversed
///     and the head reversed after it (same head setting on both sides).
/// Not whole: a log's first sector pass (begun mid-pass) and its last sweep cut by the end of the
/// recording (the CRAS log's 3 last beams), or a sweep cut by a range or gain change.
/// @param beams   beams in recording order.
/// @param sweeps  splitSweeps(beams).
/// @return        one flag per sweep.
std::vector<bool> wholeSweepFlags(const std::vector<Beam>& beams, const std::vector<SweepRange>& sweeps);

/// The whole sweeps of `beams` (wholeSweepFlags), in order: what a picture of "a sweep" shows.
std::vector<SweepRange> wholeSweeps(const std::vector<Beam>& beams);

/// splitSweeps one beam at a time, for beams arriving from a sonar (OnlineMapper): the same rules,
/// the same sweeps.
class SweepSplitter {
 public:
  /// True when `beam`, the next beam in recording order, starts a new sweep (never the first beam).
  bool startsSweep(const Beam& beam);

 private:
  struct Previous {
    double bearing_rad = 0.0;
    HeadSetting setting;
  };
  std::optional<Previous> previous_;  ///< the last beam seen
  int direction_ = 0;                 ///< +1 clockwise (bearings increase), −1 counter-clockwise, 0 not known yet
  double turned_rad_ = 0.0;           ///< accumulated |step| since the sweep's first beam
};

/// mergeShortSweeps one beam at a time: says when the oldest beams held form a final group, a sweep
/// (or sweeps joined) that no later beam can join. A sweep joins the group before it when either
/// has fewer than `min_beams` beams and both have the same head setting, except that sweeps joined
/// until they hold `min_beams` beams are a group of their own: a group is final once the sweep after
/// it has `min_beams` beams, once it is of two sweeps or more and holds `min_beams` beams when the
/// next sweep begins (a narrow sector's short passes are committed a few at a time, not all at the
/// stream's end), once the head setting changes, or at the end of the stream. A group may
/// therefore hold fewer than `min_beams` beams: a range scale or gain used for fewer beams than
/// that (a user turning the range knob through several scales), or the short last sweep of a
/// stream after such a group.
class SweepGrouper {
 public:
  explicit SweepGrouper(std::size_t min_beams);
  /// The next beam, `starts_sweep` as SweepSplitter said, `setting` its head setting. Returns the
  /// number of beams, oldest first and not counting this one, that now form a final group; 0 when
  /// none.
  std::size_t add(bool starts_sweep, const HeadSetting& setting);
  /// The end of the stream: the size of the last group (0 when no beam is held).
  std::size_t finish();

 private:
  void closeCurrent();
  std::size_t min_beams_;
  std::size_t pending_ = 0;  ///< beams of the group before the current sweep, not yet final
  std::size_t pending_sweeps_ = 0;  ///< sweeps in the pending group
  std::size_t current_ = 0;  ///< beams of the sweep being received
  std::optional<HeadSetting> setting_;  ///< the last beam's
};

/// Joins a sweep of fewer than `min_beams` beams (a log that starts or ends mid-turn) to its
/// neighbour of the same head setting, so the detector's per-sweep background is estimated over
/// enough beams where the log has them. `sweeps` must be contiguous splitSweeps(beams) output; the
/// same groups as SweepGrouper (a setting used for fewer than `min_beams` beams stays short).
std::vector<SweepRange> mergeShortSweeps(const std::vector<Beam>& beams, const std::vector<SweepRange>& sweeps,
                                         std::size_t min_beams);

/// The sweeps the mapper detects one at a time: mergeShortSweeps(beams, splitSweeps(beams), min_beams).
std::vector<SweepRange> groupSweeps(const std::vector<Beam>& beams, std::size_t min_beams);

}  // namespace sonarmap
