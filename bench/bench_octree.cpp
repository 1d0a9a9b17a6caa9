/// @file bench_octree.cpp
/// The occupancy octree on its own, sonarmap against OctoMap 1.9 on the same keys:
///
///   BM_OctreeCube/<lib>_<mode>   paper §5.4-5.5, Table 1: a 1 m cube at 1 cm, centred on the map
///                                origin (keys 32718 … 32817 on each axis, i.e. [-0.5 m, 0.5 m)),
///                                1,000,000 occupied updates, each voxel once, x outermost and
///                                z innermost. This placement reproduces the paper's node counts
///                                (1,145,977 nodes unpruned; 19,769 pruned, 5,201 of them inner).
///   BM_OctreeGauss/<lib>_<mode>_s<σ>
///                                paper §5.3, Fig. 8: 1,000,000 occupied updates at points drawn
///                                N(μ = 10000, σ) independently per axis, in voxel units from the
///                                map origin (at 1 cm: μ = 100 m), σ = 5000, 50, 5; sonarmap with
///                                and without its stability check, OctoMap once (its updateNode
///                                always searches first and aborts on a clamped leaf); in the
///                                eager and the lazy mode below, points in the order drawn.
///
/// Modes, and what each library runs:
///   noprune       sonarmap {prune = false, lazy = false}: inner nodes updated on every update,
///                 never pruned. OctoMap cannot update inner nodes eagerly without pruning (its
///                 eager updateNode always prunes), so its row is the closest equivalent that
///                 builds the same tree: updateNode(key, true, lazy_eval = true) for every key,
///                 then one updateInnerOccupancy() and no prune().
///   noprune_lazy  sonarmap {prune = false, lazy = true} + updateInnerOccupancy(): the exact
///                 counterpart of OctoMap's noprune row (sonarmap only).
///   eager         sonarmap {prune = true, lazy = false}; OctoMap updateNode(key, true) (lazy_eval
///                 = false: inner nodes updated and pruned on every update).
///   lazy          sonarmap {prune = true, lazy = true} + updateInnerOccupancy(); OctoMap
///                 updateNode(key, true, lazy_eval = true) + updateInnerOccupancy() + prune().
///
/// Keys are computed once, outside the timed loop, and are the same for both libraries (depth 16,
/// the same key layout). Every iteration builds a fresh tree; trees are freed outside the timed
/// region. After the loop each benchmark builds its map once more, untimed, to measure its heap
/// (malloc bytes in use, mallinfo2) and, for the OctoMap rows, to compare the tree node by node
/// with the sonarmap map of the same workload and mode.
///
/// Counters: updates/s; nodes, inner, leaves; bytes = sonarmap memoryBytes() or OctoMap
/// memoryUsage() (OctoMap's own estimate: 16 B per node + 64 B per inner node); heap = malloc bytes
/// the finished tree holds. OctoMap rows add bytes_sonarmap, heap_sonarmap, bytes_ratio =
/// sonarmap bytes / OctoMap bytes, heap_ratio likewise, and tree_agree: the share of nodes
/// (of the larger tree) that exist in both trees at the same place, with the same log-odds
/// (exact float equality) and both inner or both leaves. 1 with equal node counts means
/// identical trees.

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>
#include <octomap/octomap.h>

#include "bench_data.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap::bench {
namespace {

constexpr double kResolution_m = 0.01;
constexpr std::uint16_t kOriginKey = 32768;  // key of coordinate 0 at depth 16

enum class Mode { kNoPrune, kNoPruneLazy, kEager, kLazy };

/// The same keys in both libraries' types.
struct Keys {
  std::vector<Key16> sonarmap;
  std::vector<octomap::OcTreeKey> octomap;

