// Occupancy octree behaviour: log-odds updates, stability check, inner aggregation, pruning,
// lazy evaluation, expansion, counts and memory (paper §5).
#include <gtest/gtest.h>

#include <bit>
#include <map>
#include <random>
#include <tuple>

#include "octree/octree_testing.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {
namespace {

using testing::key16;
using testing::Leaf;
using testing::asTuple;
using testing::leavesOf;

TEST(Octree, EmptyTreeIsUnknown) {
  const OcTree16 tree(0.05);
  EXPECT_TRUE(tree.empty());
  EXPECT_EQ(tree.occupancyOf(key16(0, 0, 0)), Occupancy::kUnknown);
  EXPECT_EQ(tree.counts().nodes, 0U);
}

TEST(Octree, SingleHitCreatesOnePathOf17Nodes) {
  OcTree16 tree(0.01);
  EXPECT_TRUE(tree.integrate(key16(-5, -2, 100), true));
  const NodeCounts counts = tree.counts();
  EXPECT_EQ(counts.nodes, 17U);  // OctoMap's test_pruning: a single voxel makes 17 nodes
  EXPECT_EQ(counts.leaves, 1U);
  EXPECT_EQ(tree.occupancyOf(key16(-5, -2, 100)), Occupancy::kOccupied);
  EXPECT_EQ(tree.occupancyOf(key16(-4, -2, 100)), Occupancy::kUnknown);
  EXPECT_FLOAT_EQ(*tree.search(key16(-5, -2, 100)), tree.model().hit);
  // Max aggregation carries the hit up to the root.
  EXPECT_FLOAT_EQ(*tree.search(key16(-5, -2, 100), 0), tree.model().hit);
}

TEST(Octree, UpdatesClampAndStableLeavesAreSkipped) {
  OcTree16 tree(0.1);
  const Key16 key = key16(3, 4, 5);
  int applied = 0;
  for (int i = 0; i < 10; ++i) applied += tree.integrate(key, true) ? 1 : 0;
  EXPECT_FLOAT_EQ(*tree.search(key), tree.model().clamp_max);
  EXPECT_EQ(applied, 5);  // 0.847 × 5 > 3.5: the 6th hit finds the leaf clamped and is skipped
  EXPECT_FALSE(tree.updateNode(key, 0.0F));
  EXPECT_TRUE(tree.integrate(key, false));  // a miss on a clamped-occupied leaf still applies
}

TEST(Octree, WithoutStabilityCheckEveryUpdateIsApplied) {
  OctreeOptions options;
  options.stability_check = false;
  OcTree16 tree(0.1, options);
  int applied = 0;
  for (int i = 0; i < 10; ++i) applied += tree.integrate(key16(0, 0, 0), true) ? 1 : 0;
  EXPECT_EQ(applied, 10);
  EXPECT_FLOAT_EQ(*tree.search(key16(0, 0, 0)), tree.model().clamp_max);
}

TEST(Octree, EightEqualSiblingsArePrunedIntoTheirParent) {
  OcTree16 tree(0.01);
  for (int i = 0; i < 8; ++i) tree.integrate(key16(i & 1, (i >> 1) & 1, (i >> 2) & 1), true);
  NodeCounts counts = tree.counts();
  EXPECT_EQ(counts.nodes, 16U);  // the 8 leaves collapsed into one leaf at depth 15
  EXPECT_EQ(counts.leaves, 1U);
  EXPECT_EQ(tree.occupancyOf(key16(1, 1, 1)), Occupancy::kOccupied);
  // Updating one voxel of the pruned leaf expands it again.
  tree.integrate(key16(1, 1, 1), false);
  counts = tree.counts();
  EXPECT_EQ(counts.nodes, 24U);
  EXPECT_EQ(counts.leaves, 8U);
  EXPECT_FLOAT_EQ(*tree.search(key16(0, 0, 0)), tree.model().hit);
  EXPECT_FLOAT_EQ(*tree.search(key16(1, 1, 1)), tree.model().hit + tree.model().miss);
}

TEST(Octree, WithoutPruningSiblingsStay) {
  OctreeOptions options;
  options.prune = false;
  OcTree16 tree(0.01, options);
  for (int i = 0; i < 8; ++i) tree.integrate(key16(i & 1, (i >> 1) & 1, (i >> 2) & 1), true);
  EXPECT_EQ(tree.counts().nodes, 24U);
  EXPECT_EQ(tree.counts().leaves, 8U);
}

TEST(Octree, CubeOf32VoxelsPrunesToOneNodeAtDepth11) {
  OcTree16 tree(0.01);  // a 0.32 m cube aligned to a depth-11 node
  for (int x = 0; x < 32; ++x)
    for (int y = 0; y < 32; ++y)
      for (int z = 0; z < 32; ++z) tree.integrate(key16(x, y, z), true);
  const NodeCounts counts = tree.counts();
  EXPECT_EQ(counts.leaves, 1U);
  EXPECT_EQ(counts.nodes, 12U);
  int leaf_depth = -1;
  tree.forEachLeaf([&](const LeafView<16>& leaf) { leaf_depth = leaf.depth; });
  EXPECT_EQ(leaf_depth, 11);
}

TEST(Octree, MeanAggregationAveragesExistingChildren) {
  OctreeOptions options;
  options.aggregation = InnerAggregation::kMean;
  OcTree16 tree(0.01, options);
  tree.integrate(key16(0, 0, 0), true);
  tree.integrate(key16(1, 0, 0), false);
  const float expected = 0.5F * (tree.model().hit + tree.model().miss);
  EXPECT_NEAR(*tree.search(key16(0, 0, 0), 15), expected, 1e-6);
  OcTree16 max_tree(0.01);
  max_tree.integrate(key16(0, 0, 0), true);
  max_tree.integrate(key16(1, 0, 0), false);
  EXPECT_FLOAT_EQ(*max_tree.search(key16(0, 0, 0), 15), max_tree.model().hit);
}

/// Applies the same random updates to a tree and to a plain map of clamped sums.
template <int Depth>
void expectMatchesReference(const OctreeOptions& options, unsigned seed) {
  using Tree = OccupancyOctree<Depth>;
  Tree tree(0.05, options);
  const LogOddsModel& model = tree.model();
  std::map<std::tuple<long, long, long>, float> reference;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coord(-6, 5);
  std::bernoulli_distribution hit(0.6);
  for (int i = 0; i < 20000; ++i) {
    const int x = coord(rng), y = coord(rng), z = coord(rng) / 3;
    const auto key = tree.coder().keyOf({0.05 * x + 0.01, 0.05 * y + 0.01, 0.05 * z + 0.01});
    ASSERT_TRUE(key.has_value());
    const float delta = hit(rng) ? model.hit : model.miss;
    tree.updateNode(*key, delta);
    auto [it, inserted] = reference.try_emplace({x, y, z}, 0.0F);
    it->second = model.update(it->second, delta);
  }
  if (options.lazy) tree.updateInnerOccupancy();
  for (const auto& [xyz, value] : reference) {
    const auto [x, y, z] = xyz;
    const auto key = *tree.coder().keyOf({0.05 * x + 0.01, 0.05 * y + 0.01, 0.05 * z + 0.01});
    ASSERT_TRUE(tree.search(key).has_value());
    EXPECT_FLOAT_EQ(*tree.search(key), value);
  }
  std::size_t voxels = 0;
  tree.forEachLeaf([&](const LeafView<Depth>& leaf) {
    voxels += static_cast<std::size_t>(std::pow(leaf.edgeVoxels(), 3));
  });
  EXPECT_EQ(voxels, reference.size());
}

TEST(Octree, RandomUpdatesMatchAPlainVoxelMap) {
  expectMatchesReference<16>({}, 1);
  OctreeOptions no_check;
  no_check.stability_check = false;
  expectMatchesReference<16>(no_check, 2);
}

TEST(Octree, OtherDepthsBehaveTheSame) {
  expectMatchesReference<8>({}, 3);
  expectMatchesReference<32>({}, 4);
  expectMatchesReference<64>({}, 5);
  expectMatchesReference<100>({}, 6);
}

TEST(Octree, LazyEvaluationEndsInTheSameTreeAsEagerUpdates) {
  OctreeOptions lazy_options;
  lazy_options.lazy = true;
  OcTree16 eager(0.02);
  OcTree16 lazy(0.02, lazy_options);
  for (int x = -20; x < 20; ++x)
    for (int y = -20; y < 20; ++y)
      for (int z = 0; z < 4; ++z) {
        eager.integrate(key16(x, y, z), (x + y) % 7 != 0);
        lazy.integrate(key16(x, y, z), (x + y) % 7 != 0);
      }
  lazy.updateInnerOccupancy();
  const NodeCounts a = eager.counts();
  const NodeCounts b = lazy.counts();
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.leaves, b.leaves);
  EXPECT_LT(a.leaves, 40U * 40U * 4U);  // pruning did something
  std::vector<std::pair<int, float>> leaves_a, leaves_b;
  eager.forEachLeaf([&](const LeafView<16>& l) { leaves_a.emplace_back(l.depth, l.log_odds); });
  lazy.forEachLeaf([&](const LeafView<16>& l) { leaves_b.emplace_back(l.depth, l.log_odds); });
  EXPECT_EQ(leaves_a, leaves_b);
  EXPECT_FLOAT_EQ(*eager.search(key16(0, 0, 0), 0), *lazy.search(key16(0, 0, 0), 0));
}

