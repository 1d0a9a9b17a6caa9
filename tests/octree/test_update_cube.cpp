// updateCube against the voxel-by-voxel updates it stands for: on unknown space, pruned leaves,
// partly known subtrees and finest voxels, the trees after synchronisation are identical.
#include <gtest/gtest.h>

#include <random>
#include <utility>
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

/// Synchronises both trees' inner nodes and lists their leaves, for comparison.
std::pair<std::vector<Leaf>, std::vector<Leaf>> syncedLeaves(OcTree16& a, OcTree16& b) {
  a.updateDirtyInnerOccupancy();
  b.updateDirtyInnerOccupancy();
  return {leavesOf(a), leavesOf(b)};
}

/// A tree with scattered voxels, a solid block pruned to coarse leaves, and a few inner nodes.
void fillSample(OcTree16& tree, std::mt19937& rng) {
  std::uniform_int_distribution<int> coord(-12, 12);
  for (int i = 0; i < 3000; ++i) tree.integrate(key16(coord(rng), coord(rng), coord(rng)), i % 4 == 0);
  for (int x = 16; x < 24; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 8; ++z) tree.integrate(key16(x, y, z), false);
  tree.updateInnerOccupancy();
}

class UpdateCube : public ::testing::TestWithParam<bool> {};  // stability check on / off

TEST_P(UpdateCube, EqualsUpdatingEveryVoxelOfTheCube) {
  const OctreeOptions options{.stability_check = GetParam()};
  OcTree16 by_cube(0.05, options), by_voxel(0.05, options);
  std::mt19937 rng(11);
  fillSample(by_cube, rng);
  rng.seed(11);
  fillSample(by_voxel, rng);
  ASSERT_EQ(leavesOf(by_cube), leavesOf(by_voxel));

  std::uniform_int_distribution<int> coord(-16, 28);
  std::uniform_int_distribution<int> levels(0, 3);
  for (int i = 0; i < 400; ++i) {
    const Key16 key = key16(coord(rng), coord(rng), coord(rng) / 2);
    const int up = levels(rng);
    const float delta = i % 3 == 0 ? by_cube.model().hit : by_cube.model().miss;
    by_cube.updateCube(key, 16 - up, delta);
    const std::uint16_t mask = static_cast<std::uint16_t>(~((1U << up) - 1U));
    for (unsigned x = 0; x < (1U << up); ++x)
      for (unsigned y = 0; y < (1U << up); ++y)
        for (unsigned z = 0; z < (1U << up); ++z) {
          by_voxel.updateNode(Key16{{static_cast<std::uint16_t>((key[0] & mask) | x),
                                     static_cast<std::uint16_t>((key[1] & mask) | y),
                                     static_cast<std::uint16_t>((key[2] & mask) | z)}},
                              delta, /*lazy_eval=*/true);
        }
    if (i % 50 == 49) {  // sync now and then, so later cubes meet pruned leaves too
      const auto [mine, reference] = syncedLeaves(by_cube, by_voxel);
      ASSERT_EQ(mine, reference) << "after cube " << i;
    }
  }
  const auto [mine, reference] = syncedLeaves(by_cube, by_voxel);
  EXPECT_EQ(mine, reference);
  EXPECT_EQ(by_cube.counts().nodes, by_voxel.counts().nodes);
  EXPECT_EQ(*by_cube.search(key16(0, 0, 0), 0), *by_voxel.search(key16(0, 0, 0), 0));
}