  void add(std::uint16_t x, std::uint16_t y, std::uint16_t z) {
    sonarmap.push_back(Key16{{x, y, z}});
    octomap.emplace_back(x, y, z);
  }
};

/// The paper's Table 1 cube: 100 × 100 × 100 voxels centred on the origin, x outermost.
const Keys& cubeKeys() {
  static const Keys keys = [] {
    Keys k;
    constexpr int kEdge = 100;
    constexpr auto kFirst = static_cast<std::uint16_t>(kOriginKey - kEdge / 2);
    k.sonarmap.reserve(kEdge * kEdge * kEdge);
    k.octomap.reserve(kEdge * kEdge * kEdge);
    for (int x = 0; x < kEdge; ++x) {
      for (int y = 0; y < kEdge; ++y) {
        for (int z = 0; z < kEdge; ++z) {
          k.add(static_cast<std::uint16_t>(kFirst + x), static_cast<std::uint16_t>(kFirst + y),
                static_cast<std::uint16_t>(kFirst + z));
        }
      }
    }
    return k;
  }();
  return keys;
}

/// Fig. 8's clouds: 1,000,000 points, each axis N(10000, σ) in voxel units from the origin, rounded
/// to the voxel; a coordinate outside the depth-16 map (|c| ≥ 32768) is drawn again. Deterministic
/// (mt19937_64, fixed seed, libstdc++'s normal_distribution).
const Keys& gaussKeys(int sigma) {
  static std::vector<std::pair<int, std::unique_ptr<Keys>>> cache;
  for (const auto& [s, keys] : cache) {
    if (s == sigma) return *keys;
  }
  auto keys = std::make_unique<Keys>();
  constexpr std::size_t kPoints = 1'000'000;
  keys->sonarmap.reserve(kPoints);
  keys->octomap.reserve(kPoints);
  std::mt19937_64 rng(20260 + static_cast<std::uint64_t>(sigma));
  std::normal_distribution<double> normal(10000.0, static_cast<double>(sigma));
  auto draw = [&] {
    for (;;) {
      const double cell = std::floor(normal(rng) + 0.5);
      if (cell >= -32768.0 && cell < 32768.0) return static_cast<std::uint16_t>(static_cast<int>(cell) + kOriginKey);
    }
  };
  for (std::size_t i = 0; i < kPoints; ++i) {
    const std::uint16_t x = draw(), y = draw(), z = draw();
    keys->add(x, y, z);
  }
  cache.emplace_back(sigma, std::move(keys));
  return *cache.back().second;
}

OctreeOptions sonarmapOptions(Mode mode, bool stability_check) {
  OctreeOptions options;
  options.prune = mode == Mode::kEager || mode == Mode::kLazy;
  options.lazy = mode == Mode::kNoPruneLazy || mode == Mode::kLazy;
  options.stability_check = stability_check;
  return options;
}

/// The timed work for sonarmap. @return updates that changed a leaf (integrate returned true).
std::size_t buildSonarmap(OcTree16& map, const Keys& keys) {
  std::size_t applied = 0;
  for (const Key16& key : keys.sonarmap) applied += map.integrate(key, true) ? 1 : 0;
  if (map.options().lazy) map.updateInnerOccupancy();
  return applied;
}

/// The timed work for OctoMap.
void buildOctomap(octomap::OcTree& tree, const Keys& keys, Mode mode) {
  const bool lazy = mode != Mode::kEager;
  for (const octomap::OcTreeKey& key : keys.octomap) tree.updateNode(key, true, lazy);
  if (lazy) tree.updateInnerOccupancy();
  if (mode == Mode::kLazy) tree.prune();
}

/// Malloc bytes in use (arena chunks plus mmapped chunks).
std::size_t heapInUse() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

struct TreeComparison {
  std::size_t equal = 0;  ///< nodes present in both, same log-odds, same inner/leaf kind
};

void compareNodes(const OcTree16& map, NodeRef ref, const octomap::OcTree& tree, const octomap::OcTreeNode* node,
                  TreeComparison& result) {
  const OcTreeNode& ours = map.node(ref);
  const bool our_children = ours.hasChildren();
  const bool their_children = tree.nodeHasChildren(node);
  if (ours.log_odds == node->getLogOdds() && our_children == their_children) ++result.equal;
  if (!our_children || !their_children) return;
  for (unsigned i = 0; i < 8; ++i) {
    const NodeRef child = map.childRef(ours, i);
    if (child != kNoNodeRef && tree.nodeChildExists(node, i)) {
      compareNodes(map, child, tree, tree.getNodeChild(node, i), result);
    }
  }
}

/// Share of nodes of the larger tree that match (see the file comment).
double treeAgreement(const OcTree16& map, const octomap::OcTree& tree) {
  const std::size_t ours = map.counts().nodes;
  const std::size_t theirs = tree.size();
  if (ours == 0 && theirs == 0) return 1.0;
  TreeComparison result;
  if (!map.empty() && tree.getRoot() != nullptr) compareNodes(map, kRootRef, tree, tree.getRoot(), result);
  return static_cast<double>(result.equal) / static_cast<double>(std::max(ours, theirs));
}

void setTreeCounters(benchmark::State& state, std::size_t updates, std::size_t nodes, std::size_t leaves,
                     std::size_t bytes, std::size_t heap) {
  using benchmark::Counter;
  state.counters["updates/s"] = Counter(static_cast<double>(updates), Counter::kIsIterationInvariantRate);
  state.counters["nodes"] = Counter(static_cast<double>(nodes));
  state.counters["inner"] = Counter(static_cast<double>(nodes - leaves));
  state.counters["leaves"] = Counter(static_cast<double>(leaves));
  state.counters["bytes"] = Counter(static_cast<double>(bytes));
  state.counters["heap"] = Counter(static_cast<double>(heap));
}

void runSonarmap(benchmark::State& state, const Keys& keys, Mode mode, bool stability_check) {
  const OctreeOptions options = sonarmapOptions(mode, stability_check);
  for (auto _ : state) {
    auto map = std::make_unique<OcTree16>(kResolution_m, options);
    benchmark::DoNotOptimize(buildSonarmap(*map, keys));
    state.PauseTiming();
    map.reset();  // freed untimed
    state.ResumeTiming();
  }
  // Untimed: the same map once more, for its heap and counts.
  const std::size_t heap_before = heapInUse();
  auto map = std::make_unique<OcTree16>(kResolution_m, options);
  const std::size_t applied = buildSonarmap(*map, keys);
  const std::size_t heap = heapInUse() - heap_before;
  const NodeCounts counts = map->counts();
  setTreeCounters(state, keys.sonarmap.size(), counts.nodes, counts.leaves, map->memoryBytes(), heap);
  state.counters["applied"] = benchmark::Counter(static_cast<double>(applied));
}

void runOctomap(benchmark::State& state, const Keys& keys, Mode mode, bool compare_nocheck = false) {
  for (auto _ : state) {
    auto tree = std::make_unique<octomap::OcTree>(kResolution_m);
    buildOctomap(*tree, keys, mode);
    benchmark::DoNotOptimize(tree.get());
    state.PauseTiming();
    tree.reset();  // freed untimed
    state.ResumeTiming();
  }
  // Untimed: the same tree once more for its heap, and the sonarmap map of the same mode to
  // compare with (noprune: sonarmap's eager no-pruning map, which must equal OctoMap's).
  std::size_t heap_before = heapInUse();
  auto tree = std::make_unique<octomap::OcTree>(kResolution_m);
  buildOctomap(*tree, keys, mode);
  const std::size_t heap = heapInUse() - heap_before;
  const std::size_t nodes = tree->size();
  const std::size_t leaves = tree->getNumLeafNodes();
  const std::size_t bytes = tree->memoryUsage();
  setTreeCounters(state, keys.octomap.size(), nodes, leaves, bytes, heap);

  heap_before = heapInUse();
  auto map = std::make_unique<OcTree16>(kResolution_m, sonarmapOptions(mode, true));
  buildSonarmap(*map, keys);
  const std::size_t heap_sonarmap = heapInUse() - heap_before;
  using benchmark::Counter;
  state.counters["bytes_sonarmap"] = Counter(static_cast<double>(map->memoryBytes()));
  state.counters["heap_sonarmap"] = Counter(static_cast<double>(heap_sonarmap));
  state.counters["bytes_ratio"] = Counter(static_cast<double>(map->memoryBytes()) / static_cast<double>(bytes));
  state.counters["heap_ratio"] = Counter(static_cast<double>(heap_sonarmap) / static_cast<double>(heap));
  state.counters["tree_agree"] = Counter(treeAgreement(*map, *tree));
  if (mode == Mode::kNoPrune) {  // also the lazy sonarmap build without pruning
    map.reset();
    map = std::make_unique<OcTree16>(kResolution_m, sonarmapOptions(Mode::kNoPruneLazy, true));
    buildSonarmap(*map, keys);
    state.counters["tree_agree_lazy"] = Counter(treeAgreement(*map, *tree));
  }
  if (compare_nocheck) {
    // Fig. 8 rows: the sonarmap map without the stability check must be the same tree too.
    map.reset();
    map = std::make_unique<OcTree16>(kResolution_m, sonarmapOptions(mode, false));
    buildSonarmap(*map, keys);
    state.counters["tree_agree_nocheck"] = Counter(treeAgreement(*map, *tree));
  }
}

// --- Table 1: the cube ------------------------------------------------------------------------

void BM_OctreeCube(benchmark::State& state, bool octomap, Mode mode) {
  if (octomap) {
    runOctomap(state, cubeKeys(), mode);
  } else {
    runSonarmap(state, cubeKeys(), mode, true);
  }
}

BENCHMARK_CAPTURE(BM_OctreeCube, sonarmap_noprune, false, Mode::kNoPrune)->Apply(configure);
BENCHMARK_CAPTURE(BM_OctreeCube, sonarmap_noprune_lazy, false, Mode::kNoPruneLazy)->Apply(configure);
BENCHMARK_CAPTURE(BM_OctreeCube, octomap_noprune, true, Mode::kNoPrune)->Apply(configure);
BENCHMARK_CAPTURE(BM_OctreeCube, sonarmap_eager, false, Mode::kEager)->Apply(configure);
BENCHMARK_CAPTURE(BM_OctreeCube, octomap_eager, true, Mode::kEager)->Apply(configure);
BENCHMARK_CAPTURE(BM_OctreeCube, sonarmap_lazy, false, Mode::kLazy)->Apply(configure);
BENCHMARK_CAPTURE(BM_OctreeCube, octomap_lazy, true, Mode::kLazy)->Apply(configure);

// --- Fig. 8: Gaussian clouds, with and without the stability check ----------------------------

enum class GaussLib { kSonarmapCheck, kSonarmapNoCheck, kOctomap };

void BM_OctreeGauss(benchmark::State& state, GaussLib lib, Mode mode, int sigma) {
  const Keys& keys = gaussKeys(sigma);
  switch (lib) {
    case GaussLib::kSonarmapCheck: runSonarmap(state, keys, mode, true); break;
    case GaussLib::kSonarmapNoCheck: runSonarmap(state, keys, mode, false); break;
    case GaussLib::kOctomap: runOctomap(state, keys, mode, /*compare_nocheck=*/true); break;
  }
}

#define SONARMAP_GAUSS(mode, Mode, sigma)                                                              \
  BENCHMARK_CAPTURE(BM_OctreeGauss, sonarmap_check_##mode##_s##sigma, GaussLib::kSonarmapCheck, Mode, sigma)     \
      ->Apply(configure);                                                                                \
  BENCHMARK_CAPTURE(BM_OctreeGauss, sonarmap_nocheck_##mode##_s##sigma, GaussLib::kSonarmapNoCheck, Mode, sigma) \
      ->Apply(configure);                                                                                \
  BENCHMARK_CAPTURE(BM_OctreeGauss, octomap_##mode##_s##sigma, GaussLib::kOctomap, Mode, sigma)->Apply(configure)

SONARMAP_GAUSS(eager, Mode::kEager, 5000);
SONARMAP_GAUSS(eager, Mode::kEager, 50);
SONARMAP_GAUSS(eager, Mode::kEager, 5);
SONARMAP_GAUSS(lazy, Mode::kLazy, 5000);
SONARMAP_GAUSS(lazy, Mode::kLazy, 50);
SONARMAP_GAUSS(lazy, Mode::kLazy, 5);

#undef SONARMAP_GAUSS

}  // namespace
}  // namespace sonarmap::bench