TEST(Octree, NodesAreEightBytesAndMemoryFollowsCompactArrays) {
  OcTree16 tree(0.01);
  tree.integrate(key16(0, 0, 0), true);
  // Root and "no node" slots, then 16 inner nodes each with a one-child array (header + child).
  EXPECT_EQ(tree.memoryBytes(), (2U + 16U * 2U) * 8U + sizeof(OcTree16));
  // A sibling fills the one-child array of the depth-15 node: it grows to capacity 2 (3 slots).
  tree.integrate(key16(1, 0, 0), true);
  EXPECT_EQ(tree.memoryBytes(), (2U + 15U * 2U + 3U) * 8U + sizeof(OcTree16));
  // A third: an array holds exactly its children, capacity 3 (4 slots), none spare.
  tree.integrate(key16(0, 1, 0), true);
  EXPECT_EQ(tree.memoryBytes(), (2U + 15U * 2U + 4U) * 8U + sizeof(OcTree16));
  // Eight siblings: capacity 8 (9 slots) until they prune into their parent.
  for (unsigned i = 3; i < 8; ++i) tree.integrate(key16(i & 1U, (i >> 1) & 1U, i >> 2), true);
  EXPECT_EQ(tree.counts().leaves, 1U);
  EXPECT_EQ(tree.memoryBytes(), (2U + 15U * 2U) * 8U + sizeof(OcTree16));
  EXPECT_GE(tree.memoryBytesAllocated(), tree.memoryBytes());
}

