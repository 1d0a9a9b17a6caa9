// Point-cloud and ray insertion with OctoMap's semantics: trace, deduplicate, then update each
// voxel once in memory order (see point_cloud_insertion.hpp).
#include "sonarmap/algorithms/point_cloud_insertion.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "key_marks.hpp"
#include "on_threads.hpp"
#include "sonarmap/raycast/dda.hpp"

namespace sonarmap {
namespace {

using Marks = KeyMarks<16>;

/// One ray of a scan that passed the checks.
struct ScanRay {
  Eigen::Vector3d end_m;  ///< where the ray ends: the point, or the point clipped to the range limit
  bool hit;               ///< the end voxel is occupied (false for a ray clipped at the range limit)
};

/// A scan's rays with the keys they touch. When every point of the cloud is a ray that hits (none
/// dropped, none clipped at the range limit: the usual case), the rays are the cloud's own points
/// (`hit_points`), not a copy: 32 bytes a point less at the insertion's peak.
struct PreparedScan {
  const PointCloud* hit_points = nullptr;  ///< the rays' ends, every ray a hit; or nullptr: `rays`
  std::vector<ScanRay> rays;
  std::vector<Key16> hits;  ///< end keys of the rays that hit
  Key16 lo{}, hi{};         ///< box of every key the rays visit (DDA keys stay in the end keys' box)