TEST_P(UpdateCube, BricksEqualUpdatingTheirVoxels) {
  const OctreeOptions options{.stability_check = GetParam()};
  OcTree16 by_brick(0.05, options), by_voxel(0.05, options);
  std::mt19937 rng(5);
  fillSample(by_brick, rng);
  rng.seed(5);
  fillSample(by_voxel, rng);
  std::uniform_int_distribution<int> coord(-20, 40);
  std::uniform_int_distribution<unsigned> octet(0, 255);
  for (int i = 0; i < 600; ++i) {
    const Key16 corner = key16(coord(rng), coord(rng), coord(rng) / 2);
    std::uint64_t voxels = 0;
    for (unsigned k = 0; k < 8; ++k) {  // empty, full and mixed octets, a full brick now and then
      const unsigned kind = octet(rng) % 4;
      const std::uint64_t bits = kind == 0 ? 0 : kind == 1 ? 0xFF : octet(rng);
      voxels |= bits << (8 * k);
    }
    if (i % 10 == 0) voxels = ~std::uint64_t{0};
    const float delta = i % 4 == 0 ? by_brick.model().hit : by_brick.model().miss;
    by_brick.updateBrick(corner, voxels, delta);
    for (unsigned b = 0; b < 64; ++b) {
      if (((voxels >> b) & 1U) == 0) continue;
      Key16 key;
      for (unsigned axis = 0; axis < 3; ++axis) {
        const unsigned low = ((b >> axis) & 1U) | (((b >> (axis + 3)) & 1U) << 1);
        key[axis] = static_cast<std::uint16_t>((corner[axis] & ~3U) | low);
      }
      by_voxel.updateNode(key, delta, /*lazy_eval=*/true);
    }
    if (i % 75 == 74) {
      const auto [mine, reference] = syncedLeaves(by_brick, by_voxel);
      ASSERT_EQ(mine, reference) << "after brick " << i;
    }
  }
  const auto [mine, reference] = syncedLeaves(by_brick, by_voxel);
  EXPECT_EQ(mine, reference);
  EXPECT_EQ(by_brick.counts().nodes, by_voxel.counts().nodes);
}

INSTANTIATE_TEST_SUITE_P(octree, UpdateCube, ::testing::Bool());

TEST(octreeUpdateCube, UnknownSpaceBecomesOneLeaf) {
  OcTree16 tree(0.05);
  tree.updateCube(key16(5, 6, 7), 14, tree.model().miss);  // the 4 × 4 × 4 block holding (5, 6, 7)
  tree.updateDirtyInnerOccupancy();
  const std::vector<Leaf> leaves = leavesOf(tree);
  ASSERT_EQ(leaves.size(), 1U);
  EXPECT_EQ(std::get<3>(leaves[0]), 14);
  EXPECT_EQ(std::get<0>(leaves[0]), 32768 + 4);
  EXPECT_EQ(tree.occupancyOf(key16(4, 7, 4)), Occupancy::kFree);
  EXPECT_EQ(tree.occupancyOf(key16(8, 4, 4)), Occupancy::kUnknown);
}

TEST(octreeUpdateCube, WithoutPruningOrWithChangeDetectionEveryVoxelIsALeaf) {
  OcTree16 unpruned(0.05, OctreeOptions{.prune = false});
  unpruned.updateCube(key16(0, 0, 0), 15, unpruned.model().miss);
  unpruned.updateDirtyInnerOccupancy();
  EXPECT_EQ(unpruned.counts().leaves, 8U);

  OcTree16 detecting(0.05);
  detecting.enableChangeDetection(true);
  detecting.updateCube(key16(0, 0, 0), 14, detecting.model().hit);
  EXPECT_EQ(detecting.numChangesDetected(), 64U);
  EXPECT_THROW(unpruned.updateCube(key16(0, 0, 0), 2, unpruned.model().miss), ValueError);
}

TEST(octreeUpdateCube, BricksRecordTheSameChangesAsSingleVoxels) {
  OcTree16 by_brick(0.05), by_voxel(0.05);
  by_brick.enableChangeDetection(true);
  by_voxel.enableChangeDetection(true);
  const std::uint64_t voxels = 0x00FF00000000F00FULL;  // one whole octet, two partial ones
  by_brick.updateBrick(key16(8, 8, 8), voxels, by_brick.model().miss);
  for (unsigned b = 0; b < 64; ++b) {
    if (((voxels >> b) & 1U) == 0) continue;
    const int x = static_cast<int>(((b >> 0) & 1U) | (((b >> 3) & 1U) << 1));
    const int y = static_cast<int>(((b >> 1) & 1U) | (((b >> 4) & 1U) << 1));
    const int z = static_cast<int>(((b >> 2) & 1U) | (((b >> 5) & 1U) << 1));
    by_voxel.updateNode(key16(8 + x, 8 + y, 8 + z), by_voxel.model().miss, /*lazy_eval=*/true);
  }
  EXPECT_EQ(by_brick.numChangesDetected(), 16U);
  EXPECT_EQ(by_brick.changedKeys(), by_voxel.changedKeys());
  const auto [mine, reference] = syncedLeaves(by_brick, by_voxel);
  EXPECT_EQ(mine, reference);
}

}  // namespace
}  // namespace sonarmap