TEST(Octree, ChildrenAddedInAnyOrderAreFoundByIndex) {
  OcTree16 tree(0.01, OctreeOptions{.prune = false});
  const unsigned order[8] = {5, 0, 7, 2, 6, 1, 3, 4};  // grows the array 1 → 2 → 4 → 8, inserting inside
  for (unsigned n = 0; n < 8; ++n) {
    const unsigned i = order[n];
    tree.updateNode(key16(i & 1U, (i >> 1) & 1U, i >> 2), 0.1F * static_cast<float>(i + 1));
  }
  for (unsigned i = 0; i < 8; ++i) {
    EXPECT_FLOAT_EQ(*tree.search(key16(i & 1U, (i >> 1) & 1U, i >> 2)), 0.1F * static_cast<float>(i + 1)) << i;
  }
  EXPECT_EQ(tree.counts().leaves, 8U);
}

TEST(Octree, ShrinkToFitKeepsTheTreeAndGivesMemoryBack) {
  OcTree16 tree(0.01, OctreeOptions{.lazy = true});
  for (int x = 0; x < 64; ++x)
    for (int y = 0; y < 64; ++y)
      for (int z = 0; z < 64; ++z) tree.integrate(key16(x, y, z), (x / 16 + y / 16 + z / 16) % 2 == 0);
  const std::size_t before = tree.memoryBytesAllocated();
  tree.updateInnerOccupancy();  // prunes every 16³ block, then compacts: most slots were freed
  std::vector<std::tuple<Key16, int, float>> leaves;
  tree.forEachLeaf([&](const LeafView<16>& l) { leaves.emplace_back(l.key, l.depth, l.log_odds); });
  EXPECT_EQ(leaves.size(), 64U);
  EXPECT_LT(tree.memoryBytesAllocated(), before / 20);
  EXPECT_LE(tree.memoryBytes(), tree.memoryBytesAllocated());
  tree.shrinkToFit();  // again: nothing changes
  std::vector<std::tuple<Key16, int, float>> again;
  tree.forEachLeaf([&](const LeafView<16>& l) { again.emplace_back(l.key, l.depth, l.log_odds); });
  EXPECT_EQ(leaves, again);
  EXPECT_EQ(tree.occupancyOf(key16(0, 0, 0)), Occupancy::kOccupied);
  EXPECT_EQ(tree.occupancyOf(key16(16, 0, 0)), Occupancy::kFree);
}

