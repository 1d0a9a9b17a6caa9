/// @file bench_cloud.cpp
/// Point-cloud workloads, each through sonarmap and OctoMap 1.9 in the same run
/// (workloads in bench_cloud_workloads.hpp):
///   BM_CloudSonarmap/<w>        insertPointCloud (insertScan for the graph), serial, fresh map
///   BM_CloudOctoMap/<w>         OcTree::insertPointCloud (ScanNode overload for the graph)
///   BM_CloudDDA/<w>             traverseDDA origin → point for every point, no map (keys folded
///                               into a checksum); points beyond the range clipped as insertion does
///   BM_CloudOctoMapRayKeys/<w>  OcTree::computeRayKeys over the same rays, into a reused KeyRay
///   BM_CloudParallel2/<w>       insertPointCloudParallel with 2 threads, fresh map
/// Both libraries use their defaults (eager inner-node updates, OctoMap's sensor model). Trees
/// are freed outside the timed region. Counters: points; nodes, leaves, bytes of the last
/// iteration's map (sonarmap memoryBytes(), OctoMap memoryUsage()); on the sonarmap rows, the
/// comparison of the two maps, computed once outside the loop: agree (share of the finest voxels
/// known to both whose free/occupied class agrees), known_* (finest voxels, pruned leaves
/// expanded), bytes_ratio (sonarmap / OctoMap); on the parallel rows, identical (1 when the
/// 2-thread map equals the serial map leaf by leaf).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>

#include <benchmark/benchmark.h>
#include <octomap/octomap.h>

#include "bench_cloud_workloads.hpp"
#include "bench_data.hpp"
#include "sonarmap/core/key_coder.hpp"
#include "sonarmap/raycast/dda.hpp"

