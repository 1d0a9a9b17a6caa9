/// @file map_figures.cpp
/// Figures of maps (map_figures.hpp): the library's one-pixel-per-voxel renderings recoloured and
/// composed with axes in metres (figure.hpp).

#include "sonarmap/render/map_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/render/figure.hpp"
#include "sonarmap/sonar/map_views.hpp"

namespace sonarmap {
namespace {

/// The legend entries of the occupancy colours, occupied (near-black) first when `with_occupied`.
std::vector<LegendSwatch> occupancySwatches(bool with_occupied) {
  std::vector<LegendSwatch> swatches;
  if (with_occupied) swatches.push_back({kOccupiedBgr, "occupied"});
  swatches.push_back({kFreeBgr, "free"});
  swatches.push_back({kUnknownBgr, "unknown"});
  return swatches;
}

/// Components `u` and `v` of each position, as a line labelled `label` (a single position: a dot
/// labelled "sonar"); no line when empty.
std::vector<FigureLine> trackLines(const std::vector<Eigen::Vector3d>& positions_m, int u, int v,
                                   const std::string& label) {
  if (positions_m.empty()) return {};
  FigureLine line;
  line.label = positions_m.size() == 1 ? "sonar" : label;
  for (const Eigen::Vector3d& p : positions_m) line.points.emplace_back(p[u], p[v]);
  return {line};
}

/// The view itself (without its legend panel), one pixel per voxel, its border white.
cv::Mat viewRaster(const MapView& view) {
  cv::Mat raster = view.image(cv::Rect(0, 0, view.view_cols, view.view_rows)).clone();
  cv::rectangle(raster, cv::Rect(0, 0, raster.cols, raster.rows), cv::Scalar::all(255));
  return raster;
}

PlotExtent extentOf(const MapView& view) {
  return {view.left_m, view.left_m + view.view_cols * view.voxel_m, view.bottom_m,
          view.bottom_m + view.view_rows * view.voxel_m};
}

bool isGrey(const cv::Vec3b& p) { return p[0] == p[1] && p[1] == p[2]; }

/// A figure of a view coloured by a height or depth through viridis (map_views.hpp).
cv::Mat viewFigure(const MapView& view, const std::string& title, const char* v_label, const char* scale_label,
                   std::vector<FigureLine> lines) {
  FigureSpec spec;
  spec.raster = viewRaster(view);
  spec.extent = extentOf(view);
  spec.title = title;
  spec.x_label = "east (m)";
  spec.y_label = v_label;
  spec.swatches = occupancySwatches(false);
  if (view.occupied_pixels > 0) {
    spec.colour_bar = ColourBar{cv::COLORMAP_VIRIDIS, view.scale_min_m, view.scale_max_m,
                                std::string("occupied, ") + scale_label, false};
  }
  spec.lines = std::move(lines);
  return composeFigure(spec);
}

/// The view recoloured by the distance to the truth (surfaceErrorFigure): each pixel showing an
/// occupied voxel of report.occupied_errors gets the largest distance among those projecting onto
/// it along the view's depth; `v` is the map axis drawn up (1: y, top view; 2: z, side view).
cv::Mat errorFigure(const MapView& view, const GroundTruthReport& report, int v, const std::string& title,
                    const char* v_label, const std::vector<Eigen::Vector3d>& sensors_m) {
  static_assert(kFreeGrey == 200, "the views' free grey is the figures' kFreeBgr");
  FigureSpec spec;
  spec.raster = viewRaster(view);
  spec.extent = extentOf(view);
  // Pixels with an occupied voxel were coloured by height or depth: known, so light grey until scored.
  for (auto it = spec.raster.begin<cv::Vec3b>(); it != spec.raster.end<cv::Vec3b>(); ++it) {
    if (!isGrey(*it)) *it = kFreeBgr;
  }
  double largest = 0.0;
  for (const OccupiedVoxelError& voxel : report.occupied_errors) largest = std::max(largest, voxel.distance_m);
  const double scale_max = std::max(2.0 * report.tolerance_m, report.surface_error_p90_m);
  cv::Mat worst(spec.raster.size(), CV_64F, cv::Scalar(-1.0));  // the largest distance of each pixel
  for (const OccupiedVoxelError& voxel : report.occupied_errors) {
    const int col = static_cast<int>(std::floor((voxel.centre_m.x() - view.left_m) / view.voxel_m));
    const int row = worst.rows - 1 - static_cast<int>(std::floor((voxel.centre_m[v] - view.bottom_m) / view.voxel_m));
    if (col < 0 || row < 0 || col >= worst.cols || row >= worst.rows) continue;
    double& cell = worst.at<double>(row, col);
    cell = std::max(cell, voxel.distance_m);
  }
  for (int row = 0; row < worst.rows; ++row) {
    for (int col = 0; col < worst.cols; ++col) {
      const double d = worst.at<double>(row, col);
      if (d >= 0.0) spec.raster.at<cv::Vec3b>(row, col) = colourOnScale(cv::COLORMAP_TURBO, d, 0.0, scale_max);
    }
  }
  spec.title = title;
  spec.x_label = "x (m)";
  spec.y_label = v_label;
  spec.swatches = {{kFreeBgr, "known, unscored"}, {kUnknownBgr, "unknown"}};
  spec.colour_bar = ColourBar{cv::COLORMAP_TURBO, 0.0, scale_max, "distance to truth (m)", largest > scale_max};
  spec.lines = trackLines(sensors_m, 0, v, "sonar positions");
  return composeFigure(spec);
}

}  // namespace

cv::Mat sliceFigure(const OcTree16& map, double z_m, const std::string& title,
                    const std::vector<Eigen::Vector3d>& track_m) {
  return bandFigure(map, z_m, z_m, title, track_m);
}

cv::Mat bandFigure(const OcTree16& map, double z_min_m, double z_max_m, const std::string& title,
                   const std::vector<Eigen::Vector3d>& track_m) {
  const SliceView slice = renderBandView(map, z_min_m, z_max_m);
  FigureSpec spec;
  spec.raster = cv::Mat(slice.image.size(), CV_8UC3);
  for (int row = 0; row < slice.image.rows; ++row) {
    for (int col = 0; col < slice.image.cols; ++col) {
      const unsigned char value = slice.image.at<unsigned char>(row, col);
      spec.raster.at<cv::Vec3b>(row, col) = value == 0 ? kOccupiedBgr : (value == 255 ? kFreeBgr : kUnknownBgr);
    }
  }
  spec.extent = {slice.left_m, slice.left_m + slice.image.cols * slice.pixel_m, slice.bottom_m,
                 slice.bottom_m + slice.image.rows * slice.pixel_m};
  spec.title = title;
  spec.x_label = "east (m)";
  spec.y_label = "north (m)";
  spec.swatches = occupancySwatches(true);
  spec.lines = trackLines(track_m, 0, 1, "sonar track");
  return composeFigure(spec);
}

cv::Mat topViewFigure(const OcTree16& map, const std::string& title, const std::vector<Eigen::Vector3d>& track_m) {
  return viewFigure(renderTopView(map), title, "north (m)", "up z (m)", trackLines(track_m, 0, 1, "sonar track"));
}

cv::Mat sideViewFigure(const OcTree16& map, const std::string& title, const std::vector<Eigen::Vector3d>& track_m) {
  return viewFigure(renderSideView(map), title, "up z (m)", "north (m)", trackLines(track_m, 0, 2, "sonar track"));
}

cv::Mat surfaceErrorFigure(const OcTree16& map, const GroundTruthReport& report, const std::string& title,
                           const std::vector<Eigen::Vector3d>& sensors_m) {
  cv::Mat top = errorFigure(renderTopView(map), report, 1, title + ", top view", "y (m)", sensors_m);
  if (!(report.z_max_m > report.z_min_m)) return top;  // one layer: a side view would be a line
  cv::Mat side = errorFigure(renderSideView(map), report, 2, title + ", side view along +y", "z (m)", sensors_m);
  const int cols = std::max(top.cols, side.cols);  // stacked on a white page as wide as the wider
  cv::copyMakeBorder(top, top, 0, 0, 0, cols - top.cols, cv::BORDER_CONSTANT, cv::Scalar::all(255));
  cv::copyMakeBorder(side, side, 0, 0, 0, cols - side.cols, cv::BORDER_CONSTANT, cv::Scalar::all(255));
  cv::Mat both;
  cv::vconcat(top, side, both);
  return both;
}

}  // namespace sonarmap
