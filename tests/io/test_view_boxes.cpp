// The boxes the 3D viewer draws: one per leaf of the class, pruned leaves at their real size, and
// beyond the cap the deepest octree level that fits.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <tuple>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/view_boxes.hpp"

namespace sonarmap {
namespace {

constexpr double kResolution_m = 0.1;

/// A `side`³ cube of occupied voxels from the origin, plus free voxels below it.
OcTree16 cubeTree(int side) {
  OcTree16 tree(kResolution_m);
  for (int x = 0; x < side; ++x) {
    for (int y = 0; y < side; ++y) {
      for (int z = 0; z < side; ++z) tree.integrate(*tree.coder().keyOf({0.1 * x + 0.05, 0.1 * y + 0.05, 0.1 * z + 0.05}), true);
      tree.integrate(*tree.coder().keyOf({0.1 * x + 0.05, 0.1 * y + 0.05, -0.05}), false);
    }
  }
  return tree;
}

/// Whether `leaf` lies inside `box` (the box is the leaf or one of its ancestors).
bool contains(const ViewBox& box, const ViewBox& leaf) {
  if (box.depth > leaf.depth) return false;
  const int shift = 16 - box.depth;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if ((leaf.key[axis] >> shift) != (box.key[axis] >> shift)) return false;
  }
  return true;
}

TEST(ioViewBoxes, EveryOccupiedLeafIsOneBox) {
  OcTree16 tree(kResolution_m);
  for (int i = 0; i < 5; ++i) tree.integrate(*tree.coder().keyOf({0.3 * i, 0.0, 1.0}), true);
  tree.integrate(*tree.coder().keyOf({0.0, 0.0, 0.0}), false);
  const ViewBoxes occupied = collectViewBoxes(tree, Occupancy::kOccupied, 100);
  EXPECT_EQ(occupied.leaves, 5U);
  EXPECT_EQ(occupied.boxes.size(), 5U);
  EXPECT_EQ(occupied.level, 16);
  EXPECT_FALSE(occupied.downsampled());
  for (const ViewBox& box : occupied.boxes) EXPECT_EQ(box.depth, 16);
  const ViewBoxes free = collectViewBoxes(tree, Occupancy::kFree, 100);
  EXPECT_EQ(free.leaves, 1U);
  ASSERT_EQ(free.boxes.size(), 1U);
  EXPECT_TRUE(boxCorner_m(tree, free.boxes[0]).isApprox(Eigen::Vector3d(0.0, 0.0, 0.0)));
  EXPECT_DOUBLE_EQ(boxEdge_m(tree, free.boxes[0]), kResolution_m);
}

TEST(ioViewBoxes, PrunedLeavesAreBoxesOfTheirRealSize) {
  const OcTree16 tree = cubeTree(2);  // 8 siblings from the origin: pruned into one depth-15 leaf
  const ViewBoxes occupied = collectViewBoxes(tree, Occupancy::kOccupied, 100);
  ASSERT_EQ(occupied.boxes.size(), 1U);
  EXPECT_EQ(occupied.leaves, 1U);
  EXPECT_EQ(occupied.boxes[0].depth, 15);
  EXPECT_EQ(occupied.level, 16) << "not downsampled: the tree itself pruned them";
  EXPECT_DOUBLE_EQ(boxEdge_m(tree, occupied.boxes[0]), 2 * kResolution_m);
  EXPECT_TRUE(boxCorner_m(tree, occupied.boxes[0]).isApprox(Eigen::Vector3d::Zero()));
}

TEST(ioViewBoxes, BeyondTheCapTheDeepestLevelThatFitsIsDrawn) {
  OcTree16 tree(kResolution_m);  // a diagonal of 64 voxels: nothing prunes
  for (int i = 0; i < 64; ++i) tree.integrate(*tree.coder().keyOf({0.1 * i + 0.05, 0.05, 0.05}), true);
  std::vector<ViewBox> leaves;
  tree.forEachLeaf([&](const LeafView<16>& leaf) {
    if (tree.model().isOccupied(leaf.log_odds)) leaves.push_back({leaf.key, leaf.depth});
  });
  const ViewBoxes full = collectViewBoxes(tree, Occupancy::kOccupied, 64);
  EXPECT_EQ(full.boxes.size(), 64U);
  EXPECT_FALSE(full.downsampled());
  // A row of 64 voxels along x: pruning collapses nothing (y and z neighbours are missing), so
  // depth 15 gives 32 boxes, 14 gives 16, 13 gives 8.
  const ViewBoxes coarse = collectViewBoxes(tree, Occupancy::kOccupied, 10);
  EXPECT_TRUE(coarse.downsampled());
  EXPECT_EQ(coarse.level, 13);
  EXPECT_EQ(coarse.boxes.size(), 8U);
  EXPECT_EQ(coarse.leaves, 64U);
  EXPECT_EQ(collectViewBoxes(tree, Occupancy::kOccupied, 16).level, 14);
  EXPECT_EQ(collectViewBoxes(tree, Occupancy::kOccupied, 1).boxes.size(), 1U);
  // Every leaf lies in exactly one box; every box holds a leaf.
  for (const ViewBox& leaf : leaves) {
    EXPECT_EQ(std::count_if(coarse.boxes.begin(), coarse.boxes.end(), [&](const ViewBox& box) { return contains(box, leaf); }), 1);
  }
  for (const ViewBox& box : coarse.boxes) {
    EXPECT_TRUE(std::any_of(leaves.begin(), leaves.end(), [&](const ViewBox& leaf) { return contains(box, leaf); }));
    EXPECT_DOUBLE_EQ(boxEdge_m(tree, box), 8 * kResolution_m);
  }
}

TEST(ioViewBoxes, DownsamplingKeepsCoarserPrunedLeavesAndNeverOverlaps) {
  OcTree16 tree = cubeTree(4);  // one depth-14 leaf (4 voxels wide) after pruning
  for (int i = 0; i < 12; ++i) tree.integrate(*tree.coder().keyOf({-0.1 * i - 0.05, -0.05, 0.05}), true);
  const ViewBoxes all = collectViewBoxes(tree, Occupancy::kOccupied, 1000);
  EXPECT_EQ(all.leaves, 13U);
  const ViewBoxes coarse = collectViewBoxes(tree, Occupancy::kOccupied, 5);
  ASSERT_TRUE(coarse.downsampled());
  EXPECT_LE(coarse.boxes.size(), 5U);
  for (std::size_t a = 0; a < coarse.boxes.size(); ++a) {
    for (std::size_t b = 0; b < coarse.boxes.size(); ++b) {
      if (a != b) {
        EXPECT_FALSE(contains(coarse.boxes[a], coarse.boxes[b])) << a << " overlaps " << b;
      }
    }
  }
  // The same input gives the same boxes in the same order.
  const ViewBoxes again = collectViewBoxes(tree, Occupancy::kOccupied, 5);
  ASSERT_EQ(again.boxes.size(), coarse.boxes.size());
  for (std::size_t i = 0; i < again.boxes.size(); ++i) EXPECT_EQ(again.boxes[i].key, coarse.boxes[i].key);
}

TEST(ioViewBoxes, EmptyMapAndBadArguments) {
  const OcTree16 empty(kResolution_m);
  const ViewBoxes none = collectViewBoxes(empty, Occupancy::kOccupied, 10);
  EXPECT_TRUE(none.boxes.empty());
  EXPECT_EQ(none.leaves, 0U);
  EXPECT_THROW(collectViewBoxes(empty, Occupancy::kOccupied, 0), ValueError);
  EXPECT_THROW(collectViewBoxes(empty, Occupancy::kUnknown, 10), ValueError);
}

}  // namespace
}  // namespace sonarmap
