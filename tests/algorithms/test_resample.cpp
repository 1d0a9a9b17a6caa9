// resampledMap: a map copied to a coarser resolution keeps what it knew, the maximum of the leaves
// in each new voxel (occupied wins), unknown stays unknown, and the same map gives the same tree.
#include <gtest/gtest.h>

#include "sonarmap/algorithms/resample.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

TEST(algorithmsResample, KeepsTheMaximumPerVoxelAndTheUnknown) {
  OcTree16 map(0.01);
  const auto key = [&](double x, double y, double z) { return map.coder().keyOfChecked({x, y, z}); };
  // A free block of 10 × 10 × 1 voxels with one occupied voxel inside; a lone free voxel far away.
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) map.integrate(key(0.005 + 0.01 * i, 0.005 + 0.01 * j, 0.005), false);
  }
  map.integrate(key(0.055, 0.055, 0.005), true);
  map.integrate(key(1.005, 0.005, 0.005), false);
  for (const double resolution_m : {0.02, 0.05}) {
    const OcTree16 coarse = resampledMap(map, resolution_m);
    EXPECT_DOUBLE_EQ(coarse.resolution_m(), resolution_m);
    EXPECT_EQ(coarse.occupancyAt({0.055, 0.055, 0.005}), Occupancy::kOccupied) << resolution_m;
    EXPECT_EQ(coarse.occupancyAt({0.005, 0.095, 0.005}), Occupancy::kFree) << resolution_m;
    EXPECT_EQ(coarse.occupancyAt({0.5, 0.5, 0.005}), Occupancy::kUnknown) << resolution_m;
    EXPECT_EQ(coarse.occupancyAt({1.005, 0.005, 0.005}), Occupancy::kFree) << resolution_m;
    // The occupied voxel's log-odds, not a blend with its free neighbours.
    EXPECT_FLOAT_EQ(*coarse.search(coarse.coder().keyOfChecked({0.055, 0.055, 0.005})),
                    *map.search(key(0.055, 0.055, 0.005)));
  }
  // The same input, the same tree: every leaf equal.
  const OcTree16 a = resampledMap(map, 0.05), b = resampledMap(map, 0.05);
  EXPECT_EQ(a.counts().leaves, b.counts().leaves);
  EXPECT_EQ(a.memoryBytes(), b.memoryBytes());
}

TEST(algorithmsResample, APrunedLeafFillsEveryNewVoxelItCovers) {
  OcTree16 map(0.01);
  // 16 × 16 × 16 free voxels: pruned into one leaf of 16 cm.
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      for (int k = 0; k < 16; ++k) {
        map.integrate(map.coder().keyOfChecked({0.005 + 0.01 * i, 0.005 + 0.01 * j, 0.005 + 0.01 * k}), false);
      }
    }
  }
  ASSERT_LT(map.counts().leaves, 10U);
  const OcTree16 coarse = resampledMap(map, 0.04);
  for (const double x : {0.02, 0.06, 0.10, 0.14}) EXPECT_EQ(coarse.occupancyAt({x, 0.14, 0.02}), Occupancy::kFree) << x;
  EXPECT_EQ(coarse.occupancyAt({0.18, 0.02, 0.02}), Occupancy::kUnknown);
}

TEST(algorithmsResample, RefusesAFinerResolution) {
  const OcTree16 map(0.05);
  EXPECT_THROW(resampledMap(map, 0.02), ValueError);
  EXPECT_THROW(resampledMap(map, std::nan("")), ValueError);
}

}  // namespace
}  // namespace sonarmap