TEST(Octree, ReserveMakesRoomWithoutChangingTheTree) {
  OcTree16 tree(0.01);
  tree.integrate(key16(0, 0, 0), true);
  const std::size_t bytes = tree.memoryBytes();
  tree.reserve(100000);
  EXPECT_EQ(tree.memoryBytes(), bytes);
  EXPECT_GE(tree.memoryBytesAllocated(), 100000U * 8U);
  const std::size_t reserved = tree.memoryBytesAllocated();
  for (int x = 0; x < 32; ++x)  // about 40,000 slots: fits, so the pool does not grow again
    for (int y = 0; y < 32; ++y)
      for (int z = 0; z < 32; ++z) tree.integrate(key16(x, y, z), (x + y + z) % 2 == 0);
  // Only the free lists of outgrown arrays add bytes; a grown pool would add 800 KB at least.
  EXPECT_LT(tree.memoryBytesAllocated(), reserved + 64U * 1024U);
  EXPECT_GT(tree.memoryBytes(), 32U * 32U * 32U * 8U);
  EXPECT_EQ(tree.occupancyOf(key16(1, 0, 0)), Occupancy::kFree);
  const std::size_t filled = tree.memoryBytesAllocated();
  tree.reserve(10);  // already room: nothing changes
  EXPECT_EQ(tree.memoryBytesAllocated(), filled);
}

TEST(Octree, RawAccessRejectsMissingChildren) {
  OcTree16 tree(0.01);
  tree.integrate(key16(0, 0, 0), true);
  const OcTreeNode& root = tree.node(kRootRef);
  unsigned found = 0;
  for (unsigned i = 0; i < 8; ++i) found += tree.childRef(root, i) != kNoNodeRef ? 1U : 0U;
  EXPECT_EQ(found, 1U);
  EXPECT_EQ(std::popcount(tree.childMask(root)), 1);
  EXPECT_THROW(tree.setLogOdds(kNoNodeRef, 1.0F), ValueError);
  EXPECT_THROW(tree.createChildren(kRootRef, 0xFF), ValueError);  // the root already has children
}

TEST(Octree, OccupancyAtRejectsPointsOutsideTheMap) {
  OcTree16 tree(0.01);
  EXPECT_THROW(tree.occupancyAt({400.0, 0.0, 0.0}), OutOfMapError);
  EXPECT_EQ(tree.occupancyAt({1.0, 0.0, 0.0}), Occupancy::kUnknown);
}

}  // namespace
}  // namespace sonarmap
