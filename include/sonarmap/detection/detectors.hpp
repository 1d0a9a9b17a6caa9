#pragma once
/// @file detectors.hpp
/// Finding the first obstacle along each beam of a polar image (paper §6, §8.2, §9).
///
/// Every detector returns one BeamDetection per row of the polar image: the first bin, at or beyond
/// `min_range_m` and below the row's `valid_bins`, that the detector calls an obstacle, with the
/// image's intensity at that bin; −1 when the beam has none. Bins nearer than `min_range_m` are
/// never reported (paper §8.2: "measurements that are close to the sonar ... are self-reflections").

#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "sonarmap/detection/cfar.hpp"
#include "sonarmap/detection/detection.hpp"
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// Obstacle detector.
enum class Detector {
  kThreshold,             ///< paper §8.2: first rise between consecutive bins above a threshold
  kCanny,                 ///< paper §9: first Canny edge pixel along the row
  kBackgroundSubtracted,  ///< ours: first run above a per-sweep, per-range background (see below)
  kCfar,                  ///< first run of CFAR detections above an intensity floor along the row
                          ///< (cfar.hpp; Richards ch. 6, Rohling 1983), variant in CfarOptions
};

/// Paper §8.2: an obstacle starts at the first bin c with I[c] − I[c−1] > min_rise (both bins at
/// or beyond the minimum range). Rising edges only: a drop in intensity is not an obstacle.
/// On the CRAS log after the default 11 × 11 Gaussian no rise between neighbouring bins reaches 70,
/// so this finds nothing there; on the raw log it stops at the ≈1.56 m ring or in multipath.
struct ThresholdOptions {
  int min_rise = 70;  ///< intensity step, 0…255; "the threshold that produced the best results is around 70"
};

/// Paper §9: Gaussian blur (kernel 11, σ 2.3), then cv::Canny(low 0, high 113, aperture 3) on the
/// polar image; the obstacle is the first edge pixel along the row.
struct CannyOptions {
  int blur_kernel_size = 11;  ///< odd ≥ 1; 1 skips the blur (e.g. when the image is already smoothed)
  double blur_sigma = 2.3;    ///< Gaussian σ in pixels, ≥ 0 (0: derived from the kernel size)
  double low_threshold = 0.0;
  double high_threshold = 113.0;
  int aperture_size = 3;      ///< Sobel aperture: 3, 5 or 7
};

/// Ours, for MSIS data where something returns at the same range in every bearing (the floor or
/// surface entering the 35° vertical aperture: the ≈1.56 m ring of the CRAS tank data), which the
/// paper's threshold reports as the first obstacle of many beams.
///   1. Background: for each bin (range) c, the `background_percentile` of column c over the rows
///      of the image (one sweep: all bearings at that range). A return at constant range is in
///      most rows and becomes background; a wall is at a given range in few bearings and is not.
///   2. Residual: I[r][c] − background[c].
///   3. The obstacle is the first bin c ≥ min range that starts `min_run_bins` consecutive bins
///      with residual ≥ `min_excess` (the run rejects speckle and short multipath glints).
/// Defaults, chosen on the CRAS tank log (28 sweeps; checked by tests/detection/test_detectors_real.cpp):
/// at the ring's range the 25th percentile is ≈15 and the 90th ≈40 (raw), so an excess of 45 does
/// not fire on it, while the walls' leading edges (100…170) clear it; 8 bins = 10 cm is shorter
/// than a wall echo and longer than speckle. The result held with no, mean, median and Gaussian
/// smoothing alike (≈82 % of detections within 0.15 m of the fitted tank walls, none on the ring).
/// On that log the ring is faint, so the floor and the run do much of the work: without the
/// background (percentile 0) the share on the walls drops to ≈75–78 %, and with a lower floor or a
/// brighter ring (more gain) the ring takes over, which the background prevents.
/// Limits: anything at one range in more than (100 − percentile) % of the rows is background, so a
/// round tank centred on the sonar would vanish; the image should hold a sweep of many bearings
/// (with fewer than `min_beams` rows the background is not estimated and no obstacle is reported;
/// for a partial sweep, build the polar image over the last full turn instead). The intensity
/// scale is the sonar's 0…255 with its gain as logged: another gain needs another min_excess.
struct BackgroundOptions {
  double background_percentile = 25.0;  ///< percentile in [0, 100] of each bin across the rows
  int min_excess = 45;                  ///< residual intensity above background, 1…255
  int min_run_bins = 8;                 ///< consecutive bins above min_excess, ≥ 1
  int min_beams = 20;                   ///< fewest rows to estimate a background, ≥ 1
};

/// Options of detectObstacles(); each detector reads its own part.
struct DetectorOptions {
  Detector kind = Detector::kBackgroundSubtracted;
  /// Bins whose centre is nearer are ignored, metres, ≥ 0. On the CRAS log the self-reflection band
  /// ends at ≈0.35 m, but static returns (the vehicle's own body, present in every sweep) reach
  /// ≈0.8 m at bearings ≈200°…260°, so the default is 1.0 m; the tank walls start at ≈1.65 m.
  double min_range_m = 1.0;
  ThresholdOptions threshold;
  CannyOptions canny;
  BackgroundOptions background;
  CfarOptions cfar;
};

/// Finds the first obstacle of each row of `polar` with the detector `options.kind`.
///
/// @param polar    CV_8UC1 polar image, beams × bins (e.g. one sweep after removeSelfReflection
///                 and smooth), with bin_length_m > 0 and valid_bins for every row.
/// @param options  detector choice and parameters.
/// @return         polar.rows() detections, in row order.
/// @throws ValueError  when the image is not CV_8UC1, lacks valid_bins, has bin_length_m ≤ 0, or an
///   option is out of its documented range.
std::vector<BeamDetection> detectObstacles(const PolarImage& polar, const DetectorOptions& options);

/// The per-bin background of kBackgroundSubtracted: CV_32F, 1 × cols, the `percentile` of each column
/// over the rows whose valid_bins cover it (0 where no row does).
/// @throws ValueError  when percentile is outside [0, 100] or the image is not CV_8UC1.
cv::Mat estimateRangeBackground(const PolarImage& polar, double percentile);

/// Parses a detector name as the CLI writes it: "threshold", "canny", "background", or "cfar-ca",
/// "cfar-so", "cfar-go", "cfar-os" (all four give kCfar; selectDetector() also sets the variant).
/// @throws ValueError  naming the accepted values, for any other text (also for a bare "cfar").
Detector parseDetector(std::string_view name);

/// Sets options.kind and, for a CFAR name, options.cfar.variant from a name parseDetector()
/// accepts; every other option is left as it is.
/// @throws ValueError  naming the accepted values, for any other text.
void selectDetector(DetectorOptions& options, std::string_view name);

/// The name parseDetector() accepts for `kind` (kCfar: "cfar-ca", the CA variant's name).
std::string detectorName(Detector kind);

/// The name selectDetector() accepts for options.kind and, for kCfar, options.cfar.variant.
std::string detectorName(const DetectorOptions& options);

}  // namespace sonarmap
