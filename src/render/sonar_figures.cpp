/// @file sonar_figures.cpp
/// Figures of a sweep's echoes (sonar_figures.hpp).

#include "sonarmap/render/sonar_figures.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/render/figure.hpp"
#include "sonarmap/sonar/polar.hpp"

namespace sonarmap {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr cv::ColormapTypes kEchoColormap = cv::COLORMAP_INFERNO;

ColourBar echoBar() { return ColourBar{kEchoColormap, 0.0, 255.0, "echo intensity", false}; }

cv::Mat coloured(const cv::Mat& intensities) {
  cv::Mat bgr;
  cv::applyColorMap(intensities, bgr, kEchoColormap);
  return bgr;
}

/// Bearings in degrees, unwrapped along the rows (each step taken in (−180°, 180°]).
std::vector<double> unwrappedBearings_deg(const std::vector<double>& bearing_rad) {
  std::vector<double> unwrapped(bearing_rad.size());
  for (std::size_t i = 0; i < bearing_rad.size(); ++i) {
    if (i == 0) {
      unwrapped[i] = bearing_rad[i] * kDegPerRad;
      continue;
    }
    const double step = std::remainder((bearing_rad[i] - bearing_rad[i - 1]) * kDegPerRad, 360.0);
    unwrapped[i] = unwrapped[i - 1] + step;
  }
  return unwrapped;
}

}  // namespace

cv::Mat polarFigure(const PolarImage& polar, const std::string& title) {
  if (polar.intensities.empty() || !(polar.bin_length_m > 0.0)) {
    throw ValueError("polar figure: the polar image is empty or its bin length is not > 0");
  }
  const auto rows = static_cast<std::size_t>(polar.rows());
  if (polar.bearing_rad.size() != rows) {
    throw ValueError("polar figure: " + std::to_string(polar.bearing_rad.size()) + " bearings for " +
                     std::to_string(rows) + " rows");
  }
  const std::vector<double> bearing_deg = unwrappedBearings_deg(polar.bearing_rad);
  std::vector<std::size_t> order(rows);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return bearing_deg[a] < bearing_deg[b]; });
  double lowest = bearing_deg[order.front()], highest = bearing_deg[order.back()];
  const double shift = -360.0 * std::floor((lowest + 180.0) / 360.0);  // the lowest into [−180, 180)
  lowest += shift;
  highest += shift;
  const double step = rows > 1 && highest > lowest ? (highest - lowest) / static_cast<double>(rows - 1) : 1.0;
  const cv::Mat bgr = coloured(polar.intensities);
  FigureSpec spec;
  spec.raster = cv::Mat(bgr.size(), CV_8UC3);
  for (std::size_t i = 0; i < rows; ++i) {  // the highest bearing on top
    bgr.row(static_cast<int>(order[rows - 1 - i])).copyTo(spec.raster.row(static_cast<int>(i)));
  }
  spec.extent = {0.0, polar.cols() * polar.bin_length_m, lowest - step / 2.0, highest + step / 2.0};
  spec.title = title;
  spec.x_label = "range (m)";
  spec.y_label = "bearing (deg)";
  spec.equal_aspect = false;
  spec.colour_bar = echoBar();
  return composeFigure(spec);
}

cv::Mat cartesianFigure(const PolarImage& polar, double pixel_size_m, double beam_width_rad, const std::string& title) {
  const cv::Mat image = makeCartesianImage(polar, pixel_size_m, beam_width_rad);
  const double half_m = (image.cols / 2 + 0.5) * pixel_size_m;  // the centre pixel's centre is the sonar
  FigureSpec spec;
  spec.raster = coloured(image);
  spec.extent = {-half_m, half_m, -half_m, half_m};
  spec.title = title;
  spec.x_label = "starboard (m), bearing 90 deg";
  spec.y_label = "ahead (m), bearing 0";
  spec.colour_bar = echoBar();
  spec.lines = {FigureLine{{Eigen::Vector2d::Zero()}, kTrackBgr, "sonar"}};
  return composeFigure(spec);
}

}  // namespace sonarmap
