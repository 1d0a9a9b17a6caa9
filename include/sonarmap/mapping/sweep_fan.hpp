#pragma once
/// @file sweep_fan.hpp
/// Planning the rays that clear a sweep's free space (the mapper's inverse sensor model).
///
/// A beam of horizontal width w clears the wedge from the sonar to its free range (its obstacle,
/// or its full range). The free space of a sweep is the union of its beams' wedges: at each angle,
/// the longest free range among the beams that cover that angle. The planner samples that union
/// on one hierarchical grid of 2^L angles per turn, fine enough for rays to be at most one voxel
/// apart at the longest range: a grid ray of level k starts only where its two coarser neighbours
/// drift a voxel apart, or where the shorter of them ends — before that they cover its cells.
/// Overlapping beams (3° wide every 1.8°) are thus cast once, not twice, and neighbouring rays are
/// neighbours in memory. With w = 0 every beam is one ray from the sonar (paper §6).

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

namespace sonarmap {

/// One beam to integrate, in the sonar frame and with the sonar's pose at its time.
struct PlannedBeam {
  Eigen::Isometry3d sonar_to_map;
  double bearing_rad;   ///< sonar frame, [0, 2π)
  double free_range_m;  ///< the beam clears its wedge up to here: its obstacle's range minus the range
                        ///< tolerance, or the beam's full range without one
  double hit_range_m;   ///< range of the obstacle's arc (the echo's leading edge); unused without a hit
  bool hit;             ///< the beam ends in an obstacle
};

/// A segment to traverse, map frame. Every cell it crosses is free unless it is a hit cell.
struct FreeRay {
  Eigen::Vector3d start_m;
  Eigen::Vector3d end_m;
};

/// A point of an obstacle's arc, map frame.
struct HitPoint {
  Eigen::Vector3d point_m;
};

/// Plans the free rays of beams that share one pose (or nearly: each ray is placed with its own
/// beam's pose), in grid-angle order; `rays` is cleared first. With width 0 every beam is one ray.
/// Nothing is thrown.
/// @param beam_width_rad horizontal beam width, ≥ 0; @param voxel_m map resolution, > 0.
void planFreeRays(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m,
                  std::vector<FreeRay>& rays);

/// Plans the hit points of a sweep's obstacles, map frame; `hits` is cleared first. The beams may
/// each have their own pose (a moving vehicle). Nothing is thrown.
///
/// An obstacle is the arc at its range across the beam's width, points at most a voxel apart.
/// A point of the arc is dropped where another beam of the sweep, from its own pose, saw water
/// beyond it: the point lies inside that beam's wedge, nearer than the range up to which the beam
/// saw water (its echo's leading edge, or its free range without one) less `tolerance_m`
/// ("somewhere occupied, everywhere empty": Moravec & Elfes 1985, Elfes 1987). At oblique
/// incidence the leading edge comes from the beam's near side, and the neighbours, which see the
/// same wall farther away, carve the rest of the arc away. With width 0 each obstacle is one point.
/// @param beam_width_rad horizontal beam width, ≥ 0; @param voxel_m map resolution, > 0;
/// @param tolerance_m    how much farther than the arc another beam's water must reach, ≥ 0
///                       (the range uncertainty of a leading edge: a bin plus half a voxel).
void planArcs(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m, double tolerance_m,
              std::vector<HitPoint>& hits);

/// planFreeRays and planArcs of beams that share one pose.
void planSweep(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m, double tolerance_m,
               std::vector<FreeRay>& rays, std::vector<HitPoint>& hits);

}  // namespace sonarmap
