#pragma once
/// @file point_cloud_insertion.hpp
/// Integrating range measurements into an occupancy octree: whole point clouds (one scan) and
/// single rays, with OctoMap's semantics (Hornung et al. 2013; OctoMap 1.9
/// `OccupancyOcTreeBase::insertPointCloud`, `computeUpdate`, `computeDiscreteUpdate`,
/// `insertRay`; `../shared/docs/formats.md`).
///
/// A scan updates each voxel at most once: the voxels its rays cross are misses, the voxels its
/// end points fall in are hits, and a voxel that is both is only a hit. Rays are traversed with the
/// 3D DDA of raycast/dda.hpp (Amanatides & Woo 1987), without the end voxel, as OctoMap's
/// `computeRayKeys`. Where OctoMap's float DDA stops a voxel short of the end, ours reaches it, so
/// the two maps agree on all but a few boundary voxels (tests/algorithms: ≥ 99.9 % of the volume).
///
/// Speed: the scan's crossed cells are marked in a bitmap over the box of keys the scan spans (a
/// hash set when the box exceeds 2^27 voxels), its end cells in a second one, and the hits removed
/// from the crossed set word by word. Each set is then applied brick by brick — the 4 × 4 × 4
/// voxels of one node two levels above the finest (OccupancyOctree::updateBrick): a brick in
/// unknown space is built at once with its children arrays at their final size, a known one is
/// merged in place. Leaves are updated first and the inner nodes above them fixed once at the end
/// (the same tree as eager updates). See docs/performance.md, "Point-cloud workloads".

#include <algorithm>
#include <cstddef>

#include <Eigen/Core>

#include "sonarmap/core/point_cloud.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// How a point cloud is integrated. Defaults are OctoMap's.
struct InsertOptions {
  /// Longest ray in metres; < 0: no limit. A point farther than this from the sensor clears free
  /// space up to this distance along its ray and marks no occupied voxel (OctoMap's `maxrange`).
  double max_range_m = -1.0;
  /// Reduce the cloud to one point per end-point voxel, the voxel's centre, before casting
  /// (OctoMap's `discretize`, `computeDiscreteUpdate`): fewer rays for dense clouds; rays then end
  /// at voxel centres and the range limit is measured to the centre.
  bool discretize = false;
  /// Update leaves only; the caller calls `updateInnerOccupancy()` (or
  /// `updateDirtyInnerOccupancy()`) before querying inner nodes (OctoMap's `lazy_eval`). A tree
  /// built with `OctreeOptions::lazy` is lazy anyway.
  bool lazy_eval = false;
};

/// What one insertion did.
struct InsertStats {
  std::size_t points = 0;             ///< points given (before discretisation)
  std::size_t skipped_nonfinite = 0;  ///< points with a NaN or infinite coordinate, ignored
  std::size_t out_of_map = 0;         ///< rays whose (clipped) end lies outside the map, ignored
  std::size_t rays = 0;               ///< rays cast (after discretisation and the checks above)
  std::size_t free_updates = 0;       ///< voxels updated as misses (each once)
  std::size_t occupied_updates = 0;   ///< voxels updated as hits (each once)
  /// Bytes the insertion's per-scan key sets held (the crossed and the hit voxels: a bitmap of one
  /// bit per voxel of the key box spanned by the origin and the end keys, or a hash set when that
  /// box is over 2^27 voxels); the largest of one scan's, not a sum, when totalled.
  std::size_t key_set_bytes = 0;

  /// Adds another insertion's counts (totals over several scans).
  InsertStats& operator+=(const InsertStats& other) {
    points += other.points;
    skipped_nonfinite += other.skipped_nonfinite;
    out_of_map += other.out_of_map;
    rays += other.rays;
    free_updates += other.free_updates;
    occupied_updates += other.occupied_updates;
    key_set_bytes = std::max(key_set_bytes, other.key_set_bytes);
    return *this;
  }
};

/// Integrates one scan: free space along each ray from the sensor to each point, the point's
/// voxel occupied (OctoMap's `insertPointCloud(cloud, origin, maxrange, lazy_eval, discretize)`).
///
/// @param map              the octree to update (its sensor model gives the hit/miss log-odds)
/// @param points_world_m   end points of the rays, map (world) frame, metres
/// @param sensor_origin_m  origin of every ray, map frame, metres
/// @param options          range limit, discretisation, lazy evaluation
/// @return counts of points, skipped points, rays and updates.
/// @throws OutOfMapError when the origin is outside the map or not finite.
/// @throws ValueError when `options.max_range_m` is NaN.
/// Non-finite points are skipped and counted; points outside the map are counted, never wrapped.
InsertStats insertPointCloud(OcTree16& map, const PointCloud& points_world_m, const Eigen::Vector3d& sensor_origin_m,
                             const InsertOptions& options = {});

/// insertPointCloud with the rays traced by `threads` threads (0: one per hardware thread), each
/// into its own set of crossed cells; the sets are merged and applied in the same order as the
/// serial version, so the resulting map is identical to insertPointCloud's. Same parameters,
/// results and exceptions; also std::system_error if a thread cannot be started.
InsertStats insertPointCloudParallel(OcTree16& map, const PointCloud& points_world_m,
                                     const Eigen::Vector3d& sensor_origin_m, const InsertOptions& options = {},
                                     unsigned threads = 2);

/// insertPointCloudParallel on points the caller gives up: they are freed as soon as the rays are
/// traced, before the tree grows, so a scan's points and its new nodes are never resident
/// together (the peak resident set of a large scan drops by the points' size, 24 bytes a point).
/// `points_world_m` is left empty, also when an exception is thrown after the move. Same map,
/// results and exceptions as the overload that borrows the points.
InsertStats insertPointCloudParallel(OcTree16& map, PointCloud&& points_world_m, const Eigen::Vector3d& sensor_origin_m,
                                     const InsertOptions& options = {}, unsigned threads = 2);

/// Integrates a scan taken at a pose: its points (sensor frame) are transformed by
/// `scan.sensor_to_world`, the origin is the pose's translation (OctoMap's
/// `insertPointCloud(const ScanNode&, …)`). Same results and exceptions as insertPointCloud.
InsertStats insertScan(OcTree16& map, const Scan& scan, const InsertOptions& options = {});

/// Integrates one ray (OctoMap's `insertRay`): every voxel it crosses from `origin_m` up to but
/// excluding the end voxel is a miss, then the end voxel a hit. When `max_range_m` > 0 and the end
/// is farther than that, free space stops at `max_range_m` along the ray and nothing is marked
/// occupied. Unlike insertPointCloud, voxels are not deduplicated against other rays.
///
/// @param origin_m, end_m  the ray's start and end point, map frame, metres
/// @param max_range_m      range limit in metres; ≤ 0: none (OctoMap's test for insertRay)
/// @param lazy_eval        update leaves only (see InsertOptions::lazy_eval)
/// @return false, changing nothing, when the origin or the (clipped) end is outside the map or
///         not finite; true otherwise.
/// @throws ValueError when `max_range_m` is NaN.
bool insertRay(OcTree16& map, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m, double max_range_m = -1.0,
               bool lazy_eval = false);

}  // namespace sonarmap
