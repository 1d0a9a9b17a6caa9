#pragma once
/// @file detector_internal.hpp
/// Shared helpers and the per-detector entry points behind detectObstacles (not installed).

#include <vector>

#include "sonarmap/detection/detectors.hpp"

namespace sonarmap::detail {

/// First bin whose centre (bin + 0.5) × bin_length_m is at or beyond min_range_m (≥ 0).
int firstBinAtRange(const PolarImage& polar, double min_range_m);

/// The detection of `bin` in `row`, with the image's intensity there.
BeamDetection detectionAt(const PolarImage& polar, int row, int bin);

/// Paper §8.2 threshold on the rise between consecutive bins; options already validated.
std::vector<BeamDetection> detectThreshold(const PolarImage& polar, int min_bin, const ThresholdOptions& options);

/// Paper §9 Gaussian blur + Canny; options already validated.
std::vector<BeamDetection> detectCanny(const PolarImage& polar, int min_bin, const CannyOptions& options);

/// Background-subtracted run detector; options already validated.
std::vector<BeamDetection> detectBackgroundSubtracted(const PolarImage& polar, int min_bin,
                                                      const BackgroundOptions& options);

}  // namespace sonarmap::detail
