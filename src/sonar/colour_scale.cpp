#include "sonarmap/sonar/colour_scale.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>

namespace sonarmap {
namespace {

/// The 256 colours of an OpenCV colour map, low end first (built once per map).
const std::array<cv::Vec3b, 256>& colourTable(cv::ColormapTypes colormap) {
  static std::mutex mutex;
  static std::map<int, std::array<cv::Vec3b, 256>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  auto [it, inserted] = tables.try_emplace(static_cast<int>(colormap));
  if (inserted) {
    cv::Mat ramp(256, 1, CV_8U);
    for (int i = 0; i < 256; ++i) ramp.at<unsigned char>(i) = static_cast<unsigned char>(i);
    cv::Mat coloured;
    cv::applyColorMap(ramp, coloured, colormap);
    for (int i = 0; i < 256; ++i) it->second[static_cast<std::size_t>(i)] = coloured.at<cv::Vec3b>(i);
  }
  return it->second;
}

}  // namespace

cv::Vec3b colourOnScale(cv::ColormapTypes colormap, double value, double min, double max) {
  const double t = max > min ? std::clamp((value - min) / (max - min), 0.0, 1.0) : 0.5;
  return colourTable(colormap)[static_cast<std::size_t>(std::lround(t * 255.0))];
}

}  // namespace sonarmap
