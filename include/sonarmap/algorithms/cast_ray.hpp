#pragma once
/// @file cast_ray.hpp
/// Ray queries on an occupancy octree: the first occupied voxel along a direction (OctoMap 1.9's
/// `OccupancyOcTreeBase::castRay`), walked with a 3D DDA (Amanatides & Woo 1987).

#include <optional>

#include <Eigen/Core>

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// Follows the ray from `origin_m` along `direction` voxel by voxel and returns the centre of the
/// first occupied voxel, the origin's own voxel included.
///
/// @param map             the octree queried (classes by its thresholds; pruned leaves count for
///                        every voxel they cover)
/// @param origin_m        start of the ray, map frame, metres
/// @param direction       direction of the ray, map frame; any non-zero length (normalised here).
///                        A DIRECTION, not an end point: pass `end_m - origin_m` for a segment.
/// @param max_range_m     > 0: give up once a voxel centre is farther than this from the origin;
///                        ≤ 0: no limit (the walk ends at the map's border). Metres.
/// @param ignore_unknown  false (OctoMap's default): stop with no result at the first unknown
///                        voxel; true: walk through unknown space as if free.
/// @return the centre (map frame, metres) of the first occupied voxel; nullopt when the ray
///         reaches unknown space (unless ignored), the range limit, or the map's border first.
/// @throws ValueError when `direction` is zero or not finite, or `max_range_m` is NaN.
/// @throws OutOfMapError when `origin_m` is outside the map or not finite (OctoMap returns false).
std::optional<Eigen::Vector3d> castRay(const OcTree16& map, const Eigen::Vector3d& origin_m,
                                       const Eigen::Vector3d& direction, double max_range_m = -1.0,
                                       bool ignore_unknown = false);

}  // namespace sonarmap
