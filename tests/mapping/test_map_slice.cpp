// Horizontal slices of a map: cells by class, pruned leaves expanded, the top-view image.
#include <gtest/gtest.h>

#include "sonarmap/mapping/map_slice.hpp"

namespace sonarmap {
namespace {

TEST(mappingSlice, CellsAndImageFollowTheMap) {
  OcTree16 map(0.1);
  map.integrate(*map.coder().keyOf({0.05, 0.05, 0.05}), true);    // occupied at (0.05, 0.05)
  map.integrate(*map.coder().keyOf({-0.25, 0.05, 0.05}), false);  // free at (-0.25, 0.05)
  map.integrate(*map.coder().keyOf({0.05, 0.05, 1.05}), true);    // another slice
  const auto occupied = cellsInSlice(map, 0.0, Occupancy::kOccupied);
  ASSERT_EQ(occupied.size(), 1U);
  EXPECT_NEAR(occupied[0].x(), 0.05, 1e-9);
  EXPECT_EQ(cellsInSlice(map, 0.0, Occupancy::kFree).size(), 1U);

  const cv::Mat image = renderSlice(map, 0.0);
  ASSERT_EQ(image.type(), CV_8U);
  EXPECT_EQ(image.cols, 4 + 2);  // x keys −3…0 plus a border
  EXPECT_EQ(image.rows, 1 + 2);
  EXPECT_EQ(image.at<unsigned char>(1, 4), 0);    // occupied, rightmost
  EXPECT_EQ(image.at<unsigned char>(1, 1), 255);  // free, leftmost
  EXPECT_EQ(image.at<unsigned char>(1, 2), 128);  // unknown between

  // Where it lies: column 0 is the border voxel left of x = −0.3 m, the last row the one below y = 0.
  const SliceView view = renderSliceView(map, 0.0);
  EXPECT_EQ(cv::countNonZero(view.image != image), 0);
  EXPECT_NEAR(view.left_m, -0.4, 1e-9);
  EXPECT_NEAR(view.bottom_m, -0.1, 1e-9);
  EXPECT_DOUBLE_EQ(view.pixel_m, 0.1);
}

TEST(mappingSlice, PrunedLeavesContributeEveryVoxel) {
  OcTree16 map(0.1);
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 4; ++z) map.integrate(*map.coder().keyOf({0.1 * x + 0.05, 0.1 * y + 0.05, 0.1 * z + 0.05}), false);
  EXPECT_EQ(map.counts().leaves, 1U);  // one pruned 4 × 4 × 4 leaf
  EXPECT_EQ(cellsInSlice(map, 0.15, Occupancy::kFree).size(), 16U);
  const cv::Mat image = renderSlice(map, 0.15);
  EXPECT_EQ(cv::countNonZero(image == 255), 16);
}

TEST(mappingSlice, EmptyMapAndOutOfMapSlice) {
  const OcTree16 map(0.1);
  EXPECT_EQ(renderSlice(map, 0.0).total(), 1U);
  EXPECT_THROW(cellsInSlice(map, 1.0e6, Occupancy::kFree), OutOfMapError);
}

}  // namespace
}  // namespace sonarmap
