/// @file threshold_detector.cpp
/// Paper §8.2 threshold detector: first rise between consecutive bins above a threshold.

#include <algorithm>
#include <vector>

#include "detector_internal.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap::detail {

std::vector<BeamDetection> detectThreshold(const PolarImage& polar, const DetectionContext& context,
                                           const ThresholdOptions& options) {
  std::vector<BeamDetection> detections(static_cast<std::size_t>(polar.rows()));
  const double min_rise = countsForDb(options.min_rise_db, context.span_db);
  for (int r = 0; r < polar.rows(); ++r) {
    const auto* row = polar.intensities.ptr<std::uint8_t>(r);
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], polar.cols());
    for (int c = context.min_bin + 1; c < end; ++c) {
      if (static_cast<double>(row[c]) - static_cast<double>(row[c - 1]) > min_rise) {
        detections[static_cast<std::size_t>(r)] = detectionAt(polar, r, c);
        break;
      }
    }
  }
  return detections;
}

}  // namespace sonarmap::detail
