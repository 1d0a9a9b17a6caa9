/// @file bench_cloud.cpp
/// Point-cloud workloads, each through sonarmap and OctoMap 1.9 in the same run
/// (workloads in bench_cloud_workloads.hpp):
///   BM_CloudSonarmap/<w>        insertPointCloud (insertScan for the graph), serial, fresh map
///   BM_CloudOctoMap/<w>         OcTree::insertPointCloud (ScanNode overload for the graph)
///   BM_CloudDDA/<w>             traverseDDA origin → point for every point, no map (keys folded
///                               into a checksum); points beyond the range clipped as insertion does
///   BM_CloudOctoMapRayKeys/<w>  OcTree::computeRayKeys over the same rays, into a reused KeyRay
///   BM_CloudThreads/<w>/threads:N  insertPointCloudParallel with N threads (1, 2, 4), fresh map,
///                               wall time
///   BM_CloudFloor/<w>           the floor: every input point keyed once, then each scan's distinct
///                               free and occupied voxels (computed outside the loop) updated once,
///                               brick by brick, and the inner nodes synced: what any insertion
///                               with OctoMap's map must at least do
/// Both libraries use their defaults (eager inner-node updates, OctoMap's sensor model). Trees
/// are freed outside the timed region. Counters: points; nodes, leaves, bytes of the last
/// iteration's map (sonarmap memoryBytes(), OctoMap memoryUsage()); on the sonarmap rows, the
/// comparison of the two maps, computed once outside the loop: agree (share of the finest voxels
/// known to both whose free/occupied class agrees), known_* (finest voxels, pruned leaves
/// expanded), bytes_ratio (sonarmap / OctoMap); on the thread rows, identical (1 when the map
/// equals the serial map leaf by leaf).

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <memory>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

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

void BM_CloudThreads(benchmark::State& state, CloudId id) {
  const CloudWorkload* w = cloudOrSkip(state, id);
  if (w == nullptr) return;
  const auto threads = static_cast<unsigned>(state.range(0));
  std::unique_ptr<OcTree16> last;
  PointCloud buffer;
  for (auto _ : state) {
    auto map = std::make_unique<OcTree16>(w->resolution_m);
    insertSonarmapParallel(*map, *w, threads, buffer);
    benchmark::DoNotOptimize(map.get());
    state.PauseTiming();
    last = std::move(map);
    state.ResumeTiming();
  }
  const NodeCounts counts = last->counts();
  setTreeCounters(state, *w, counts.nodes, counts.leaves, last->memoryBytes());
  state.counters["identical"] = Counter(parallelMapIsSerial(*w, *last) ? 1.0 : 0.0);
}

/// One brick of distinct voxels: its lowest key and its voxels in updateBrick's (Morton) order.
struct FloorBrick {
  Key16 corner;
  std::uint64_t voxels;
};

/// The distinct voxels of one scan as OctoMap's computeUpdate defines them, brick by brick.
struct FloorScan {
  std::vector<FloorBrick> free, occupied;
};

std::vector<FloorBrick> bricksOf(std::vector<Key16> keys) {
  const auto corner = [](const Key16& k) {
    return Key16{{static_cast<std::uint16_t>(k[0] & ~3U), static_cast<std::uint16_t>(k[1] & ~3U),
                  static_cast<std::uint16_t>(k[2] & ~3U)}};
  };
  const auto order = [&](const Key16& a, const Key16& b) {
    const Key16 ca = corner(a), cb = corner(b);
    return std::tie(ca[2], ca[1], ca[0]) < std::tie(cb[2], cb[1], cb[0]);
  };
  std::sort(keys.begin(), keys.end(), order);
  std::vector<FloorBrick> bricks;
  for (const Key16& k : keys) {
    const unsigned bit = (k[0] & 1U) | ((k[1] & 1U) << 1) | ((k[2] & 1U) << 2) | ((k[0] & 2U) << 2) |
                         ((k[1] & 2U) << 3) | ((k[2] & 2U) << 4);
    if (bricks.empty() || !(bricks.back().corner == corner(k))) bricks.push_back({corner(k), 0});
    bricks.back().voxels |= std::uint64_t{1} << bit;
  }
  return bricks;
}

