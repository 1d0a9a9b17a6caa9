/// @file background_detector.cpp
/// Background-subtracted run detector and its per-range background (see detectors.hpp).

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "detector_internal.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// The `percentile` (0…100) of `values` by the nearest-rank rule on the sorted values; `values` is reordered.
float percentileOf(std::vector<std::uint8_t>& values, double percentile) {
  const double position = percentile / 100.0 * static_cast<double>(values.size() - 1);
  const auto k = static_cast<std::ptrdiff_t>(std::lround(position));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return static_cast<float>(values[static_cast<std::size_t>(k)]);
}

/// First bin c in [min_bin, end) starting `run` consecutive bins with row[c] − background[c] ≥ excess; −1 if none.
int firstRunAboveBackground(const std::uint8_t* row, const float* background, int min_bin, int end,
                            const BackgroundOptions& options) {
  int run = 0;
  for (int c = min_bin; c < end; ++c) {
    run = static_cast<float>(row[c]) - background[c] >= static_cast<float>(options.min_excess) ? run + 1 : 0;
    if (run == options.min_run_bins) return c - run + 1;
  }
  return -1;
}

}  // namespace

cv::Mat estimateRangeBackground(const PolarImage& polar, double percentile) {
  if (polar.intensities.type() != CV_8UC1) throw ValueError("estimateRangeBackground: the polar image must be CV_8UC1");
  if (!(percentile >= 0.0 && percentile <= 100.0)) {
    throw ValueError("estimateRangeBackground: percentile must be in [0, 100], got " + std::to_string(percentile));
  }
  cv::Mat background = cv::Mat::zeros(1, polar.cols(), CV_32FC1);
  std::vector<std::uint8_t> column;
  for (int c = 0; c < polar.cols(); ++c) {
    column.clear();
    for (int r = 0; r < polar.rows(); ++r) {
      const bool valid = polar.valid_bins.empty() || c < polar.valid_bins[r];
      if (valid) column.push_back(polar.intensities.at<std::uint8_t>(r, c));
    }
    if (!column.empty()) background.at<float>(0, c) = percentileOf(column, percentile);
  }
  return background;
}

namespace detail {

std::vector<BeamDetection> detectBackgroundSubtracted(const PolarImage& polar, int min_bin,
                                                      const BackgroundOptions& options) {
  std::vector<BeamDetection> detections(static_cast<std::size_t>(polar.rows()));
  if (polar.rows() < options.min_beams || polar.cols() == 0) return detections;
  const cv::Mat background = estimateRangeBackground(polar, options.background_percentile);
  const auto* bg = background.ptr<float>(0);
  for (int r = 0; r < polar.rows(); ++r) {
    const int end = std::min(polar.valid_bins[r], polar.cols());
    const int bin = firstRunAboveBackground(polar.intensities.ptr<std::uint8_t>(r), bg, min_bin, end, options);
    if (bin >= 0) detections[r] = detectionAt(polar, r, bin);
  }
  return detections;
}

}  // namespace detail
}  // namespace sonarmap
