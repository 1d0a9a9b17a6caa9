/// @file echo_mosaic.cpp
/// The echo-intensity mosaic (see echo_mosaic.hpp).

#include "sonarmap/mapping/echo_mosaic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <absl/container/flat_hash_map.h>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

MosaicGrid echoMosaic(BeamSource& source, const SonarPoseAt& pose_at, const EchoMosaicOptions& options) {
  const double resolution_m = options.resolution_m;
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m)) throw ValueError("the echo mosaic's resolution must be positive and finite");
  if (!(options.beam_width_rad >= 0.0) || !std::isfinite(options.beam_width_rad) || !(options.min_range_m >= 0.0) ||
      !std::isfinite(options.min_range_m)) {
    throw ValueError("the echo mosaic's beam width and minimum range must be finite and not negative");
  }
  absl::flat_hash_map<std::int64_t, std::uint8_t> columns;  // key: (ix << 32) | iy as unsigned
  auto key = [](std::int64_t ix, std::int64_t iy) { return (ix << 32) ^ (iy & 0xffffffffLL); };
  std::int64_t x_lo = std::numeric_limits<std::int64_t>::max(), x_hi = std::numeric_limits<std::int64_t>::min();
  std::int64_t y_lo = x_lo, y_hi = x_hi;
  passOver(source)([&](const Beam& beam) {
    const std::optional<Eigen::Isometry3d> pose = pose_at(beam.time_s);
    if (!pose) return;
    for (std::size_t k = 0; k < beam.intensities.size(); ++k) {
      const double range_m = (static_cast<double>(k) + 0.5) * beam.bin_length_m;
      if (range_m < options.min_range_m) continue;
      // points along the arc every half column, at least the bearing itself
      const int half_points = static_cast<int>(std::ceil(range_m * options.beam_width_rad / resolution_m));
      for (int a = -half_points; a <= half_points; ++a) {
        const double bearing_rad =
            beam.bearing_rad + (half_points == 0 ? 0.0 : 0.5 * options.beam_width_rad * a / half_points);
        const Eigen::Vector3d p = *pose * Eigen::Vector3d(range_m * std::cos(bearing_rad), range_m * std::sin(bearing_rad), 0.0);
        const auto ix = static_cast<std::int64_t>(std::floor(p.x() / resolution_m));
        const auto iy = static_cast<std::int64_t>(std::floor(p.y() / resolution_m));
        std::uint8_t& value = columns[key(ix, iy)];
        value = std::max<std::uint8_t>({value, beam.intensities[k], std::uint8_t{1}});
        x_lo = std::min(x_lo, ix), x_hi = std::max(x_hi, ix), y_lo = std::min(y_lo, iy), y_hi = std::max(y_hi, iy);
      }
    }
  });
  MosaicGrid grid;
  grid.pixel_m = resolution_m;
  if (columns.empty()) {
    grid.image = cv::Mat(1, 1, CV_8U, cv::Scalar(0));
    return grid;
  }
  const int cols = static_cast<int>(x_hi - x_lo + 1), rows = static_cast<int>(y_hi - y_lo + 1);
  grid.image = cv::Mat(rows, cols, CV_8U, cv::Scalar(0));
  grid.left_m = static_cast<double>(x_lo) * resolution_m;
  grid.bottom_m = static_cast<double>(y_lo) * resolution_m;
  for (std::int64_t ix = x_lo; ix <= x_hi; ++ix) {
    for (std::int64_t iy = y_lo; iy <= y_hi; ++iy) {
      const auto found = columns.find(key(ix, iy));
      if (found != columns.end()) grid.image.at<std::uint8_t>(static_cast<int>(y_hi - iy), static_cast<int>(ix - x_lo)) = found->second;
    }
  }
  return grid;
}

}  // namespace sonarmap
