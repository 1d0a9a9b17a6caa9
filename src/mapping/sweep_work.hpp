#pragma once
/// @file sweep_work.hpp
/// The sweep's plan and cells that SonarMapper keeps from sweep to sweep (private to src/mapping:
/// sonar_mapper.cpp integrates them, sweep_plan.cpp plans them).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "sonarmap/mapping/level_surfaces.hpp"
#include "sonarmap/mapping/seabed_slope.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "../algorithms/key_marks.hpp"

namespace sonarmap {

struct SonarMapper::SweepWork {
  std::vector<PlannedBeam> beams;                     ///< the sweep's beams inside the map
  std::vector<FreeRay> rays;                          ///< free-space rays, in grid-angle order
  std::vector<HitPoint> hit_points;
  /// Hit cells: mortonCode(key) << 16 | the largest weight among the cell's arc points, in
  /// 1/65535. keySweep gathers one per arc point, then sorts them (tree order) and keeps one per cell.
  std::vector<std::uint64_t> hits;
  std::vector<std::uint64_t> sort_scratch;            ///< radixSortHighBits' working memory
  /// Log-odds of a hit of each weight code (hits' low 16 bits), NaN until first needed.
  std::vector<float> hit_log_odds;
  Key16 box_lo{}, box_hi{};                           ///< keys the sweep's rays stay within
  double tolerance_m = 0.0;                           ///< the sweep's range tolerance
  KeyMarks<16> crossed;  ///< cells the sweep's free rays cross, each once
  KeyMarks<16> outer;    ///< cells only the outer rays of the cones cross (the volume model)
  std::vector<KeyMarks<16>> parts;  ///< with several threads: the other threads' marks
  /// The volume model: every cell that ever received a hit (a superset of the map's occupied
  /// cells), so a sweep can protect them from the outer part of its cones.
  std::vector<std::uint64_t> occupied_keys;  ///< mortonCode() of each, sorted, unique
  std::vector<std::uint64_t> merged_keys;    ///< integrateHits: scratch for the union
  SeabedSlope seabed;
  /// The volume model: the looks of every beam so far at the fitted seabed and at the water surface
  /// (level_surfaces.hpp), created at the first sweep (they need its bins per cell).
  std::optional<LevelSurfaceEvidence> seabed_looks, surface_looks;
  /// The latest sweep's weak seabed onsets: their centroid (map frame) and the radius their plane
  /// is fitted over (placeSeabedTraces); the seabed's looks go to that plane.
  std::optional<std::pair<Eigen::Vector3d, double>> seabed_onsets_m;  ///< the volume model: the onsets of every seabed trace so far (placeSeabedTraces)
  /// The sweep's loud traces (PlannedBeam::loud_trace): their index in `beams`, and each as the
  /// obstacle it was detected as, which it becomes again where the seabed lies well below its
  /// trace (checkLoudTraces).
  std::vector<std::pair<std::size_t, PlannedBeam>> loud_obstacles;
  std::vector<PlannedBeam> group;    ///< planBeams: the beams of one group of nearby poses
  std::vector<FreeRay> group_rays;   ///< planBeams: that group's rays
};

}  // namespace sonarmap
