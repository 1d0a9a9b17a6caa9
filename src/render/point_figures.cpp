/// @file point_figures.cpp
/// pointPanel, pointFigureCell and pointPanelsFigure (point_figures.hpp).

#include "sonarmap/render/point_figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include <opencv2/core.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/render/figure.hpp"

namespace sonarmap {

PointPanel pointPanel(std::string title, std::vector<Eigen::Vector2d> points_ned_m, const NavTrack& track) {
  PointPanel panel;
  panel.title = std::move(title);
  panel.points_ned_m = std::move(points_ned_m);
  panel.track_ned_m.reserve(track.size());
  for (const NavSample& fix : track) panel.track_ned_m.push_back(fix.position_ned_m.head<2>());
  return panel;
}

namespace {

/// The corners of every panel's finite points' bounding box (NED's plane, metres).
/// @throws ValueError for no panel or no point.
std::pair<Eigen::Vector2d, Eigen::Vector2d> extentOf(const std::vector<PointPanel>& panels) {
  if (panels.empty()) throw ValueError("point figure: no panel to draw");
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (const PointPanel& panel : panels) {
    for (const Eigen::Vector2d& p : panel.points_ned_m) {
      if (!p.allFinite()) continue;
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  }
  if (!(low.x() <= high.x())) throw ValueError("point figure: no point to draw");
  return {low, high};
}

}  // namespace

double pointFigureCell(const std::vector<PointPanel>& panels, double cell_m) {
  if (!(std::isfinite(cell_m) && cell_m > 0.0)) throw ValueError("point figure: the cell must be > 0 m");
  const auto [low, high] = extentOf(panels);
  // ceil(span / cell) + 1 cells along the longer side: at most kMaxPointPanelCells, with a cell of
  // span / (kMaxPointPanelCells - 2) for rounding's sake.
  return std::max(cell_m, (high - low).maxCoeff() / (kMaxPointPanelCells - 2));
}

cv::Mat pointPanelsFigure(const std::vector<PointPanel>& panels, double cell_m) {
  cell_m = pointFigureCell(panels, cell_m);
  const auto [low, high] = extentOf(panels);
  const int cols = static_cast<int>(std::ceil((high.y() - low.y()) / cell_m)) + 1;  // east
  const int rows = static_cast<int>(std::ceil((high.x() - low.x()) / cell_m)) + 1;  // north, up
  std::vector<cv::Mat> figures;
  for (const PointPanel& panel : panels) {
    cv::Mat count(rows, cols, CV_32F, cv::Scalar(0));
    for (const Eigen::Vector2d& p : panel.points_ned_m) {
      if (!p.allFinite()) continue;
      const int col = std::clamp(static_cast<int>((p.y() - low.y()) / cell_m), 0, cols - 1);
      const int row = std::clamp(rows - 1 - static_cast<int>((p.x() - low.x()) / cell_m), 0, rows - 1);
      count.at<float>(row, col) += 1.0F;
    }
    // Grey levels by the points in a cell: one point light grey, 8 or more black.
    cv::Mat raster(rows, cols, CV_8UC1);
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        const float n = count.at<float>(r, c);
        raster.at<std::uint8_t>(r, c) = n <= 0.0F ? 255 : static_cast<std::uint8_t>(200.0 - 200.0 * std::min(1.0, std::log2(n) / 3.0));
      }
    }
    FigureSpec spec;
    spec.raster = raster;
    spec.extent = {low.y(), low.y() + cols * cell_m, low.x(), low.x() + rows * cell_m};
    spec.title = panel.title;
    spec.x_label = "east (m)";
    spec.y_label = "north (m)";
    FigureLine track;
    for (const Eigen::Vector2d& p : panel.track_ned_m) track.points.emplace_back(p.y(), p.x());
    track.label = panel.track_label;
    if (!track.points.empty()) spec.lines.push_back(track);
    figures.push_back(composeFigure(spec));
  }
  int height = 0;
  for (const cv::Mat& figure : figures) height = std::max(height, figure.rows);
  for (cv::Mat& figure : figures) {
    if (figure.rows < height) {
      cv::copyMakeBorder(figure, figure, 0, height - figure.rows, 0, 0, cv::BORDER_CONSTANT, cv::Scalar(255, 255, 255));
    }
  }
  cv::Mat all;
  cv::hconcat(figures, all);
  return all;
}

}  // namespace sonarmap
