/// @file detectors.cpp
/// detectObstacles: validation, dispatch and names (see detectors.hpp).

#include "sonarmap/detection/detectors.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>

#include "detector_internal.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

[[noreturn]] void throwOption(const std::string& what) { throw ValueError("detectObstacles: " + what); }

void checkImage(const PolarImage& polar) {
  if (polar.intensities.type() != CV_8UC1) throwOption("the polar image must be CV_8UC1");
  if (static_cast<int>(polar.valid_bins.size()) != polar.rows()) {
    throwOption("valid_bins has " + std::to_string(polar.valid_bins.size()) + " entries for " +
                std::to_string(polar.rows()) + " rows");
  }
  if (!(polar.bin_length_m > 0.0) || !std::isfinite(polar.bin_length_m)) throwOption("bin_length_m must be > 0 m");
}

void checkCanny(const CannyOptions& o) {
  if (o.blur_kernel_size < 1 || o.blur_kernel_size % 2 == 0 || o.blur_kernel_size > 255) {
    throwOption("canny.blur_kernel_size must be odd in [1, 255], got " + std::to_string(o.blur_kernel_size));
  }
  if (!(o.blur_sigma >= 0.0) || !std::isfinite(o.blur_sigma)) throwOption("canny.blur_sigma must be finite and >= 0");
  if (!(o.low_threshold >= 0.0) || !(o.high_threshold >= o.low_threshold) || !std::isfinite(o.high_threshold)) {
    throwOption("canny thresholds must satisfy 0 <= low_threshold <= high_threshold");
  }
  if (o.aperture_size != 3 && o.aperture_size != 5 && o.aperture_size != 7) {
    throwOption("canny.aperture_size must be 3, 5 or 7, got " + std::to_string(o.aperture_size));
  }
}

void checkBackground(const BackgroundOptions& o) {
  if (!(o.background_percentile >= 0.0 && o.background_percentile <= 100.0)) {
    throwOption("background.background_percentile must be in [0, 100]");
  }
  if (o.min_excess < 1 || o.min_excess > 255) throwOption("background.min_excess must be in [1, 255]");
  if (o.min_run_bins < 1) throwOption("background.min_run_bins must be >= 1");
  if (o.min_beams < 1) throwOption("background.min_beams must be >= 1");
}

void checkOptions(const DetectorOptions& options) {
  if (!(options.min_range_m >= 0.0) || !std::isfinite(options.min_range_m)) {
    throwOption("min_range_m must be finite and >= 0, got " + std::to_string(options.min_range_m));
  }
  switch (options.kind) {
    case Detector::kThreshold:
      if (options.threshold.min_rise < 0 || options.threshold.min_rise > 255) {
        throwOption("threshold.min_rise must be in [0, 255]");
      }
      break;
    case Detector::kCanny:
      checkCanny(options.canny);
      break;
    case Detector::kBackgroundSubtracted:
      checkBackground(options.background);
      break;
    case Detector::kCfar:
      options.cfar.validate();
      break;
  }
}

/// CFAR along each row over its valid bins (cfar.hpp); options already validated.
std::vector<BeamDetection> detectCfar(const PolarImage& polar, int min_bin, const CfarOptions& options) {
  std::vector<BeamDetection> detections(static_cast<std::size_t>(polar.rows()));
  for (int r = 0; r < polar.rows(); ++r) {
    const auto end = static_cast<std::size_t>(std::clamp(polar.valid_bins[r], 0, polar.cols()));
    const int bin = firstCfarBin(std::span(polar.intensities.ptr<std::uint8_t>(r), end), min_bin, options);
    if (bin >= 0) detections[r] = detail::detectionAt(polar, r, bin);
  }
  return detections;
}

/// A name the CLI accepts, with the detector and (for kCfar) the variant it selects.
struct NamedDetector {
  const char* name;
  Detector kind;
  CfarVariant variant;
};

constexpr NamedDetector kDetectorNames[] = {
    {"threshold", Detector::kThreshold, CfarVariant::kCellAveraging},
    {"canny", Detector::kCanny, CfarVariant::kCellAveraging},
    {"background", Detector::kBackgroundSubtracted, CfarVariant::kCellAveraging},
    {"cfar-ca", Detector::kCfar, CfarVariant::kCellAveraging},
    {"cfar-so", Detector::kCfar, CfarVariant::kSmallestOf},
    {"cfar-go", Detector::kCfar, CfarVariant::kGreatestOf},
    {"cfar-os", Detector::kCfar, CfarVariant::kOrderedStatistic},
};

const NamedDetector& namedDetector(std::string_view name) {
  for (const NamedDetector& named : kDetectorNames) {
    if (name == named.name) return named;
  }
  std::string expected;
  for (const NamedDetector& named : kDetectorNames) expected += (expected.empty() ? "" : ", ") + std::string(named.name);
  throw ValueError("unknown detector '" + std::string(name) + "', expected one of " + expected);
}

}  // namespace

namespace detail {

int firstBinAtRange(const PolarImage& polar, double min_range_m) {
  const double limit = min_range_m / polar.bin_length_m - 0.5;  // bins with centre < min_range_m
  return std::max(0, static_cast<int>(std::min(std::ceil(limit), 1e9)));
}

BeamDetection detectionAt(const PolarImage& polar, int row, int bin) {
  return BeamDetection{bin, polar.intensities.at<std::uint8_t>(row, bin)};
}

}  // namespace detail

std::vector<BeamDetection> detectObstacles(const PolarImage& polar, const DetectorOptions& options) {
  checkImage(polar);
  checkOptions(options);
  const int min_bin = detail::firstBinAtRange(polar, options.min_range_m);
  switch (options.kind) {
    case Detector::kThreshold:
      return detail::detectThreshold(polar, min_bin, options.threshold);
    case Detector::kCanny:
      return detail::detectCanny(polar, min_bin, options.canny);
    case Detector::kBackgroundSubtracted:
      return detail::detectBackgroundSubtracted(polar, min_bin, options.background);
    case Detector::kCfar:
      return detectCfar(polar, min_bin, options.cfar);
  }
  return std::vector<BeamDetection>(static_cast<std::size_t>(polar.rows()));
}

Detector parseDetector(std::string_view name) { return namedDetector(name).kind; }

void selectDetector(DetectorOptions& options, std::string_view name) {
  const NamedDetector& named = namedDetector(name);
  options.kind = named.kind;
  if (named.kind == Detector::kCfar) options.cfar.variant = named.variant;
}

std::string detectorName(Detector kind) {
  DetectorOptions options;
  options.kind = kind;
  options.cfar.variant = CfarVariant::kCellAveraging;
  return detectorName(options);
}

std::string detectorName(const DetectorOptions& options) {
  for (const NamedDetector& named : kDetectorNames) {
    if (named.kind == options.kind && (named.kind != Detector::kCfar || named.variant == options.cfar.variant)) {
      return named.name;
    }
  }
  return "unknown";
}

}  // namespace sonarmap
