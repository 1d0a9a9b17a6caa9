#pragma once
/// @file detection.hpp
/// The result of obstacle detection along a beam (paper §6, §8.2).

#include <cstdint>
#include <limits>
#include <vector>

namespace sonarmap {

/// First obstacle along one beam (one row of a PolarImage).
struct BeamDetection {
  int obstacle_bin = -1;         ///< bin of the first obstacle, −1 when the beam saw none
  std::uint8_t intensity = 0;    ///< intensity at that bin (0…255)
  /// Range of the obstacle's leading edge along the beam, metres, > 0 when there is an obstacle:
  /// the centre of the first bin where the echo comes within BackgroundOptions::leading_edge_db of its
  /// peak (detectors.hpp).
  double range_m = 0.0;
  /// How far the beam is known to travel through water, metres: with an obstacle, its range; without
  /// one, the start of the first bin at or beyond the minimum range whose echo reaches the detection
  /// threshold above the background (an echo too short to be an obstacle still proves nothing beyond
  /// it), the beam's full range when there is none, or 0 when the beam shows nothing at all beyond
  /// the minimum range (its bins may be zeroed). The mapper clears a beam's free space up to here.
  double water_range_m = 0.0;
  /// How far behind the leading edge the echo reaches its peak, metres, ≥ 0: the pulse's length at
  /// normal incidence, the range spread across the beam at oblique incidence — how uncertain the
  /// surface's range is within this echo (the mapper's automatic range tolerance uses it).
  double rise_m = 0.0;
  /// Where the beam's echo first rises above the background at all, metres: the start of the first
  /// stretch of DetectorOptions::onset_length_m whose mean rise reaches onset_db, at or beyond the
  /// minimum range; at most the obstacle's range (or water_range_m without one). Weak extended
  /// returns below the obstacle threshold (a grazing seabed, a soft or grazing wall) start here:
  /// the beam-volume model clears its cone no farther, nor does the planar model a beam without
  /// an obstacle (Elfes 1987: only an empty return proves empty space). +∞ when
  /// not measured (a detection made by hand).
  double echo_onset_m = std::numeric_limits<double>::infinity();
  /// Where the obstacle's echo falls back, metres: the centre of the last bin of the run that starts
  /// at the obstacle's bin and ends where the echo stays below half the sweep's threshold over the
  /// background for DetectorOptions' echo length (BackgroundOptions::min_echo_length_m, at least a
  /// bin): the mirror of the leading edge's foot (detectors.hpp, rule 3), so that a speckle dip
  /// within the echo does not end it. A face's loud echo ends here even where a weak return goes on
  /// behind it (the seabed at a quay's foot, seen by the lower rays of the cone); the beam-volume
  /// model's vertical face reaches no farther (PlannedBeam::hit_end_m). NaN without an obstacle.
  double echo_end_m = std::numeric_limits<double>::quiet_NaN();
  /// An extended return found in the whole echo (extended_returns.hpp): of a beam without an
  /// obstacle, a weak one (a grazing seabed or water surface); of a beam with one, the lit run that
  /// starts with the obstacle's echo. Its first and last lit bins' centres, metres, onset ≤ end;
  /// NaN when the beam has none or the extended returns were not sought.
  double extended_onset_m = std::numeric_limits<double>::quiet_NaN();
  double extended_end_m = std::numeric_limits<double>::quiet_NaN();
  /// Whether the obstacle is a weak return: one no run of bins above the obstacle threshold found
  /// (the background detector's), certain by the summed evidence of its bins alone (the evidence
  /// detector, water_evidence.hpp): a step into reverberation, a soft or oblique face. The planar
  /// model maps it as any obstacle; the beam-volume model detects with the loud echoes alone and
  /// traces weak returns in its cone as extended returns (SonarMapper).
  bool weak = false;
  bool hasExtendedReturn() const { return extended_onset_m <= extended_end_m; }
  bool hasObstacle() const { return obstacle_bin >= 0; }
};

}  // namespace sonarmap
