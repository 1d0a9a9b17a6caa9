#pragma once
/// @file calibration.hpp
/// Self-calibration of one sweep: what the sonar records where there is no obstacle, measured on
/// the sweep itself, so that thresholds follow each log's gain, noise and range scale instead of
/// fixed intensities.
///
/// On a polar image of one sweep (rows = beams, columns = bins):
///  - Background B(c): the `background_percentile` of column c over the rows (all bearings at that
///    range). What returns at the same range in most bearings — the transducer's ringing, the
///    surface or seabed entering the vertical aperture (the CRAS log's ring at 1.56 m), the
///    near-field reverberation of a high-gain head — is background, not an obstacle.
///  - Noise spread σ(c): (Q50(c) − Q25(c)) / 0.674, the spread of a Gaussian with those quartiles,
///    from the lower half of column c only, so obstacles in up to half of the bearings do not
///    inflate it; then the median over ±noise_window_m along the beam (a wall filling many bearings
///    at a few ranges does not either). 0 where the noise is clipped at the AD converter's low level.
///  - Threshold T(c) on the residual I − B(c), intensity counts: max(min_contrast_db converted with
///    the log's dB span, κ σ(c)) with κ = Φ⁻¹(1 − false_alarm_probability) (a Gaussian model of the
///    residual's spread; the required echo length makes a run of noise rarer still).
///  - Near field: the self-reflection band ends where the median profile (median of each column)
///    falls below half-way between its peak within the first quarter of the range and the median
///    of the far half. The near-field clutter then extends, contiguous with the band (gaps shorter
///    than max_gap_m bridged), over the ranges where at least `clutter_share` of the bearings rise
///    above the threshold (the (1 − clutter_share) quantile of the column minus B(c) ≥ T(c)): the
///    vehicle's own body and fixtures seen in many bearings at short range. On the CRAS log the
///    band ends at ≈ 0.3 m and the vehicle's returns at ≈ 0.8 m; on the SeaNet sector log the band
///    ends at ≈ 0.6 m and nothing follows it (its near-field reverberation is background).

#include <vector>

#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// Options of the per-sweep calibration (see the file's comment for each definition).
struct CalibrationOptions {
  double background_percentile = 25.0;  ///< percentile in [0, 100] of each column over the rows
  /// Least rise of an echo above the background, dB, ≥ 0: used where the noise is clipped (σ = 0)
  /// or below it. 8 dB is 45 counts on a 45 dB scale.
  double min_contrast_db = 8.0;
  /// Probability, per bin, that noise alone exceeds κ σ, in (0, 0.5): κ = 4.0 at 3.2 × 10⁻⁵.
  double false_alarm_probability = 3.2e-5;
  double noise_window_m = 0.5;  ///< half-width of the window σ's median is taken over, metres, ≥ 0
  double clutter_share = 0.10;  ///< share of bearings that makes a range near-field clutter, (0, 0.5]
  double max_gap_m = 0.10;      ///< clutter-free stretch that ends the near field, metres, ≥ 0

  /// @throws ValueError naming the option when it is outside its range or not finite.
  void validate() const;
};

/// One sweep's calibration (see the file's comment). Vectors hold one value per column.
struct SweepCalibration {
  std::vector<float> background;  ///< B(c), intensity counts
  std::vector<float> noise_sigma; ///< σ(c), intensity counts
  std::vector<float> threshold;   ///< T(c), intensity counts above B(c)
  double span_db = 0.0;           ///< dB span of the intensity scale used for min_contrast_db
  double band_end_m = 0.0;        ///< end of the self-reflection band, metres
  double near_field_end_m = 0.0;  ///< end of the near-field clutter (≥ band_end_m), metres
};

/// Calibrates one sweep over all its rows. `span_db`: the dB span of the intensities
/// (intensitySpan_db of the image, or an override). The background detector measures B, σ and T
/// again over the beams still in water at each range (detectors.hpp); the band and the near field
/// are this function's. Cost: O(rows × cols + 256 × cols) (a histogram per column).
/// @throws ValueError for invalid options, an image that is not CV_8UC1 with bin_length_m > 0 and
///         one valid_bins entry per row, or a span that is not finite and > 0.
SweepCalibration calibrateSweep(const PolarImage& polar, const CalibrationOptions& options, double span_db);

/// T for a noise spread σ: max(min_contrast_db in counts, κ σ) (see the file's comment).
/// @throws ValueError when span_db is not finite and > 0.
float thresholdFor(float sigma, const CalibrationOptions& options, double span_db);

/// The median of values[c − half_window … c + half_window] (clipped to the vector) for every c.
std::vector<float> windowedMedian(const std::vector<float>& values, int half_window);

/// κ of the threshold: the standard normal quantile Φ⁻¹(1 − p), by bisection on std::erfc.
/// @throws ValueError when p is not in (0, 0.5).
double gaussianQuantile(double upper_tail_probability);

}  // namespace sonarmap
