#pragma once
/// @file first_returns.hpp
/// How many of a log's first returns a map holds: the recall measure for real logs whose walls
/// are steps into reverberation rather than peaks (docs/accuracy.md, "First returns").
///
/// A beam's first return is where its echo first rises out of the water in front of it and stays
/// up, measured on the beam alone with no detector, background or threshold model of the mapper's:
/// scanning outward from `front_m`, the first bin c whose intensity, the next bin's, and the mean
/// intensity over the `stay_m` from c on all reach `rise_db` above the water in front of c (one loud
/// bin is a speckle spike, not a return that stays up), the 90th percentile
/// of the beam's bins over the `front_m` before c. (The bright near-field band at the start of a
/// beam is in front of everything within `front_m` of it, so it is never a first return itself.)
/// The intensities' dB span is the beam's own, else 45 dB. A return counts as mapped when an
/// occupied voxel's centre lies in the beam's wedge (its bearing ± half the horizontal beam width)
/// within `tolerance_m` of the return's range (at least two voxels), at the beam's height within the
/// same tolerance: the planar map traces the return where the beam met it.

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/octree/occupancy_octree.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Options of firstReturns(), in physical units.
struct FirstReturnOptions {
  double rise_db = 6.0;        ///< rise above the water in front, dB, > 0
  double front_m = 0.5;        ///< the water in front of a bin: this much range before it, metres, > 0 (≥ 8 bins)
  double stay_m = 0.2;         ///< how far the return stays up, metres, > 0 (≥ 2 bins)
  double tolerance_m = 0.1;    ///< match distance in range and height, metres, > 0 (at least two voxels)
  double beam_width_rad = 3.0 * 3.14159265358979323846 / 180.0;  ///< horizontal beam width, radians, in [0, π)
  /// @throws ValueError naming the option when it is outside its range or not finite.
  void validate() const;
};

/// One beam's first return (see the file's comment).
struct FirstReturn {
  std::size_t beam = 0;   ///< index into the log's beams
  double range_m = 0.0;   ///< the return's first bin's start, metres
  bool mapped = false;    ///< an occupied voxel holds it
};

/// The measure over a log.
struct FirstReturnScore {
  std::size_t beams = 0;                 ///< beams placed (with a pose)
  std::vector<FirstReturn> returns;      ///< the placed beams that have a first return, in log order
  std::size_t mapped = 0;                ///< of those, mapped
  double share() const { return returns.empty() ? 0.0 : static_cast<double>(mapped) / static_cast<double>(returns.size()); }
};

/// The first return of each beam of `log` (see the file's comment), without a map: `returns` holds
/// them with mapped = false.
/// @throws ValueError for invalid options.
FirstReturnScore findFirstReturns(const SonarLog& log, const FirstReturnOptions& options = {});

/// The first returns of `log` scored against `map`.
/// @param sonar_to_map  per beam of `log`, the sonar's pose in the map frame, nullopt for a beam not
///                      placed; empty: every beam at the identity (a static sonar at the map's
///                      origin, as mapSonarLog without navigation).
/// @throws ValueError for invalid options, or poses that are neither empty nor one per beam.
FirstReturnScore firstReturns(const OcTree16& map, const SonarLog& log,
                              const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map = {},
                              const FirstReturnOptions& options = {});

}  // namespace sonarmap
