/// @file preprocess.cpp
/// removeSelfReflection, smooth and the smoothing names (see preprocess.hpp).

#include "sonarmap/sonar/preprocess.hpp"

#include <algorithm>
#include <initializer_list>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap {
namespace {

constexpr int kMaxKernelSize = 255;

void checkImage(const PolarImage& polar, const char* function) {
  if (polar.intensities.type() != CV_8UC1) {
    throw ValueError(std::string(function) + ": the polar image must be CV_8UC1");
  }
}

}  // namespace

void SmoothingOptions::validate() const {
  if (!(std::isfinite(range_m) && range_m >= 0.0)) {
    throw ValueError("smoothing: the extent along the beam must be >= 0 m, got " + std::to_string(range_m));
  }
  if (!(std::isfinite(bearing_rad) && bearing_rad >= 0.0)) {
    throw ValueError("smoothing: the extent across beams must be >= 0 degrees, got " + std::to_string(bearing_rad));
  }
}

namespace {

/// An odd kernel side of at least 1 and at most kMaxKernelSize pixels for `pixels` pixels.
int oddKernel(double pixels) {
  const int side = static_cast<int>(std::min(std::round(pixels), static_cast<double>(kMaxKernelSize)));
  return std::max(1, side % 2 == 0 ? side + 1 : side);
}

/// The Gaussian kernel side covering ±3σ for σ in pixels (1 when σ is under half a pixel).
int gaussianKernel(double sigma_px) { return sigma_px < 0.5 ? 1 : oddKernel(2.0 * std::ceil(3.0 * sigma_px) + 1.0); }

}  // namespace

void removeSelfReflection(PolarImage& polar, double min_range_m) {
  checkImage(polar, "removeSelfReflection");
  if (!(min_range_m >= 0.0) || !std::isfinite(min_range_m)) {
    throw ValueError("self-reflection removal: min_range_m must be finite and >= 0, got " +
                     std::to_string(min_range_m));
  }
  if (!(polar.bin_length_m > 0.0)) throw ValueError("self-reflection removal: bin_length_m must be > 0 m");
  // Bins with (i + 0.5)·L < min_range_m; saturates at the image's width (never overflows).
  const int count = firstBinAtOrBeyond(min_range_m, polar.bin_length_m, polar.cols());
  if (count > 0 && polar.rows() > 0) polar.intensities.colRange(0, count).setTo(0);
}

void smooth(PolarImage& polar, const SmoothingOptions& options) {
  checkImage(polar, "smooth");
  options.validate();
  if (polar.intensities.empty() || options.kind == Smoothing::kNone) return;
  if (!(polar.bin_length_m > 0.0)) throw ValueError("smooth: bin_length_m must be > 0 m");
  const double range_px = options.range_m / polar.bin_length_m;
  const double spacing_rad = beamSpacing_rad(polar);
  const double bearing_px = spacing_rad > 0.0 ? options.bearing_rad / spacing_rad : 0.0;
  cv::Mat out;
  switch (options.kind) {
    case Smoothing::kNone:
      return;
    case Smoothing::kMean: {
      const cv::Size kernel(oddKernel(range_px), oddKernel(bearing_px));
      if (kernel.area() == 1) return;
      cv::blur(polar.intensities, out, kernel);
      break;
    }
    case Smoothing::kMedian: {
      const int side = oddKernel(range_px);
      if (side == 1) return;
      cv::medianBlur(polar.intensities, out, side);
      break;
    }
    case Smoothing::kGaussian: {
      const cv::Size kernel(gaussianKernel(range_px), gaussianKernel(bearing_px));
      if (kernel.area() == 1) return;
      cv::GaussianBlur(polar.intensities, out, kernel, std::max(range_px, 1e-3), std::max(bearing_px, 1e-3));
      break;
    }
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
