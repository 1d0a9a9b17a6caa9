#pragma once
/// @file simulated_accuracy.hpp
/// One row of the accuracy table of docs/accuracy.md: a simulated sonar head (sonar_presets.hpp)
/// scanning a built-in scene built for its range (builtin_scenes.hpp), mapped with the mapper's
/// default options as `sonarmap map` maps a log, scored against the scene (ground_truth.hpp).

#include <cstddef>
#include <string>
#include <vector>

#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/mapping/mapper_options.hpp"

namespace sonarmap {

/// How the simulated head scans and moves.
struct SimulatedRun {
  std::string preset = "micron";  ///< sonarPresetNames()
  std::string scene = "tank";     ///< builtinSceneNames(), built for the preset's range
  std::size_t turns = 8;          ///< full turns, or passes across the sector
  double sector_deg = 360.0;      ///< 360: continuous; less: a sector centred on the map's +x
  /// Vehicle speed as a share of the head's range per minute: 0 static. A moving vehicle heads
  /// along the map's +y (the scenes' quay face), the middle of its run at the map origin, and its
  /// beams are mapped with the simulated navigation (mapSonarLog with a NavTrack).
  double speed_range_per_min = 0.0;
  std::uint64_t seed = 1;
};

/// The scores of one run (shares in [0, 1]).
struct SimulatedAccuracy {
  SimulatedRun run;
  double resolution_m = 0.0;       ///< the map's (automatic) resolution
  std::size_t sweeps = 0;
  std::size_t obstacles = 0;       ///< beams with an obstacle
  GroundTruthReport truth;         ///< precision, recall, free accuracy, per-surface offsets
  /// The largest |median signed offset| over the surfaces that cross the map's slab with at least
  /// 10 matched voxels, metres (surfaces that do not cross it, such as the tank's floater above the
  /// sonar's plane, are listed in `off_plane` instead).
  double worst_offset_m = 0.0;
  std::vector<SurfaceOffset> off_plane;  ///< matched surfaces that do not cross the slab
  double seconds_mapping = 0.0;    ///< mapSonarLog's wall time
};

/// Simulates `run`, maps it with `options` (defaults: the mapper's) and scores it against the
/// scene with the default GroundTruthOptions (a moving run: its sensor positions sampled every
/// tenth of its duration).
/// @throws ValueError for an unknown preset or scene, invalid options, or a map with no known voxel.
SimulatedAccuracy evaluateSimulatedRun(const SimulatedRun& run, const MapperOptions& options = {});

}  // namespace sonarmap
