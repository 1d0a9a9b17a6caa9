/// @file background_detector.cpp
/// The calibrated background-subtracted detector: one outward pass over the ranges measuring the
/// background over the beams still in water, and the leading-edge range (see detectors.hpp).

#include <algorithm>
#include <cmath>
#include <vector>

#include "column_histogram.hpp"
#include "detector_internal.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap::detail {
namespace {

/// A range's water statistics need this share of the rows (and at least 3) still in water there;
/// beyond, the last range that had them is used. Where fewer beams remain, they are mostly those
/// whose walls were missed so far, and their echoes would raise the background that hides them (the
/// CRAS tank's far corners: the 25th percentile of the last 10 % of the beams jumps from ≈ 10 to 70
/// within 10 cm).
constexpr double kMinWaterShare = 0.3;

/// Residual of bin c of `row` above the background, intensity counts.
float residual(const std::uint8_t* row, const SweepCalibration& calibration, int c) {
  return static_cast<float>(row[c]) - calibration.background[static_cast<std::size_t>(c)];
}

}  // namespace

std::vector<int> outwardPass(const PolarImage& polar, const DetectionContext& context, const BackgroundOptions& options,
                             SweepCalibration& water) {
  const int rows = polar.rows(), cols = polar.cols();
  const CalibrationOptions& calibration = options.calibration;
  const int run = binsForLength(options.min_echo_length_m, polar.bin_length_m, 1, std::max(1, cols));
  const auto min_water = static_cast<std::uint32_t>(std::max(3.0, std::ceil(kMinWaterShare * rows)));
  std::vector<int> first(static_cast<std::size_t>(rows), -1), length(static_cast<std::size_t>(rows), 0);
  std::vector<int> in_water;  // rows not yet detected
  for (int r = 0; r < rows; ++r) in_water.push_back(r);
  IntensityHistogram histogram;
  const cv::Mat columns = polar.intensities.t();  // row c: column c's values, contiguous
  const RowRingDown ring(polar, water);
  for (int c = context.min_bin; c < cols && !in_water.empty(); ++c) {
    const auto i = static_cast<std::size_t>(c);
    const auto* column = columns.ptr<std::uint8_t>(c);
    histogram.clear();
    for (const int r : in_water) {
      // A row already above the threshold is in an echo, not in water.
      if (c < polar.valid_bins[static_cast<std::size_t>(r)] && length[static_cast<std::size_t>(r)] == 0) {
        histogram.add(column[r]);
      }
    }
    if (!context.measure_background) {
      // The given calibration's background, as measured on an earlier sweep.
    } else if (histogram.total() >= min_water) {
      water.background[i] = std::min(histogram.percentile(calibration.background_percentile), water.backgroundCap(c));
    } else if (c > context.min_bin) {
      water.background[i] = water.background[i - 1];
    }
    // Rows whose run reaches the echo length leave the water.
    std::erase_if(in_water, [&](int r) {
      const auto row = static_cast<std::size_t>(r);
      if (c >= polar.valid_bins[row]) return true;
      const float excess = static_cast<float>(column[r]) - std::max({water.background[i], ring.at(r, c), context.floorAt(r, c)});
      length[row] = excess >= water.threshold[i] ? length[row] + 1 : 0;
      if (length[row] < run) return false;
      first[row] = c - run + 1;
      return true;
    });
  }
  return first;
}

BeamDetection leadingEdgeAt(const PolarImage& polar, int row, int bin, const DetectionContext& context,
                            const SweepCalibration& calibration, double edge_db) {
  const auto* values = polar.intensities.ptr<std::uint8_t>(row);
  return leadingEdgeOf(polar, row, bin, context, [&](int c) { return residual(values, calibration, c); },
                       calibration.threshold[static_cast<std::size_t>(bin)], edge_db);
}

std::vector<BeamDetection> detectBackgroundSubtracted(const PolarImage& polar, const DetectionContext& context,
                                                      const BackgroundOptions& options, SweepCalibration& water) {
  std::vector<BeamDetection> detections(static_cast<std::size_t>(polar.rows()));
  if ((context.measure_background && polar.rows() < options.min_beams) || polar.cols() == 0) return detections;
  const std::vector<int> first = outwardPass(polar, context, options, water);
  for (int r = 0; r < polar.rows(); ++r) {
    const int bin = first[static_cast<std::size_t>(r)];
    if (bin >= 0) detections[static_cast<std::size_t>(r)] = leadingEdgeAt(polar, r, bin, context, water, options.leading_edge_db);
  }
  return detections;
}

}  // namespace sonarmap::detail
