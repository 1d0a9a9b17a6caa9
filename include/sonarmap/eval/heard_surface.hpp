#pragma once
/// @file heard_surface.hpp
/// An oracle for the 3D accuracy missions (simulated_mission.hpp): the surface a mission's beams
/// could hear, as a map. Scored like a mapped log (evaluateAgainstScene with missionTruthOptions),
/// its recall bounds what any map of that log can reach with a detector that needs a surface's
/// mean echo that far above the receiver's floor (sim/echo_levels.hpp), and its precision is 1 up
/// to the voxel grid: every occupied voxel holds a surface point. F1 ≤ 2R / (1 + R) follows for
/// any map whose recall is bounded by R (issue 21: how far the 3D targets can be reached).
///
/// Method: for every beam of the mission's log, from the head's true pose at the beam's time, a
/// grid of rays spans the echo model's whole ray extent (EchoModelOptions::horizontal and
/// vertical: extent × the beam widths), at most one voxel apart at the head's range. A ray's first
/// surface within the range is kept when that primitive's echo in the bin of the ray's range is at
/// least `min_level_db` over the floor (EchoLevels::levels); its voxel is marked occupied once.
/// The grid is finer than the echo model's own rays, so a surface the model lights between its
/// rays is found too; the levels are the model's.

#include <cstddef>
#include <limits>

#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// Options of heardSurfaceMap().
struct HeardSurfaceOptions {
  double resolution_m = 0.05;  ///< the map's voxel edge, metres, > 0
  /// A surface point is kept where its primitive's echo in the point's bin is at least this many
  /// dB over the floor; −infinity keeps every surface point a ray meets (the geometry alone).
  double min_level_db = 0.0;

  /// @throws ValueError when resolution_m is not a finite number > 0 or min_level_db is NaN or +∞.
  void validate() const;
};

/// What heardSurfaceMap() found besides the map.
struct HeardSurfaceStats {
  std::size_t beams = 0;        ///< beams of the log traced
  std::size_t rays = 0;         ///< rays cast in all
  std::size_t surface_hits = 0; ///< rays that met a surface within the range
  std::size_t heard_hits = 0;   ///< of those, at least min_level_db over the floor
};

/// The heard surface of `run` (see the file's comment) as an octree at options.resolution_m whose
/// occupied voxels are the heard points' voxels (one hit each) and which holds nothing else.
/// `stats`, when given, receives the counts.
/// @throws ValueError for invalid options, or when no point is heard (an empty map cannot be scored).
OcTree16 heardSurfaceMap(const MissionRun& run, const HeardSurfaceOptions& options,
                         HeardSurfaceStats* stats = nullptr);

}  // namespace sonarmap
