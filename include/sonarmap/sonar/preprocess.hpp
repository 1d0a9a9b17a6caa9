#pragma once
/// @file preprocess.hpp
/// Cleaning a polar image before detection (paper §8.1): self-reflection removal and smoothing.
/// Both work in polar coordinates, as the paper does ("converting the image into the Cartesian
/// coordinate system propagates these errors even further").

#include <string>
#include <string_view>

#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// Zeroes, in every row, the bins whose centre range (bin + 0.5) × bin_length_m is below
/// `min_range_m`: the bright band of reflections from the vehicle's own body (paper §8.1, "the
/// vertical stripe on the left side of the polar image"; about the first 0.3 m on the CRAS data).
///
/// @param polar        image to change in place (CV_8UC1, beams × bins).
/// @param min_range_m  range in metres below which bins are zeroed, ≥ 0 (0 changes nothing).
/// @throws ValueError  when min_range_m is negative or not finite, or the image is not CV_8UC1
///   with bin_length_m > 0.
void removeSelfReflection(PolarImage& polar, double min_range_m);

/// Image smoothing filter (paper §8.1, Fig. 15: mean, median and Gaussian were compared; Gaussian
/// handled small noise best).
enum class Smoothing { kNone, kMean, kMedian, kGaussian };

/// Options of smooth(). The defaults are the paper's Gaussian (§9: kernel 11, σ = 2.3).
struct SmoothingOptions {
  Smoothing kind = Smoothing::kGaussian;
  int kernel_size = 11;  ///< side of the square kernel in pixels (beams × bins), odd, 1…255
  double sigma = 2.3;    ///< Gaussian σ in pixels (both axes); 0 lets OpenCV derive it from kernel_size
};

/// Smooths the polar image in place with a kernel_size × kernel_size filter over beams × bins:
/// cv::blur (kMean), cv::medianBlur (kMedian), cv::GaussianBlur (kGaussian), nothing (kNone).
/// Borders are reflected (OpenCV's BORDER_REFLECT_101), also across the first and last beam.
///
/// @throws ValueError  when kernel_size is even, < 1 or > 255, when sigma is negative or not finite,
///   or when the image is not CV_8UC1.
void smooth(PolarImage& polar, const SmoothingOptions& options);

/// Parses a smoothing name: "none", "mean", "median" or "gaussian" (as the CLI writes them).
/// @throws ValueError  naming the accepted values, for any other text.
Smoothing parseSmoothing(std::string_view name);

/// The name parseSmoothing() accepts for `kind`.
std::string smoothingName(Smoothing kind);

}  // namespace sonarmap
