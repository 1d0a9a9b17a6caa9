/// @file bench_octomap.cpp
/// The same map work through OctoMap (the reference; linked by the benchmarks only).
///
/// Detections come from the sonarmap pipeline (preprocess + detect), computed once outside the
/// timed loop. Per sweep, inside the timed loop, the beams are planned by the mapper's own planner
/// (planSweep, sonarmap/mapping/sweep_fan.hpp) and OctoMap receives what the mapper casts:
///   - the hit points (each obstacle's arc across the 3° beam width, on the planner's angle grid,
///     at most one voxel apart) as one octomap::Pointcloud, inserted with
///     insertPointCloud(cloud, origin, -1, lazy_eval = true): free from the sonar to every point,
///     occupied at the point, each cell updated once per scan, occupied winning over free;
///   - the wedges of beams without an obstacle (none on the CRAS log), planned alone: their ray
///     keys and end keys from the sonar, each updated free once (computeRayKeys + updateNode).
/// updateInnerOccupancy() closes every sweep, as the lazy sonarmap mapper does. Compare with
/// BM_CrasStages/integrate_* (same detections, same planner, sonarmap's octree).
///
/// What differs, by design of each library: OctoMap casts a ray from the sonar to every hit point
/// (the mapper casts the union of the wedges once, finer rays starting where coarser ones drift a
/// voxel apart); OctoMap gives every hit its fixed log-odds (the mapper scales it by the echo
/// intensity). The map is one voxel thick, so nothing prunes in either library.

#include <cmath>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <octomap/octomap.h>

#include "bench_data.hpp"
#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"

