#pragma once
/// @file polar_image.hpp
/// The polar image of a run of beams (paper §2.1): row r is beam r, column c is bin c.

#include <cstddef>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Intensities of consecutive beams as an image.
/// `intensities` is CV_8U, rows = beams, cols = the largest bin count; bins a beam does not have
/// are 0 and lie at or beyond `valid_bins[row]`.
struct PolarImage {
  cv::Mat intensities;               ///< CV_8U, beams × bins
  std::vector<int> valid_bins;       ///< number of real bins of each row
  std::vector<double> bearing_rad;   ///< bearing of each row, sonar frame
  std::vector<double> time_s;        ///< time of each row
  double bin_length_m = 0.0;         ///< bin length (all beams of one image share it)
  std::optional<double> intensity_span_db;  ///< the first beam's Beam::intensity_span_db
  /// The shortest Beam::pulse_length_m of the rows, metres; unset when no row has one.
  std::optional<double> pulse_length_m;

  int rows() const { return intensities.rows; }
  int cols() const { return intensities.cols; }
};

}  // namespace sonarmap