namespace sonarmap::bench {
namespace {

using benchmark::Counter;

std::uint64_t fold(std::uint64_t sum, std::uint16_t x, std::uint16_t y, std::uint16_t z) {
  return sum + (static_cast<std::uint64_t>(x) | (static_cast<std::uint64_t>(y) << 16) |
                (static_cast<std::uint64_t>(z) << 32));
}

void setTreeCounters(benchmark::State& state, const CloudWorkload& w, std::size_t nodes, std::size_t leaves,
                     std::size_t bytes) {
  state.counters["points"] = Counter(static_cast<double>(w.points));
  state.counters["points/s"] = Counter(static_cast<double>(w.points), Counter::kIsIterationInvariantRate);
  state.counters["nodes"] = Counter(static_cast<double>(nodes));
  state.counters["leaves"] = Counter(static_cast<double>(leaves));
  state.counters["bytes"] = Counter(static_cast<double>(bytes), Counter::kDefaults, Counter::kIs1024);
}

void BM_CloudSonarmap(benchmark::State& state, CloudId id) {
  const CloudWorkload* w = cloudOrSkip(state, id);
  if (w == nullptr) return;
  std::unique_ptr<OcTree16> last;
  for (auto _ : state) {
    auto map = std::make_unique<OcTree16>(w->resolution_m);
    insertSonarmap(*map, *w);
    benchmark::DoNotOptimize(map.get());
    state.PauseTiming();
    last = std::move(map);  // frees the previous iteration's map, untimed
    state.ResumeTiming();
  }
  const NodeCounts counts = last->counts();
  setTreeCounters(state, *w, counts.nodes, counts.leaves, last->memoryBytes());
  const CloudComparison& c = cloudComparison(id, *w);
  state.counters["agree"] = Counter(c.known_both == 0 ? 0.0 : static_cast<double>(c.agree) / c.known_both);
  state.counters["known_both"] = Counter(static_cast<double>(c.known_both));
  state.counters["known_sonarmap"] = Counter(static_cast<double>(c.known_sonarmap));
  state.counters["known_octomap"] = Counter(static_cast<double>(c.known_octomap));
  state.counters["bytes_ratio"] = Counter(static_cast<double>(c.sonarmap_bytes) / c.octomap_bytes);
}

void BM_CloudOctoMap(benchmark::State& state, CloudId id) {
  const CloudWorkload* w = cloudOrSkip(state, id);
  if (w == nullptr) return;
  std::unique_ptr<octomap::OcTree> last;
  for (auto _ : state) {
    auto tree = std::make_unique<octomap::OcTree>(w->resolution_m);
    insertOctomap(*tree, *w);
    benchmark::DoNotOptimize(tree.get());
    state.PauseTiming();
    last = std::move(tree);
    state.ResumeTiming();
  }
  setTreeCounters(state, *w, last->size(), last->getNumLeafNodes(), last->memoryUsage());
}

void BM_CloudParallel2(benchmark::State& state, CloudId id) {
  const CloudWorkload* w = cloudOrSkip(state, id);
  if (w == nullptr) return;
  std::unique_ptr<OcTree16> last;
  PointCloud buffer;
  for (auto _ : state) {
    auto map = std::make_unique<OcTree16>(w->resolution_m);
    insertSonarmapParallel(*map, *w, 2, buffer);
    benchmark::DoNotOptimize(map.get());
    state.PauseTiming();
    last = std::move(map);
    state.ResumeTiming();
  }
  const NodeCounts counts = last->counts();
  setTreeCounters(state, *w, counts.nodes, counts.leaves, last->memoryBytes());
  state.counters["identical"] = Counter(cloudComparison(id, *w).parallel_identical ? 1.0 : 0.0);
}

void setRayCounters(benchmark::State& state, const CloudWorkload& w, std::size_t voxels) {
  state.counters["points"] = Counter(static_cast<double>(w.points));
  state.counters["voxels"] = Counter(static_cast<double>(voxels));
  state.counters["voxels/s"] = Counter(static_cast<double>(voxels), Counter::kIsIterationInvariantRate);
}

void BM_CloudDDA(benchmark::State& state, CloudId id) {
  const CloudWorkload* w = cloudOrSkip(state, id);
  if (w == nullptr) return;
  const KeyCoder<16> coder(w->resolution_m);
  std::size_t voxels = 0;
  for (auto _ : state) {
    std::uint64_t sum = 0;
    voxels = 0;
    for (std::size_t s = 0; s < w->ray_ends.size(); ++s) {
      for (const Eigen::Vector3d& end : w->ray_ends[s]) {
        traverseDDA(coder, w->origins[s], end, [&](const Key16& key) {
          sum = fold(sum, key[0], key[1], key[2]);
          ++voxels;
        });
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  setRayCounters(state, *w, voxels);
}

void BM_CloudOctoMapRayKeys(benchmark::State& state, CloudId id) {
  const CloudWorkload* w = cloudOrSkip(state, id);
  if (w == nullptr) return;
  const octomap::OcTree tree(w->resolution_m);
  octomap::KeyRay ray;
  std::size_t voxels = 0;
  for (auto _ : state) {
    std::uint64_t sum = 0;
    voxels = 0;
    for (std::size_t s = 0; s < w->ray_ends_o.size(); ++s) {
      for (const octomap::point3d& end : w->ray_ends_o[s]) {
        tree.computeRayKeys(w->origins_o[s], end, ray);
        for (const octomap::OcTreeKey& key : ray) sum = fold(sum, key[0], key[1], key[2]);
        voxels += ray.size();
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  setRayCounters(state, *w, voxels);
}

#define SONARMAP_CLOUD_ROWS(fn)                                                                \
  BENCHMARK_CAPTURE(fn, graph_5cm, CloudId::kGraph5cm)->Apply(configure);                      \
  BENCHMARK_CAPTURE(fn, graph_2cm, CloudId::kGraph2cm)->Apply(configure);                      \
  BENCHMARK_CAPTURE(fn, sphere_5cm, CloudId::kSphere5cm)->Apply(configure);                    \
  BENCHMARK_CAPTURE(fn, room_5cm, CloudId::kRoom5cm)->Apply(configure)

SONARMAP_CLOUD_ROWS(BM_CloudSonarmap);
SONARMAP_CLOUD_ROWS(BM_CloudOctoMap);
SONARMAP_CLOUD_ROWS(BM_CloudDDA);
SONARMAP_CLOUD_ROWS(BM_CloudOctoMapRayKeys);
BENCHMARK_CAPTURE(BM_CloudParallel2, graph_2cm, CloudId::kGraph2cm)->Apply(configure);
BENCHMARK_CAPTURE(BM_CloudParallel2, room_5cm, CloudId::kRoom5cm)->Apply(configure);

}  // namespace
}  // namespace sonarmap::bench
