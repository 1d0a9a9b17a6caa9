/// @file threshold_detector.cpp
/// Paper §8.2 threshold detector: first rise between consecutive bins above a threshold.

#include <algorithm>
#include <vector>

#include "detector_internal.hpp"

namespace sonarmap::detail {

std::vector<BeamDetection> detectThreshold(const PolarImage& polar, int min_bin, const ThresholdOptions& options) {
  std::vector<BeamDetection> detections(static_cast<std::size_t>(polar.rows()));
  for (int r = 0; r < polar.rows(); ++r) {
    const auto* row = polar.intensities.ptr<std::uint8_t>(r);
    const int end = std::min(polar.valid_bins[r], polar.cols());
    for (int c = min_bin + 1; c < end; ++c) {
      if (static_cast<int>(row[c]) - static_cast<int>(row[c - 1]) > options.min_rise) {
        detections[r] = detectionAt(polar, r, c);
        break;
      }
    }
  }
  return detections;
}

}  // namespace sonarmap::detail
