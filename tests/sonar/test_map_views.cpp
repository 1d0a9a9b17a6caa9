/// Tests of the map views: the top view coloured by height, the side view coloured by the nearest
/// y, their colours for free and unknown pixels, pruned leaves, and the occupied height extent.

#include <gtest/gtest.h>

#include "sonarmap/sonar/map_views.hpp"
#include "sonarmap/sonar/png_writer.hpp"

namespace sonarmap {
namespace {

constexpr double kVoxel_m = 0.1;

/// A 0.1 m map (voxel index i has its centre at (i + 0.5) · 0.1 m): a floor at z index −5 under
/// x 0…9, y 0…4; a wall at x index 9, y 2…4, z −5…4; water (free) at x 0…8, y 0…4, z −4…2; and a
/// free strip at y 5, x 0…8, z 0 with nothing under it.
OcTree16 pool(bool prune) {
  OctreeOptions options;
  options.prune = prune;
  OcTree16 map(kVoxel_m, options);
  const auto key = [&](int i, int j, int k) {
    return map.coder().keyOfChecked({(i + 0.5) * kVoxel_m, (j + 0.5) * kVoxel_m, (k + 0.5) * kVoxel_m});
  };
  for (int i = 0; i <= 9; ++i)
    for (int j = 0; j <= 4; ++j) map.integrate(key(i, j, -5), true);
  for (int j = 2; j <= 4; ++j)
    for (int k = -5; k <= 4; ++k) map.integrate(key(9, j, k), true);
  for (int i = 0; i <= 8; ++i) {
    for (int j = 0; j <= 4; ++j)
      for (int k = -4; k <= 2; ++k) map.integrate(key(i, j, k), false);
    map.integrate(key(i, 5, 0), false);
  }
  return map;
}

const cv::Vec3b kWhite(255, 255, 255);
const cv::Vec3b kGrey(kFreeGrey, kFreeGrey, kFreeGrey);
const cv::Vec3b kFrame(kFrameGrey, kFrameGrey, kFrameGrey);

TEST(sonarMapViews, TopViewShowsEachColumnsHighestOccupiedVoxelByHeight) {
  const MapView view = renderTopView(pool(true));
  // x 0…9 and y 0…5 plus the border.
  ASSERT_EQ(view.view_cols, 12);
  ASSERT_EQ(view.view_rows, 8);
  // Its edges in metres: x index 0 starts at 0 m, y index 0 at 0 m; one border voxel before each.
  EXPECT_NEAR(view.left_m, -kVoxel_m, 1e-9);
  EXPECT_NEAR(view.bottom_m, -kVoxel_m, 1e-9);
  EXPECT_DOUBLE_EQ(view.voxel_m, kVoxel_m);
  EXPECT_EQ(view.image.type(), CV_8UC3);
  EXPECT_EQ(view.image.cols, 12 + kLegendCols);
  EXPECT_EQ(view.image.rows, kLegendMinRows);
  EXPECT_EQ(view.occupied_pixels, 50U);  // the floor's columns, the wall's among them
  EXPECT_DOUBLE_EQ(view.scale_min_m, -0.45);
  EXPECT_DOUBLE_EQ(view.scale_max_m, 0.45);
  // Pixel of column (i, j): image column i + 1, row 8 − 1 − (j + 1) (+y up).
  const auto at = [&](int i, int j) { return view.image.at<cv::Vec3b>(6 - j, i + 1); };
  EXPECT_EQ(at(9, 3), scaleColour(0.45, -0.45, 0.45));   // the wall's top
  EXPECT_EQ(at(9, 0), scaleColour(-0.45, -0.45, 0.45));  // the floor in front of the wall's end
  EXPECT_EQ(at(3, 2), scaleColour(-0.45, -0.45, 0.45));  // the floor under the water
  EXPECT_NE(at(9, 3), at(3, 2));
  EXPECT_EQ(at(3, 5), kGrey);   // free, nothing occupied under it
  EXPECT_EQ(at(9, 5), kWhite);  // unknown
  EXPECT_EQ(view.image.at<cv::Vec3b>(0, 0), kFrame);
  EXPECT_EQ(view.image.at<cv::Vec3b>(7, 11), kFrame);
  EXPECT_EQ(view.image.at<cv::Vec3b>(kLegendMinRows - 1, 5), kWhite);  // below the view, beside the legend
  EXPECT_FALSE(encodePng(view.image).empty());
}

TEST(sonarMapViews, SideViewShowsTheNearestOccupiedVoxelAlongY) {
  const MapView view = renderSideView(pool(true));
  // x 0…9 and z −5…4 plus the border.
  ASSERT_EQ(view.view_cols, 12);
  ASSERT_EQ(view.view_rows, 12);
  EXPECT_EQ(view.occupied_pixels, 10U + 9U);  // the floor's row, the wall's column above it
  EXPECT_DOUBLE_EQ(view.scale_min_m, 0.05);   // the floor from y index 0
  EXPECT_DOUBLE_EQ(view.scale_max_m, 0.25);   // the wall from y index 2
  // Pixel (i, k): image column i + 1, row 12 − 1 − (k + 5 + 1) (+z up).
  const auto at = [&](int i, int k) { return view.image.at<cv::Vec3b>(5 - k, i + 1); };
  EXPECT_EQ(at(9, 4), scaleColour(0.25, 0.05, 0.25));   // the wall's top
  EXPECT_EQ(at(9, -5), scaleColour(0.05, 0.05, 0.25));  // the floor is nearer than the wall's foot
  EXPECT_EQ(at(3, -5), scaleColour(0.05, 0.05, 0.25));
  EXPECT_EQ(at(3, 0), kGrey);   // water
  EXPECT_EQ(at(3, 4), kWhite);  // above the water: unknown
}

TEST(sonarMapViews, PrunedLeavesDrawAsTheirVoxels) {
  const OcTree16 pruned = pool(true), unpruned = pool(false);
  ASSERT_LT(pruned.counts().leaves, unpruned.counts().leaves);
  for (const auto render : {&renderTopView, &renderSideView}) {
    const cv::Mat a = render(pruned, 0).image, b = render(unpruned, 0).image;
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  }
}

TEST(sonarMapViews, MagnifiedViewDrawsEachVoxelAsASquare) {
  const OcTree16 map = pool(true);
  const MapView plain = renderTopView(map), big = renderTopView(map, 50);  // 12 × 8 voxels: 4 pixels each
  EXPECT_EQ(plain.pixels_per_voxel, 1);
  ASSERT_EQ(big.pixels_per_voxel, 4);
  EXPECT_EQ(big.view_cols, 48);
  EXPECT_EQ(big.view_rows, 32);
  EXPECT_EQ(big.image.cols, 48 + kLegendCols);
  EXPECT_EQ(big.occupied_pixels, plain.occupied_pixels);  // voxels, not screen pixels
  for (int row = 1; row < 7; ++row) {
    for (int col = 1; col < 11; ++col) {
      for (const int d : {0, 3}) {
        EXPECT_EQ(big.image.at<cv::Vec3b>(row * 4 + d, col * 4 + 3 - d), plain.image.at<cv::Vec3b>(row, col))
            << row << ", " << col;
      }
    }
  }
  EXPECT_EQ(renderSideView(map, 10000).pixels_per_voxel, kMaxPixelsPerVoxel);
  EXPECT_EQ(renderSideView(map, 5).pixels_per_voxel, 1);
}

TEST(sonarMapViews, HeightExtentOfTheOccupiedVoxels) {
  const std::optional<HeightExtent> extent = occupiedHeightExtent(pool(true));
  ASSERT_TRUE(extent.has_value());
  EXPECT_DOUBLE_EQ(extent->min_m, -0.45);
  EXPECT_DOUBLE_EQ(extent->max_m, 0.45);
  OcTree16 water(kVoxel_m);
  EXPECT_FALSE(occupiedHeightExtent(water).has_value());
  water.integrate(water.coder().keyOfChecked({0.05, 0.05, 0.05}), false);
  EXPECT_FALSE(occupiedHeightExtent(water).has_value());
}

TEST(sonarMapViews, EmptyMapGivesAnEmptyFramedViewAndALegend) {
  const MapView view = renderTopView(OcTree16(kVoxel_m));
  EXPECT_EQ(view.view_cols, 3);
  EXPECT_EQ(view.view_rows, 3);
  EXPECT_EQ(view.occupied_pixels, 0U);
  EXPECT_EQ(view.image.at<cv::Vec3b>(1, 1), kWhite);
  EXPECT_EQ(view.image.rows, kLegendMinRows);
  EXPECT_FALSE(encodePng(view.image).empty());
}

TEST(sonarMapViews, ScaleColourRunsFromViridisLowToHigh) {
  const cv::Vec3b low = scaleColour(0.0, 0.0, 1.0), high = scaleColour(1.0, 0.0, 1.0);
  EXPECT_LT(low[1], high[1]);  // dark violet to yellow: green rises
  EXPECT_GT(low[0], low[1]);   // violet: more blue than green
  EXPECT_GT(high[2], high[0]);  // yellow: more red than blue
  EXPECT_EQ(scaleColour(-5.0, 0.0, 1.0), low);  // clamped
  EXPECT_EQ(scaleColour(0.3, 0.3, 0.3), scaleColour(0.5, 0.0, 1.0));  // one value: the middle
}

}  // namespace
}  // namespace sonarmap
