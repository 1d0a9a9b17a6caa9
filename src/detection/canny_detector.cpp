/// @file canny_detector.cpp
/// Paper §9 Canny detector: Gaussian blur, cv::Canny, first edge pixel along each row.

#include <algorithm>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "detector_internal.hpp"

namespace sonarmap::detail {

std::vector<BeamDetection> detectCanny(const PolarImage& polar, int min_bin, const CannyOptions& options) {
  std::vector<BeamDetection> detections(static_cast<std::size_t>(polar.rows()));
  if (polar.intensities.empty()) return detections;
  cv::Mat blurred;  // a fresh buffer: blurring into a header of the input would change the caller's image
  if (options.blur_kernel_size > 1) {
    const cv::Size kernel(options.blur_kernel_size, options.blur_kernel_size);
    cv::GaussianBlur(polar.intensities, blurred, kernel, options.blur_sigma, options.blur_sigma);
  } else {
    blurred = polar.intensities;
  }
  cv::Mat edges;
  cv::Canny(blurred, edges, options.low_threshold, options.high_threshold, options.aperture_size);
  for (int r = 0; r < polar.rows(); ++r) {
    const auto* row = edges.ptr<std::uint8_t>(r);
    const int end = std::min(polar.valid_bins[r], polar.cols());
    const auto* hit = std::find_if(row + std::min(min_bin, end), row + end, [](std::uint8_t e) { return e != 0; });
    if (hit != row + end) detections[r] = detectionAt(polar, r, static_cast<int>(hit - row));
  }
  return detections;
}

}  // namespace sonarmap::detail
