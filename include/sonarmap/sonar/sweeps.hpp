#pragma once
/// @file sweeps.hpp
/// Splitting a beam log into sweeps (paper §2.1: "a scan has beams that span 360° around the AUV").

#include <cstddef>
#include <vector>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

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
///   - sector scan (SeaNet, issue 4): the direction of rotation reverses (the step's sign differs
///     from the sweep's direction); the beam at the turning point ends the old sweep;
///   - the bin length changes (a range change), so each sweep can become one PolarImage.
/// Zero steps (repeated bearings) neither set nor reverse the direction. Bearing jitter that
/// looks like a reversal would split a sweep; the MSIS logs we know step cleanly.
///
/// On the CRAS log (5,603 valid beams, 1.8° steps, first bearing 0) this gives 28 full sweeps of
/// 200 beams and a last partial sweep of 3 beams.
///
/// @param beams  beams in recording order; bearings in radians (any value; differences are wrapped).
/// @return       sweeps covering all beams in order, without gaps; empty when `beams` is empty.
std::vector<SweepRange> splitSweeps(const std::vector<Beam>& beams);

}  // namespace sonarmap
