/// Tests of the figure layer (figure.hpp): the magnification to >= 800 pixels, the plot area
/// holding the raster pixel for pixel, the title and axes drawn around it, the lines, the ticks,
/// and the polar figure's rows ordered by bearing (sonar_figures.hpp).

#include <gtest/gtest.h>

#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/render/figure.hpp"
#include "sonarmap/render/sonar_figures.hpp"

namespace sonarmap {
namespace {

const cv::Vec3b kWhite(255, 255, 255);

/// Pixels of `area` of `image` that are not white.
int inkIn(const cv::Mat& image, const cv::Rect& area) {
  int ink = 0;
  for (int row = area.y; row < area.y + area.height; ++row)
    for (int col = area.x; col < area.x + area.width; ++col) ink += image.at<cv::Vec3b>(row, col) != kWhite ? 1 : 0;
  return ink;
}

int countOf(const cv::Mat& image, const cv::Rect& area, const cv::Vec3b& colour) {
  int n = 0;
  for (int row = area.y; row < area.y + area.height; ++row)
    for (int col = area.x; col < area.x + area.width; ++col) n += image.at<cv::Vec3b>(row, col) == colour ? 1 : 0;
  return n;
}

TEST(renderFigure, LayoutMagnifiesByWholePixelsToTheLongSide) {
  const FigureLayout tank = figureLayout(224, 214, true);  // the tank map, one pixel per voxel
  EXPECT_EQ(tank.scale_x, 4);
  EXPECT_EQ(tank.scale_y, 4);
  EXPECT_GE(std::max(tank.plot.width, tank.plot.height), kMinFigureLongSide_px);
  EXPECT_EQ(tank.plot.width, 214 * 4);
  const FigureLayout large = figureLayout(900, 1200, true);  // never shrunk
  EXPECT_EQ(large.scale_x, 1);
  EXPECT_EQ(large.plot.size(), cv::Size(1200, 900));
  const FigureLayout sector = figureLayout(28, 399, false);  // a 28-beam sector's polar image
  EXPECT_EQ(sector.scale_x, 3);
  EXPECT_EQ(sector.scale_y, 18);
  EXPECT_GE(sector.plot.height, kMinFigureShortSide_px);
  EXPECT_THROW(figureLayout(0, 5, true), ValueError);
}

TEST(renderFigure, ComposesTheRasterWithTitleAxesLegendAndLines) {
  cv::Mat raster(20, 40, CV_8UC3, cv::Scalar(200, 200, 200));
  raster(cv::Rect(10, 5, 3, 2)).setTo(cv::Scalar(25, 25, 25));
  FigureSpec spec;
  spec.raster = raster;
  spec.extent = {-1.0, 3.0, 0.0, 2.0};  // 0.1 m pixels
  spec.title = "input.mat  |  0.1 m voxels";
  spec.x_label = "x (m)";
  spec.y_label = "y (m)";
  spec.swatches = {{kOccupiedBgr, "occupied"}, {kFreeBgr, "free"}};
  spec.colour_bar = ColourBar{cv::COLORMAP_VIRIDIS, 0.0, 2.0, "z (m)", false};
  spec.lines = {FigureLine{{{-0.5, 0.5}, {2.5, 0.5}}, kTrackBgr, "track"}};
  const cv::Mat figure = composeFigure(spec);
  ASSERT_EQ(figure.type(), CV_8UC3);
  const FigureLayout layout = figureLayout(20, 40, true);
  ASSERT_EQ(layout.scale_x, 20);
  const cv::Rect plot = layout.plot;
  EXPECT_GE(figure.cols, plot.x + plot.width);
  EXPECT_GE(std::max(figure.cols, figure.rows), kMinFigureLongSide_px);
  // Nearest-neighbour: raster pixel (row 5, col 10) fills a 20 × 20 block.
  EXPECT_EQ(figure.at<cv::Vec3b>(plot.y + 5 * 20, plot.x + 10 * 20), kOccupiedBgr);
  EXPECT_EQ(figure.at<cv::Vec3b>(plot.y + 6 * 20 + 19, plot.x + 12 * 20 + 19), kOccupiedBgr);
  EXPECT_EQ(figure.at<cv::Vec3b>(plot.y + 7 * 20, plot.x + 10 * 20), kFreeBgr);
  // The title band, the x tick labels under the plot, the y tick labels left of it: ink.
  EXPECT_GT(inkIn(figure, cv::Rect(0, 0, figure.cols, plot.y)), 200);
  EXPECT_GT(inkIn(figure, cv::Rect(plot.x, plot.y + plot.height + 2, plot.width, 50)), 200);
  EXPECT_GT(inkIn(figure, cv::Rect(0, plot.y, plot.x - 2, plot.height)), 200);
  // The legend right of the plot: the swatches' colours and the colour bar.
  const cv::Rect legend(plot.x + plot.width + 2, 0, figure.cols - plot.x - plot.width - 2, figure.rows);
  EXPECT_GT(countOf(figure, legend, kOccupiedBgr), 100);
  // The track along y = 0.5 m: raster row 15 from the top, x from −0.5 to 2.5 m.
  const int track_row = plot.y + 15 * 20;
  EXPECT_EQ(figure.at<cv::Vec3b>(track_row, plot.x + 200), kTrackBgr);
  EXPECT_GT(countOf(figure, cv::Rect(plot.x, track_row - 2, plot.width, 5), kTrackBgr), 2 * 500);

  FigureSpec empty = spec;
  empty.raster = cv::Mat();
  EXPECT_THROW(composeFigure(empty), ValueError);
  FigureSpec flipped = spec;
  flipped.extent = {3.0, -1.0, 0.0, 2.0};
  EXPECT_THROW(composeFigure(flipped), ValueError);
}

TEST(renderFigure, TicksAreNiceSteps) {
  EXPECT_EQ(niceTicks(0.0, 4.3, 5), (std::vector<double>{0.0, 1.0, 2.0, 3.0, 4.0}));
  // 0.26 / 5 = 0.052: the next nice step is 0.1.
  EXPECT_EQ(niceTicks(-0.13, 0.13, 5), (std::vector<double>{-0.1, 0.0, 0.1}));
  EXPECT_EQ(niceTicks(-0.13, 0.13, 10), (std::vector<double>{-0.1, -0.05, 0.0, 0.05, 0.1}));
  EXPECT_GE(niceTicks(1.01, 1.02, 5).size(), 2U);
}

TEST(renderFigure, PolarFigureOrdersRowsByBearingAcrossZero) {
  // Three beams at 350°, 0° and 10°: intensities 50, 150, 250.
  PolarImage polar;
  polar.intensities = cv::Mat(3, 100, CV_8U);
  polar.intensities.row(0).setTo(50);
  polar.intensities.row(1).setTo(150);
  polar.intensities.row(2).setTo(250);
  polar.bin_length_m = 0.05;
  constexpr double kDeg = std::numbers::pi / 180.0;
  polar.bearing_rad = {350.0 * kDeg, 0.0, 10.0 * kDeg};
  polar.valid_bins = {100, 100, 100};
  const cv::Mat figure = polarFigure(polar, "sector");
  const FigureLayout layout = figureLayout(3, 100, false);
  EXPECT_GE(layout.plot.height, kMinFigureShortSide_px);
  EXPECT_GE(figure.cols, kMinFigureLongSide_px);
  const cv::Rect& plot = layout.plot;
  auto at = [&](int raster_row) {
    return figure.at<cv::Vec3b>(plot.y + raster_row * layout.scale_y + layout.scale_y / 2, plot.x + plot.width / 2);
  };
  EXPECT_EQ(at(0), colourOnScale(cv::COLORMAP_INFERNO, 250, 0, 255));  // 10° on top
  EXPECT_EQ(at(1), colourOnScale(cv::COLORMAP_INFERNO, 150, 0, 255));
  EXPECT_EQ(at(2), colourOnScale(cv::COLORMAP_INFERNO, 50, 0, 255));   // −10° at the bottom
  polar.bearing_rad.pop_back();
  EXPECT_THROW(polarFigure(polar, "bad"), ValueError);
}

}  // namespace
}  // namespace sonarmap
