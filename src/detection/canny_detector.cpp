/// @file canny_detector.cpp
/// Paper §9 Canny detector: Gaussian blur, cv::Canny, first edge pixel along each row.

#include <algorithm>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "detector_internal.hpp"
#include "sonarmap/sonar/polar_units.hpp"
#include "sonarmap/sonar/preprocess.hpp"

namespace sonarmap::detail {

std::vector<BeamDetection> detectCanny(const PolarImage& polar, const DetectionContext& context,
                                       const CannyOptions& options) {
  std::vector<BeamDetection> detections(static_cast<std::size_t>(polar.rows()));
  if (polar.intensities.empty()) return detections;
  PolarImage blurred = polar;  // a fresh buffer: blurring a header of the input would change the caller's image
  blurred.intensities = polar.intensities.clone();
  smooth(blurred, SmoothingOptions{Smoothing::kGaussian, options.blur_range_m, options.blur_bearing_rad});
  cv::Mat edges;
  cv::Canny(blurred.intensities, edges, countsForDb(options.low_threshold_db, context.span_db),
            countsForDb(options.high_threshold_db, context.span_db), options.aperture_size);
  for (int r = 0; r < polar.rows(); ++r) {
    const auto* row = edges.ptr<std::uint8_t>(r);
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], polar.cols());
    const auto* hit = std::find_if(row + std::min(context.min_bin, end), row + end, [](std::uint8_t e) { return e != 0; });
    if (hit != row + end) detections[static_cast<std::size_t>(r)] = detectionAt(polar, r, static_cast<int>(hit - row));
  }
  return detections;
}

}  // namespace sonarmap::detail
