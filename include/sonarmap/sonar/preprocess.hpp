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

/// Options of smooth(), in physical units converted with each image's bin length and beam spacing
/// (polar_units.hpp). The default is no smoothing: every filter spreads an echo's leading edge
/// towards the sonar (a Gaussian of σ along the beam moves a threshold crossing nearer by about
/// 2σ: 5 cm on the CRAS Micron with the paper's kernel), while the detectors already reject
/// speckle by the echo length they require. When chosen, the extents default to the paper's
/// Gaussian (§9: kernel 11, σ 2.3 pixels on the Micron's 1.25 cm bins and 1.8° steps): σ 2.9 cm
/// along the beam and 4.1° across beams.
struct SmoothingOptions {
  Smoothing kind = Smoothing::kNone;
  /// Along the beam, metres, ≥ 0. Gaussian: σ (the kernel spans ±3σ); mean and median: the
  /// kernel's length. Rounded to whole bins; less than half a bin does not smooth along the beam.
  double range_m = 0.029;
  /// Across beams, radians, ≥ 0. Gaussian: σ; mean: the kernel's width; median: not used (OpenCV's
  /// median kernel is square: its side is the range extent in bins).
  double bearing_rad = 4.1 * 3.14159265358979323846 / 180.0;

  /// @throws ValueError when an extent is negative or not finite.
  void validate() const;
};

/// Smooths the polar image in place: cv::GaussianBlur (kGaussian), cv::blur (kMean) or
/// cv::medianBlur (kMedian) with the kernel of `options` in pixels (at most 255 on a side, odd);
/// nothing for kNone. Borders are reflected (OpenCV's BORDER_REFLECT_101), also across the first
/// and last beam.
///
/// @throws ValueError when the options are invalid or the image is not CV_8UC1 with
///   bin_length_m > 0.
void smooth(PolarImage& polar, const SmoothingOptions& options);

/// Parses a smoothing name: "none", "mean", "median" or "gaussian" (as the CLI writes them).
/// @throws ValueError  naming the accepted values, for any other text.
Smoothing parseSmoothing(std::string_view name);

/// The name parseSmoothing() accepts for `kind`.
std::string smoothingName(Smoothing kind);

}  // namespace sonarmap
