/// @file preprocess.cpp
/// removeSelfReflection, smooth and the smoothing names (see preprocess.hpp).

#include "sonarmap/sonar/preprocess.hpp"

#include <algorithm>
#include <initializer_list>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr int kMaxKernelSize = 255;

void checkImage(const PolarImage& polar, const char* function) {
  if (polar.intensities.type() != CV_8UC1) {
    throw ValueError(std::string(function) + ": the polar image must be CV_8UC1");
  }
}

void checkSmoothingOptions(const SmoothingOptions& options) {
  const int k = options.kernel_size;
  if (k < 1 || k > kMaxKernelSize || k % 2 == 0) {
    throw ValueError("smooth: kernel_size must be odd and in [1, 255], got " + std::to_string(k));
  }
  if (!(options.sigma >= 0.0) || !std::isfinite(options.sigma)) {
    throw ValueError("smooth: sigma must be finite and >= 0, got " + std::to_string(options.sigma));
  }
}

}  // namespace

void removeSelfReflection(PolarImage& polar, double min_range_m) {
  checkImage(polar, "removeSelfReflection");
  if (!(min_range_m >= 0.0) || !std::isfinite(min_range_m)) {
    throw ValueError("removeSelfReflection: min_range_m must be finite and >= 0, got " +
                     std::to_string(min_range_m));
  }
  if (!(polar.bin_length_m > 0.0)) throw ValueError("removeSelfReflection: bin_length_m must be > 0 m");
  // Bins with (i + 0.5)·L < min_range_m, i.e. i < min_range_m / L − 0.5.
  const double limit = min_range_m / polar.bin_length_m - 0.5;
  const int count = std::clamp(static_cast<int>(std::ceil(limit)), 0, polar.cols());
  if (count > 0 && polar.rows() > 0) polar.intensities.colRange(0, count).setTo(0);
}

void smooth(PolarImage& polar, const SmoothingOptions& options) {
  checkImage(polar, "smooth");
  checkSmoothingOptions(options);
  if (polar.intensities.empty() || options.kernel_size == 1) return;
  const cv::Size kernel(options.kernel_size, options.kernel_size);
  cv::Mat out;
  switch (options.kind) {
    case Smoothing::kNone:
      return;
    case Smoothing::kMean:
      cv::blur(polar.intensities, out, kernel);
      break;
    case Smoothing::kMedian:
      cv::medianBlur(polar.intensities, out, options.kernel_size);
      break;
    case Smoothing::kGaussian:
      cv::GaussianBlur(polar.intensities, out, kernel, options.sigma, options.sigma);
      break;
  }
  polar.intensities = out;
}

Smoothing parseSmoothing(std::string_view name) {
  for (Smoothing kind : {Smoothing::kNone, Smoothing::kMean, Smoothing::kMedian, Smoothing::kGaussian}) {
    if (name == smoothingName(kind)) return kind;
  }
  throw ValueError("unknown smoothing '" + std::string(name) + "', expected none, mean, median or gaussian");
}

std::string smoothingName(Smoothing kind) {
  switch (kind) {
    case Smoothing::kNone:
      return "none";
    case Smoothing::kMean:
      return "mean";
    case Smoothing::kMedian:
      return "median";
    case Smoothing::kGaussian:
      return "gaussian";
  }
  return "unknown";
}

}  // namespace sonarmap