/// Each scan's distinct free and occupied voxels (every ray's DDA keys but a clipped ray's end,
/// minus the hit ends), computed once.
const std::vector<FloorScan>& floorScans(CloudId id, const CloudWorkload& w) {
  static std::array<std::optional<std::vector<FloorScan>>, kCloudWorkloads> cache;
  std::optional<std::vector<FloorScan>>& slot = cache[static_cast<std::size_t>(id)];
  if (slot) return *slot;
  const KeyCoder<16> coder(w.resolution_m);
  slot.emplace();
  for (std::size_t s = 0; s < w.ray_ends.size(); ++s) {
    std::vector<Key16> crossed, hits;
    for (std::size_t i = 0; i < w.ray_ends[s].size(); ++i) {
      const Eigen::Vector3d& end = w.ray_ends[s][i];
      const bool hit = end == w.world[s][i];
      std::vector<Key16> ray;
      traverseDDA(coder, w.origins[s], end, [&](const Key16& key) { ray.push_back(key); });
      if (ray.empty()) continue;
      if (hit) hits.push_back(ray.back());
      crossed.insert(crossed.end(), ray.begin(), ray.end() - 1);
    }
    const auto less = [](const Key16& a, const Key16& b) {
      return std::tie(a[2], a[1], a[0]) < std::tie(b[2], b[1], b[0]);
    };
    std::sort(hits.begin(), hits.end(), less);
    hits.erase(std::unique(hits.begin(), hits.end()), hits.end());
    std::sort(crossed.begin(), crossed.end(), less);
    crossed.erase(std::unique(crossed.begin(), crossed.end()), crossed.end());
    std::vector<Key16> free;
    std::set_difference(crossed.begin(), crossed.end(), hits.begin(), hits.end(), std::back_inserter(free), less);
    slot->push_back({bricksOf(std::move(free)), bricksOf(std::move(hits))});
  }
  return *slot;
}

void BM_CloudFloor(benchmark::State& state, CloudId id) {
  const CloudWorkload* w = cloudOrSkip(state, id);
  if (w == nullptr) return;
  const std::vector<FloorScan>& scans = floorScans(id, *w);
  const KeyCoder<16> coder(w->resolution_m);
  std::size_t voxels = 0;
  for (const FloorScan& scan : scans) {
    for (const FloorBrick& b : scan.free) voxels += static_cast<std::size_t>(std::popcount(b.voxels));
    for (const FloorBrick& b : scan.occupied) voxels += static_cast<std::size_t>(std::popcount(b.voxels));
  }
  std::unique_ptr<OcTree16> last;
  for (auto _ : state) {
    auto map = std::make_unique<OcTree16>(w->resolution_m);
    const float miss = map->model().miss, hit = map->model().hit;
    std::uint64_t sum = 0;
    for (std::size_t s = 0; s < scans.size(); ++s) {
      for (const Eigen::Vector3d& point : w->world[s]) {  // the input: every point keyed once
        Key16 key;
        if (coder.keyInto(point, key)) sum = fold(sum, key[0], key[1], key[2]);
      }
      map->reserve(scans[s].free.size() * 8 + scans[s].occupied.size() * 2);
      for (const FloorBrick& b : scans[s].free) map->updateBrick(b.corner, b.voxels, miss);
      for (const FloorBrick& b : scans[s].occupied) map->updateBrick(b.corner, b.voxels, hit);
      map->updateDirtyInnerOccupancy();
    }
    benchmark::DoNotOptimize(sum);
    benchmark::DoNotOptimize(map.get());
    state.PauseTiming();
    last = std::move(map);
    state.ResumeTiming();
  }
  const NodeCounts counts = last->counts();
  setTreeCounters(state, *w, counts.nodes, counts.leaves, last->memoryBytes());
  state.counters["voxels"] = Counter(static_cast<double>(voxels));
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
SONARMAP_CLOUD_ROWS(BM_CloudFloor);
#define SONARMAP_CLOUD_THREAD_ROWS(w, id) \
  BENCHMARK_CAPTURE(BM_CloudThreads, w, id)->Apply(configure)->ArgName("threads")->Arg(1)->Arg(2)->Arg(4)->UseRealTime()
SONARMAP_CLOUD_THREAD_ROWS(graph_5cm, CloudId::kGraph5cm);
SONARMAP_CLOUD_THREAD_ROWS(graph_2cm, CloudId::kGraph2cm);
SONARMAP_CLOUD_THREAD_ROWS(sphere_5cm, CloudId::kSphere5cm);
SONARMAP_CLOUD_THREAD_ROWS(room_5cm, CloudId::kRoom5cm);

}  // namespace
}  // namespace sonarmap::bench