  std::size_t size() const { return hit_points ? hit_points->size() : rays.size(); }
  ScanRay ray(std::size_t i) const { return hit_points ? ScanRay{(*hit_points)[i], true} : rays[i]; }
};

void checkRange(double max_range_m) {
  if (std::isnan(max_range_m)) throw ValueError("max range must be a number of metres (< 0: none), got NaN");
}


/// OctoMap's computeDiscreteUpdate: the centre of each distinct end-point voxel. Non-finite points
/// and points outside the map are counted and dropped (OctoMap would wrap their keys).
PointCloud discretized(const KeyCoder<16>& coder, const PointCloud& points, InsertStats& stats) {
  std::vector<Key16> keys;
  keys.reserve(points.size());
  for (const Eigen::Vector3d& point : points) {
    if (!point.allFinite()) {
      ++stats.skipped_nonfinite;
    } else if (const auto key = coder.keyOf(point)) {
      keys.push_back(*key);
    } else {
      ++stats.out_of_map;
    }
  }
  std::sort(keys.begin(), keys.end(), Marks::visitLess);
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  PointCloud centres;
  centres.reserve(keys.size());
  for (const Key16& key : keys) centres.push_back(coder.centerOf(key));
  return centres;
}

/// Where the ray to `point_m` ends, and whether it hits: clipped at `max_range_m` (when ≥ 0) like
/// OctoMap's computeUpdate.
ScanRay clipRay(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& point_m, double max_range_m) {
  const Eigen::Vector3d ray = point_m - origin_m;
  double range_m = ray.norm();
  if (!std::isfinite(range_m)) range_m = ray.stableNorm();  // huge but finite coordinates
  if (max_range_m < 0.0 || range_m <= max_range_m) return {point_m, true};
  return {origin_m + ray * (max_range_m / range_m), false};
}

PreparedScan prepareScan(const KeyCoder<16>& coder, const PointCloud& points, const Eigen::Vector3d& origin_m,
                         const Key16& origin_key, double max_range_m, InsertStats& stats) {
  PreparedScan scan;
  scan.lo = scan.hi = origin_key;
  scan.hit_points = &points;  // until a point is dropped or clipped
  scan.hits.reserve(points.size());
  const auto own_rays = [&](std::size_t kept) {  // the points so far were all kept as hits
    scan.rays.reserve(points.size());
    for (std::size_t i = 0; i < kept; ++i) scan.rays.push_back({points[i], true});
    scan.hit_points = nullptr;
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool finite = points[i].allFinite();
    const ScanRay ray = finite ? clipRay(origin_m, points[i], max_range_m) : ScanRay{points[i], false};
    const std::optional<Key16> end_key = finite ? coder.keyOf(ray.end_m) : std::nullopt;
    if (scan.hit_points && !(end_key && ray.hit)) own_rays(i);  // this ray is not the point as a hit
    if (!end_key) {
      ++(finite ? stats.out_of_map : stats.skipped_nonfinite);
      continue;
    }
    growKeyBox(scan.lo, scan.hi, *end_key);
    if (!scan.hit_points) scan.rays.push_back(ray);
    if (ray.hit) scan.hits.push_back(*end_key);
  }
  stats.rays = scan.size();
  return scan;
}

/// Marks every voxel the rays [first, last) cross, except each ray's end voxel (computeRayKeys).
/// A hit ray marks its end voxel too: every hit voxel is erased from the set afterwards anyway
/// (occupied wins), so only rays clipped at the range limit need to stop one voxel short.
void traceRays(const KeyCoder<16>& coder, const Eigen::Vector3d& origin_m, const PreparedScan& scan,
               std::size_t first, std::size_t last, Marks& marks) {
  marks.marking([&](auto mark) {
    for (std::size_t i = first; i != last; ++i) {
      const ScanRay ray = scan.ray(i);
      if (ray.hit) {
        traverseDDASteps(coder, origin_m, ray.end_m, mark);
        continue;
      }
      bool started = false;
      Key16 previous{};
      traverseDDA(coder, origin_m, ray.end_m, [&](const Key16& key) {
        if (started) mark(previous);  // one key behind: the end voxel is never marked
        previous = key;
        started = true;
      });
    }
  });
}

/// The crossed cells of all rays, traced by `threads` threads into their own sets, merged.
void traceScan(const KeyCoder<16>& coder, const Eigen::Vector3d& origin_m, const PreparedScan& scan,
               unsigned threads, Marks& crossed) {
  crossed.reset(scan.lo, scan.hi);
  const std::size_t n = scan.size();
  threads = static_cast<unsigned>(std::clamp<std::size_t>(n / 256, 1, threads));  // ≥ 256 rays per thread
  if (threads <= 1) {
    traceRays(coder, origin_m, scan, 0, n, crossed);
    return;
  }
  std::vector<Marks> parts(threads - 1);
  for (Marks& part : parts) part.reset(scan.lo, scan.hi);
  runOnThreads(threads, [&](unsigned t) {
    traceRays(coder, origin_m, scan, n * t / threads, n * (t + 1) / threads, t == 0 ? crossed : parts[t - 1]);
  });
  for (const Marks& part : parts) crossed.merge(part);
}

/// `owned`, when not null, is `points_world_m` given up by the caller: freed once the rays are
/// traced, before the tree grows, so the points and the new nodes are not resident together.
InsertStats insertCloud(OcTree16& map, const PointCloud& points_world_m, const Eigen::Vector3d& sensor_origin_m,
                        const InsertOptions& options, unsigned threads, PointCloud* owned = nullptr) {
  checkRange(options.max_range_m);
  const KeyCoder<16>& coder = map.coder();
  const Key16 origin_key = coder.keyOfChecked(sensor_origin_m);  // throws OutOfMapError
  if (threads == 0) threads = std::max(1U, std::thread::hardware_concurrency());

  InsertStats stats;
  stats.points = points_world_m.size();
  std::optional<PointCloud> centres;
  if (options.discretize) centres = discretized(coder, points_world_m, stats);
  PreparedScan scan = prepareScan(coder, centres ? *centres : points_world_m, sensor_origin_m, origin_key,
                                  options.max_range_m, stats);
  Marks crossed;
  traceScan(coder, sensor_origin_m, scan, threads, crossed);
  // The rays are traced: what held them goes before the tree grows (vectors this size are their
  // own mappings, so freeing them lowers the peak resident set).
  std::vector<ScanRay>().swap(scan.rays);
  scan.hit_points = nullptr;
  centres.reset();
  if (owned != nullptr) PointCloud().swap(*owned);

  // Occupied wins over free (OctoMap's disjoint sets); then misses, then hits, each voxel once,
  // brick by brick. Leaves first and inner nodes once at the end: the same tree as eager updates
  // (each voxel is updated once, and pruning is canonical), without re-aggregating ancestors
  // after every update.
  Marks hits;
  hits.reset(scan.lo, scan.hi);
  for (const Key16& key : scan.hits) hits.insert(key);
  const std::size_t hit_keys = scan.hits.size();
  std::vector<Key16>().swap(scan.hits);
  const std::size_t free_voxels = crossed.subtract(hits);
  stats.key_set_bytes = crossed.memoryBytes() + hits.memoryBytes();
  map.reserve(free_voxels + hit_keys);  // one allocation instead of growth and copies
  const LogOddsModel& model = map.model();
  const auto update = [&map](float delta, std::size_t& count) {
    return [&map, delta, &count](const Key16& corner, std::uint64_t voxels) {
      map.updateBrick(corner, voxels, delta);
      count += static_cast<std::size_t>(std::popcount(voxels));
    };
  };
  crossed.forEachBrick(update(model.miss, stats.free_updates));
  hits.forEachBrick(update(model.hit, stats.occupied_updates));
  if (!options.lazy_eval && !map.options().lazy) map.updateDirtyInnerOccupancy();
  return stats;
}

}  // namespace

InsertStats insertPointCloud(OcTree16& map, const PointCloud& points_world_m, const Eigen::Vector3d& sensor_origin_m,
                             const InsertOptions& options) {
  return insertCloud(map, points_world_m, sensor_origin_m, options, 1);
}

InsertStats insertPointCloudParallel(OcTree16& map, const PointCloud& points_world_m,
                                     const Eigen::Vector3d& sensor_origin_m, const InsertOptions& options,
                                     unsigned threads) {
  return insertCloud(map, points_world_m, sensor_origin_m, options, threads);
}

InsertStats insertPointCloudParallel(OcTree16& map, PointCloud&& points_world_m, const Eigen::Vector3d& sensor_origin_m,
                                     const InsertOptions& options, unsigned threads) {
  PointCloud points = std::move(points_world_m);
  return insertCloud(map, points, sensor_origin_m, options, threads, &points);
}

InsertStats insertScan(OcTree16& map, const Scan& scan, const InsertOptions& options) {
  PointCloud world;
  world.reserve(scan.points_m.size());
  for (const Eigen::Vector3d& point : scan.points_m) world.push_back(scan.sensor_to_world * point);
  return insertPointCloud(map, world, scan.sensor_to_world.translation(), options);
}

bool insertRay(OcTree16& map, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m, double max_range_m,
               bool lazy_eval) {
  checkRange(max_range_m);
  const KeyCoder<16>& coder = map.coder();
  if (!coder.keyOf(origin_m) || !end_m.allFinite()) return false;
  const ScanRay ray = clipRay(origin_m, end_m, max_range_m > 0.0 ? max_range_m : -1.0);
  const auto end_key = coder.keyOf(ray.end_m);
  if (!end_key) return false;
  const float miss = map.model().miss;
  bool started = false;
  Key16 previous{};
  traverseDDA(coder, origin_m, ray.end_m, [&](const Key16& key) {
    if (started) map.updateNode(previous, miss, lazy_eval);  // every crossed voxel but the end's
    previous = key;
    started = true;
  });
  if (ray.hit) map.updateNode(*end_key, map.model().hit, lazy_eval);
  return true;
}

}  // namespace sonarmap
