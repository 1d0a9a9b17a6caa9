/// Tests of the map figures (map_figures.hpp): the slice's occupancy colours and track, the 3D
/// views' size, and the surface-error figure's colours from the evaluator's distances.

#include <gtest/gtest.h>

#include "sonarmap/render/figure.hpp"
#include "sonarmap/render/map_figures.hpp"

namespace sonarmap {
namespace {

constexpr double kVoxel_m = 0.1;

int countOf(const cv::Mat& image, const cv::Vec3b& colour) {
  int n = 0;
  for (auto it = image.begin<cv::Vec3b>(); it != image.end<cv::Vec3b>(); ++it) n += *it == colour ? 1 : 0;
  return n;
}

/// A 0.1 m map at z = 0.05: free x 0…8, y −5…4 and a wall of occupied voxels at x index 9.
OcTree16 wallMap() {
  OcTree16 map(kVoxel_m);
  auto key = [&](int i, int j) { return map.coder().keyOfChecked({(i + 0.5) * kVoxel_m, (j + 0.5) * kVoxel_m, 0.05}); };
  for (int j = -5; j < 5; ++j) {
    for (int i = 0; i < 9; ++i) map.updateNode(key(i, j), -2.0F);
    map.updateNode(key(9, j), 2.0F);
  }
  return map;
}

TEST(renderMapFigures, SliceFigureDrawsOccupiedInTheStrongColourAndTheTrack) {
  const OcTree16 map = wallMap();
  const cv::Mat plain = sliceFigure(map, 0.05, "wall");
  EXPECT_GE(std::max(plain.cols, plain.rows), kMinFigureLongSide_px);
  // The raster is 12 × 12 voxels (10 known plus the border): magnified 67 times.
  const FigureLayout layout = figureLayout(12, 12, true);
  ASSERT_EQ(layout.scale_x, 67);
  const int wall_pixels = 10 * 67 * 67;
  EXPECT_EQ(countOf(plain(layout.plot), kOccupiedBgr), wall_pixels);
  EXPECT_EQ(countOf(plain(layout.plot), kFreeBgr), 9 * 10 * 67 * 67);
  EXPECT_EQ(countOf(plain(layout.plot), kTrackBgr), 0);
  const cv::Mat tracked = sliceFigure(map, 0.05, "wall", {{0.1, -0.4, 0.0}, {0.1, 0.4, 0.0}, {0.5, 0.4, 0.0}});
  EXPECT_GT(countOf(tracked(layout.plot), kTrackBgr), 500);
}

TEST(renderMapFigures, ViewFiguresAreLargeAndCarryTheTrack) {
  const OcTree16 map = wallMap();
  for (const cv::Mat& figure : {topViewFigure(map, "top", {{0.1, -0.4, 0.05}, {0.1, 0.4, 0.05}}),
                                sideViewFigure(map, "side", {{0.1, -0.4, 0.05}, {0.5, -0.4, 0.05}})}) {
    EXPECT_GE(std::max(figure.cols, figure.rows), kMinFigureLongSide_px);
    EXPECT_GT(countOf(figure, kTrackBgr), 100);
  }
}

TEST(renderMapFigures, SurfaceErrorFigureColoursEachColumnByItsDistance) {
  const OcTree16 map = wallMap();
  Scene scene;
  scene.primitives.push_back(Plane{{1.05, 0.0, 0.0}, {1.0, 0.0, 0.0}, 0.9});  // the wall one voxel behind
  const GroundTruthReport report = evaluateAgainstScene(map, scene);
  ASSERT_EQ(report.occupied_errors.size(), 10U);
  for (const OccupiedVoxelError& voxel : report.occupied_errors) EXPECT_NEAR(voxel.distance_m, 0.1, 1e-9);
  const cv::Mat figure = surfaceErrorFigure(map, report, "errors");
  const FigureLayout layout = figureLayout(12, 12, true);
  const double scale_max = std::max(2.0 * report.tolerance_m, report.surface_error_p90_m);
  const cv::Vec3b expected = colourOnScale(cv::COLORMAP_TURBO, 0.1, 0.0, scale_max);
  EXPECT_EQ(countOf(figure(layout.plot), expected), 10 * 67 * 67);
  EXPECT_EQ(countOf(figure(layout.plot), kOccupiedBgr), 0);

  // A second layer of the wall: the side view is stacked under the top view, coloured alike.
  OcTree16 tall = map;
  for (int j = -5; j < 5; ++j) tall.updateNode(tall.coder().keyOfChecked({0.95, (j + 0.5) * kVoxel_m, 0.15}), 2.0F);
  const GroundTruthReport tall_report = evaluateAgainstScene(tall, scene);
  ASSERT_EQ(tall_report.occupied_errors.size(), 20U);
  const cv::Mat stacked = surfaceErrorFigure(tall, tall_report, "errors");
  EXPECT_GT(stacked.rows, figure.rows + 300);
  const cv::Vec3b tall_colour = colourOnScale(cv::COLORMAP_TURBO, 0.1, 0.0,
                                              std::max(2.0 * tall_report.tolerance_m, tall_report.surface_error_p90_m));
  EXPECT_GT(countOf(stacked(cv::Rect(0, figure.rows, stacked.cols, stacked.rows - figure.rows)), tall_colour), 1000)
      << "the wall in the side view";
}

}  // namespace
}  // namespace sonarmap
