// Octree queries and bookkeeping: leaves in a box of keys (against a brute-force filter of
// forEachLeaf), change detection (against class snapshots), lazy per-update evaluation.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "octree/octree_testing.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {
namespace {

using testing::key16;
using testing::Leaf;
using testing::asTuple;
using testing::leavesOf;

/// Random hits and misses around the origin plus a solid block that prunes to coarse leaves.
OcTree16 sampleTree(const OctreeOptions& options = {}) {
  OcTree16 tree(0.05, options);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> coord(-40, 40);
  for (int i = 0; i < 20000; ++i) tree.integrate(key16(coord(rng), coord(rng), coord(rng) / 4), i % 3 == 0);
  for (int x = 0; x < 32; ++x)
    for (int y = 0; y < 32; ++y)
      for (int z = 0; z < 16; ++z) tree.integrate(key16(64 + x, y, 16 + z), false);
  if (options.lazy) tree.updateInnerOccupancy();
  return tree;
}

std::vector<Leaf> bruteForceInBox(const OcTree16& tree, const Key16& lo, const Key16& hi) {
  std::vector<Leaf> leaves;
  tree.forEachLeaf([&](const LeafView<16>& leaf) {
    const long edge = static_cast<long>(leaf.edgeVoxels());
    for (int axis = 0; axis < 3; ++axis) {
      if (leaf.key[axis] > hi[axis] || leaf.key[axis] + edge - 1 < lo[axis]) return;
    }
    leaves.push_back(asTuple(leaf));
  });
  return leaves;
}

std::vector<Leaf> inBox(const OcTree16& tree, const Key16& lo, const Key16& hi) {
  std::vector<Leaf> leaves;
  tree.forEachLeafInBox(lo, hi, [&](const LeafView<16>& leaf) { leaves.push_back(asTuple(leaf)); });
  return leaves;
}

TEST(octreeLeafBox, VisitsExactlyTheLeavesIntersectingTheBox) {
  const OcTree16 tree = sampleTree();
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> coord(-50, 100);
  std::size_t visited = 0, pruned_seen = 0;
  for (int i = 0; i < 300; ++i) {
    Key16 lo = key16(coord(rng), coord(rng), coord(rng) / 3), hi = key16(coord(rng), coord(rng), coord(rng) / 3);
    for (int axis = 0; axis < 3; ++axis) {
      if (lo[axis] > hi[axis]) std::swap(lo[axis], hi[axis]);
    }
    const std::vector<Leaf> leaves = inBox(tree, lo, hi);
    ASSERT_EQ(leaves, bruteForceInBox(tree, lo, hi)) << "box " << i;
    visited += leaves.size();
    for (const Leaf& leaf : leaves) pruned_seen += std::get<3>(leaf) < 16 ? 1 : 0;
  }
  EXPECT_GT(visited, 10000U);
  EXPECT_GT(pruned_seen, 0U);  // boxes cut pruned leaves too
}

TEST(octreeLeafBox, SingleVoxelWholeMapAndEmptyBoxes) {
  const OcTree16 tree = sampleTree();
  const Key16 voxel = key16(70, 3, 20);  // inside the pruned block
  const std::vector<Leaf> one = inBox(tree, voxel, voxel);
  ASSERT_EQ(one.size(), 1U);
  EXPECT_LT(std::get<3>(one[0]), 16);
  std::vector<Leaf> all;
  tree.forEachLeaf([&](const LeafView<16>& leaf) { all.push_back(asTuple(leaf)); });
  EXPECT_EQ(inBox(tree, Key16{{0, 0, 0}}, Key16{{0xFFFF, 0xFFFF, 0xFFFF}}), all);
  EXPECT_TRUE(inBox(tree, key16(5, 0, 0), key16(4, 10, 10)).empty());    // min > max
  EXPECT_TRUE(inBox(tree, key16(500, 500, 500), key16(600, 600, 600)).empty());  // unknown space
  EXPECT_TRUE(inBox(OcTree16(0.1), key16(0, 0, 0), key16(1, 1, 1)).empty());
}

TEST(octreeLeafBox, MetreCornersMatchKeyCorners) {
  const OcTree16 tree = sampleTree();
  const Eigen::Vector3d lo_m(-0.52, -0.31, 0.0), hi_m(1.07, 0.66, 0.4);
  std::vector<Leaf> by_metres;
  tree.forEachLeafInBox(lo_m, hi_m, [&](const LeafView<16>& leaf) { by_metres.push_back(asTuple(leaf)); });
  EXPECT_EQ(by_metres, inBox(tree, *tree.coder().keyOf(lo_m), *tree.coder().keyOf(hi_m)));
  EXPECT_THROW(tree.forEachLeafInBox(Eigen::Vector3d(-5000, 0, 0), hi_m, [](const LeafView<16>&) {}), OutOfMapError);
}

/// Class of every voxel of a box around the updates.
std::map<std::tuple<int, int, int>, Occupancy> snapshot(const OcTree16& tree, int half) {
  std::map<std::tuple<int, int, int>, Occupancy> classes;
  for (int x = -half; x <= half; ++x)
    for (int y = -half; y <= half; ++y)
      for (int z = -2; z <= 2; ++z) classes[{x, y, z}] = tree.occupancyOf(key16(x, y, z));
  return classes;
}

/// Random updates on a small box: enough repeats to cross thresholds back and forth.
void randomUpdates(OcTree16& tree, unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coord(-6, 6), zc(-2, 2);
  std::bernoulli_distribution hit(0.45);
  for (int i = 0; i < count; ++i) tree.integrate(key16(coord(rng), coord(rng), zc(rng)), hit(rng));
}

void expectChangesMatchSnapshots(const OcTree16& tree, const std::map<std::tuple<int, int, int>, Occupancy>& before) {
  std::size_t expected = 0;
  for (const auto& [xyz, was] : before) {
    const auto [x, y, z] = xyz;
    const Occupancy now = tree.occupancyOf(key16(x, y, z));
    const auto it = tree.changedKeys().find(key16(x, y, z));
    if (now == was) {
      EXPECT_TRUE(it == tree.changedKeys().end()) << x << " " << y << " " << z;
      continue;
    }
    ++expected;
    ASSERT_TRUE(it != tree.changedKeys().end()) << x << " " << y << " " << z;
    EXPECT_EQ(it->second.created, was == Occupancy::kUnknown);
    EXPECT_EQ(it->second.before, was);
    EXPECT_EQ(it->second.now, now);
    EXPECT_EQ(it->second.occupied(), now == Occupancy::kOccupied);
  }
  EXPECT_EQ(tree.numChangesDetected(), expected);
}

TEST(octreeChangeDetection, ReportsExactlyTheVoxelsWhoseClassChanged) {
  for (const bool lazy : {false, true}) {
    OctreeOptions options;
    options.lazy = lazy;
    OcTree16 tree(0.05, options);
    randomUpdates(tree, 1, 200);  // not recorded: detection is off
    EXPECT_EQ(tree.numChangesDetected(), 0U);
    tree.enableChangeDetection(true);
    for (unsigned round = 0; round < 4; ++round) {
      const auto before = snapshot(tree, 8);
      randomUpdates(tree, 10 + round, 400);
      if (lazy) tree.updateInnerOccupancy();
      expectChangesMatchSnapshots(tree, before);
      EXPECT_GT(tree.numChangesDetected(), 0U);
      tree.resetChangeDetection();
      EXPECT_EQ(tree.numChangesDetected(), 0U);
    }
  }
}

TEST(octreeChangeDetection, RevertedChangesDisappearButCreatedVoxelsStay) {
  OcTree16 tree(0.05);
  tree.integrate(key16(0, 0, 0), false);
  tree.enableChangeDetection(true);
  tree.integrate(key16(0, 0, 0), true);  // −0.405 + 0.847 > 0: free → occupied
  ASSERT_EQ(tree.numChangesDetected(), 1U);
  EXPECT_TRUE(tree.changedKeys().at(key16(0, 0, 0)).occupied());
  tree.integrate(key16(0, 0, 0), false);
  tree.integrate(key16(0, 0, 0), false);  // back to free: no change since the reset
  EXPECT_EQ(tree.numChangesDetected(), 0U);
  tree.integrate(key16(1, 0, 0), false);  // created
  tree.integrate(key16(1, 0, 0), true);
  tree.integrate(key16(1, 0, 0), false);
  ASSERT_EQ(tree.numChangesDetected(), 1U);
  EXPECT_TRUE(tree.changedKeys().at(key16(1, 0, 0)).created);
  tree.enableChangeDetection(false);
  tree.integrate(key16(2, 0, 0), true);
  EXPECT_EQ(tree.numChangesDetected(), 1U);
  tree.clear();
  EXPECT_EQ(tree.numChangesDetected(), 0U);
}

TEST(octreeLazyUpdates, LazyUpdatesInAnEagerTreeSyncToTheEagerTree) {
  OcTree16 eager(0.05), mixed(0.05), dirty_only(0.05);
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> coord(-20, 20);
  for (int i = 0; i < 30000; ++i) {
    const Key16 key = key16(coord(rng), coord(rng), coord(rng) / 5);
    const bool hit = i % 4 == 0;
    eager.integrate(key, hit);
    mixed.integrate(key, hit, /*lazy_eval=*/i % 2 == 0);  // lazy and eager updates interleaved
    dirty_only.integrate(key, hit, /*lazy_eval=*/i % 3 != 0);
  }
  mixed.updateInnerOccupancy();
  dirty_only.updateDirtyInnerOccupancy();
  std::vector<Leaf> a, b, c;
  eager.forEachLeaf([&](const LeafView<16>& l) { a.push_back(asTuple(l)); });
  mixed.forEachLeaf([&](const LeafView<16>& l) { b.push_back(asTuple(l)); });
  dirty_only.forEachLeaf([&](const LeafView<16>& l) { c.push_back(asTuple(l)); });
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, c);
  EXPECT_EQ(eager.counts().nodes, dirty_only.counts().nodes);
  EXPECT_FLOAT_EQ(*eager.search(key16(0, 0, 0), 0), *dirty_only.search(key16(0, 0, 0), 0));
  EXPECT_FLOAT_EQ(*eager.search(key16(3, 3, 0), 10), *dirty_only.search(key16(3, 3, 0), 10));
}

}  // namespace
}  // namespace sonarmap
