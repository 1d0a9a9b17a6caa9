/// Tests of the point figures (point_figures.hpp): a panel's track from a navigation track, the
/// cells' grey levels by their points, the panels side by side on one extent, and a cell too fine
/// for the extent coarsened.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/render/figure.hpp"
#include "sonarmap/render/point_figures.hpp"

namespace sonarmap {
namespace {

/// One point at the origin and eight at (north 1, east 2): on 0.5 m cells a raster of 3 rows × 5
/// columns, the lone point in the bottom-left cell, the eight in the top-right one.
PointPanel twoCorners(const std::string& title) {
  PointPanel panel;
  panel.title = title;
  panel.points_ned_m.emplace_back(0.0, 0.0);
  for (int i = 0; i < 8; ++i) panel.points_ned_m.emplace_back(1.0, 2.0);
  return panel;
}

/// The figure's pixel at the centre of raster cell (row, col) of its first panel.
cv::Vec3b cellColour(const cv::Mat& figure, const FigureLayout& layout, int row, int col) {
  return figure.at<cv::Vec3b>(layout.plot.y + row * layout.scale_y + layout.scale_y / 2,
                              layout.plot.x + col * layout.scale_x + layout.scale_x / 2);
}

TEST(renderPointFigures, APanelsTrackIsTheFixesHorizontalPositions) {
  NavTrack track(2);
  track[0].position_ned_m = {1.0, 2.0, 3.0};
  track[1].position_ned_m = {-4.0, 5.0, 6.0};
  const PointPanel panel = pointPanel("title", {{0.5, 0.5}}, track);
  EXPECT_EQ(panel.title, "title");
  ASSERT_EQ(panel.points_ned_m.size(), 1U);
  ASSERT_EQ(panel.track_ned_m.size(), 2U);
  EXPECT_EQ(panel.track_ned_m[1], Eigen::Vector2d(-4.0, 5.0));
}

TEST(renderPointFigures, ACellIsDarkerTheMorePointsFallInIt) {
  const cv::Mat figure = pointPanelsFigure({twoCorners("corners")}, 0.5);
  const FigureLayout layout = figureLayout(3, 5, true);
  ASSERT_EQ(layout.plot.width, 5 * layout.scale_x);
  EXPECT_EQ(cellColour(figure, layout, 2, 0), cv::Vec3b(200, 200, 200)) << "one point: light grey";
  EXPECT_EQ(cellColour(figure, layout, 0, 4), cv::Vec3b(0, 0, 0)) << "eight points: black";
  EXPECT_EQ(cellColour(figure, layout, 1, 2), cv::Vec3b(255, 255, 255)) << "no point: white";
}

TEST(renderPointFigures, PanelsStandSideBySideOnOneExtent) {
  const cv::Mat one = pointPanelsFigure({twoCorners("a")}, 0.5);
  PointPanel inside = twoCorners("b");
  inside.points_ned_m = {{0.5, 1.0}};  // within the first panel's extent: the extent is unchanged
  const cv::Mat two = pointPanelsFigure({twoCorners("a"), inside}, 0.5);
  EXPECT_EQ(two.rows, one.rows);
  EXPECT_EQ(two.cols, 2 * one.cols);
  // The second panel's lone point in its middle cell (row 1, column 2), nothing in its corners.
  const FigureLayout layout = figureLayout(3, 5, true);
  const cv::Mat second = two.colRange(one.cols, two.cols);
  EXPECT_EQ(cellColour(second, layout, 1, 2), cv::Vec3b(200, 200, 200));
  EXPECT_EQ(cellColour(second, layout, 0, 4), cv::Vec3b(255, 255, 255));
}

TEST(renderPointFigures, ACellTooFineForTheExtentIsCoarsened) {
  EXPECT_DOUBLE_EQ(pointFigureCell({twoCorners("a")}, 0.25), 0.25);
  PointPanel far = twoCorners("far");
  far.points_ned_m.emplace_back(0.0, 10000.0);  // one point 10 km east
  const double cell_m = pointFigureCell({far}, 0.25);
  EXPECT_GT(cell_m, 0.25);
  EXPECT_LE(std::ceil(10000.0 / cell_m) + 1, kMaxPointPanelCells);
  const cv::Mat figure = pointPanelsFigure({far}, 0.25);
  EXPECT_LT(figure.cols, 2 * kMaxPointPanelCells);
}

TEST(renderPointFigures, NothingToDrawIsRefused) {
  EXPECT_THROW(pointPanelsFigure({}, 0.25), ValueError);
  EXPECT_THROW(pointPanelsFigure({PointPanel{}}, 0.25), ValueError);
  EXPECT_THROW(pointPanelsFigure({twoCorners("a")}, 0.0), ValueError);
  EXPECT_THROW(pointPanelsFigure({twoCorners("a")}, std::nan("")), ValueError);
}

}  // namespace
}  // namespace sonarmap