namespace sonarmap::bench {
namespace {

/// Buffers reused from sweep to sweep.
struct SweepBuffers {
  std::vector<PlannedBeam> beams, free_beams;
  std::vector<FreeRay> rays;
  std::vector<HitPoint> hits;
  octomap::Pointcloud cloud;
  octomap::KeySet free_keys;
  octomap::KeyRay ray;
};

octomap::point3d toOctomap(const Eigen::Vector3d& point_m) {
  return {static_cast<float>(point_m.x()), static_cast<float>(point_m.y()), static_cast<float>(point_m.z())};
}

/// Inserts one sweep into `tree`. @return the number of rays OctoMap cast.
std::size_t insertSweep(octomap::OcTree& tree, const PolarImage& polar, const std::vector<BeamDetection>& detections,
                        const MapperOptions& options, SweepBuffers& buffers) {
  const octomap::point3d origin(0.0F, 0.0F, 0.0F);
  sweepBeams(polar, detections, buffers.beams);
  planSweep(buffers.beams, options.beam_width_rad, *options.resolution_m, 0.0, buffers.rays, buffers.hits);
  buffers.cloud.clear();
  for (const HitPoint& hit : buffers.hits) buffers.cloud.push_back(toOctomap(hit.point_m));
  tree.insertPointCloud(buffers.cloud, origin, -1.0, /*lazy_eval=*/true);
  std::size_t rays = buffers.hits.size();

  buffers.free_beams.clear();
  for (const PlannedBeam& beam : buffers.beams) {
    if (!beam.hit) buffers.free_beams.push_back(beam);
  }
  if (!buffers.free_beams.empty()) {
    planSweep(buffers.free_beams, options.beam_width_rad, *options.resolution_m, 0.0, buffers.rays, buffers.hits);
    buffers.free_keys.clear();
    for (const FreeRay& ray : buffers.rays) {
      const octomap::point3d end = toOctomap(ray.end_m);
      if (tree.computeRayKeys(origin, end, buffers.ray)) {
        buffers.free_keys.insert(buffers.ray.begin(), buffers.ray.end());
      }
      octomap::OcTreeKey end_key;
      if (tree.coordToKeyChecked(end, end_key)) buffers.free_keys.insert(end_key);
    }
    for (const octomap::OcTreeKey& key : buffers.free_keys) tree.updateNode(key, false, /*lazy_eval=*/true);
    rays += buffers.rays.size();
  }
  tree.updateInnerOccupancy();
  return rays;
}

/// Voxels of the z = 0 slice known to each map, and the agreement of the occupied/free class on
/// the voxels known to both.
struct SliceAgreement {
  std::size_t sonarmap_known = 0, octomap_known = 0, both = 0, agree = 0;
  std::size_t sonarmap_occupied = 0, octomap_occupied = 0;  ///< among the voxels known to both
};

SliceAgreement compareSliceZ0(const OcTree16& map, const octomap::OcTree& tree) {
  SliceAgreement result;
  const double z_m = map.coder().centerOf(map.coder().keyOfChecked({0.0, 0.0, 0.0})[2]);
  for (const Occupancy occupancy : {Occupancy::kOccupied, Occupancy::kFree}) {
    const bool occupied = occupancy == Occupancy::kOccupied;
    for (const Eigen::Vector2d& cell : cellsInSlice(map, 0.0, occupancy)) {
      ++result.sonarmap_known;
      const octomap::OcTreeNode* node = tree.search(cell.x(), cell.y(), z_m);
      if (node == nullptr) continue;
      ++result.both;
      const bool octomap_occupied = tree.isNodeOccupied(node);
      result.sonarmap_occupied += occupied ? 1 : 0;
      result.octomap_occupied += octomap_occupied ? 1 : 0;
      result.agree += octomap_occupied == occupied ? 1 : 0;
    }
  }
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const double half_m = it.getSize() / 2.0;
    if (z_m < it.getZ() - half_m || z_m >= it.getZ() + half_m) continue;
    const double edge = it.getSize() / tree.getResolution();
    result.octomap_known += static_cast<std::size_t>(std::lround(edge * edge));
  }
  return result;
}

void octomapSameRays(benchmark::State& state, Source source, Variant variant) {
  const SonarLog* log = logOrSkip(state, source);
  if (log == nullptr) return;
  const MapperOptions options = mapperOptions(variant);
  const PreparedSweeps prepared = prepareSweeps(*log, options);

  std::unique_ptr<octomap::OcTree> last;
  SweepBuffers buffers;
  std::size_t rays = 0;
  for (auto _ : state) {
    auto tree = std::make_unique<octomap::OcTree>(*options.resolution_m);
    rays = 0;
    for (std::size_t i = 0; i < prepared.polar.size(); ++i) {
      rays += insertSweep(*tree, prepared.polar[i], prepared.detections[i], options, buffers);
    }
    benchmark::DoNotOptimize(tree.get());
    state.PauseTiming();
    last = std::move(tree);  // frees the previous iteration's tree, untimed
    state.ResumeTiming();
  }

  setMapCounters(state, prepared.polar.size(), prepared.beams, last->size(), last->getNumLeafNodes(),
                 last->memoryUsage());
  state.counters["rays"] = benchmark::Counter(static_cast<double>(rays));

  // The sonarmap map of the same detections, for the agreement at z = 0 (not timed).
  SonarMapper mapper(options);
  for (std::size_t i = 0; i < prepared.polar.size(); ++i) {
    mapper.integrateSweep(prepared.polar[i], prepared.detections[i]);
  }
  const SliceAgreement slice = compareSliceZ0(mapper.map(), *last);
  using benchmark::Counter;
  state.counters["z0_known_sonarmap"] = Counter(static_cast<double>(slice.sonarmap_known));
  state.counters["z0_known_octomap"] = Counter(static_cast<double>(slice.octomap_known));
  state.counters["z0_known_both"] = Counter(static_cast<double>(slice.both));
  state.counters["z0_occ_sonarmap"] = Counter(static_cast<double>(slice.sonarmap_occupied));
  state.counters["z0_occ_octomap"] = Counter(static_cast<double>(slice.octomap_occupied));
  state.counters["z0_agree"] =
      Counter(slice.both == 0 ? 0.0 : static_cast<double>(slice.agree) / static_cast<double>(slice.both));
}

void BM_OctoMapSameRays(benchmark::State& state, Source source, Variant variant) {
  octomapSameRays(state, source, variant);
}

BENCHMARK_CAPTURE(BM_OctoMapSameRays, dda_fan3deg, Source::kCras, Variant::kDefault)->Apply(configure);
BENCHMARK_CAPTURE(BM_OctoMapSameRays, single_ray, Source::kCras, Variant::kSingleRay)->Apply(configure);
BENCHMARK_CAPTURE(BM_OctoMapSameRays, synthetic_fan3deg, Source::kSynthetic, Variant::kDefault)->Apply(configure);

}  // namespace
}  // namespace sonarmap::bench
