#pragma once
/// @file detectors.hpp
/// Finding the first obstacle along each beam of a polar image (paper §6, §8.2, §9).
///
/// Every detector returns one BeamDetection per row of the polar image: the first bin, at or beyond
/// the minimum range and below the row's `valid_bins`, that the detector calls an obstacle, with
/// the image's intensity at that bin and the range of the echo's leading edge; −1 when the beam
/// has none. Bins nearer than the minimum range are never reported (paper §8.2: "measurements that
/// are close to the sonar ... are self-reflections").

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "sonarmap/detection/calibration.hpp"
#include "sonarmap/detection/cfar.hpp"
#include "sonarmap/detection/detection.hpp"
#include "sonarmap/detection/reverberation.hpp"
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// Obstacle detector.
enum class Detector {
  kThreshold,             ///< paper §8.2: first rise between consecutive bins above a threshold
  kCanny,                 ///< paper §9: first Canny edge pixel along the row
  kBackgroundSubtracted,  ///< ours: first echo above the calibrated background (below)
  kCfar,                  ///< first run of CFAR detections above a level floor along the row
                          ///< (cfar.hpp; Richards ch. 6, Rohling 1983), variant in CfarOptions
  kEvidence,              ///< ours, the default: the background detector's loud echoes, and where a
                          ///< beam has none, its first return certain by each bin's evidence
                          ///< against the water measured where it is water (water_evidence.hpp)
};

/// Paper §8.2: an obstacle starts at the first bin c with I[c] − I[c−1] above min_rise_db (both
/// bins at or beyond the minimum range). Rising edges only: a drop in intensity is not an obstacle.
/// The paper's "around 70" of 255 on its Micron data is 12.4 dB on a 45 dB scale.
struct ThresholdOptions {
  double min_rise_db = 12.4;  ///< rise between consecutive bins, dB, ≥ 0
};

/// Paper §9: Gaussian blur (the paper's kernel 11, σ 2.3 pixels on the Micron: 2.9 cm along the
/// beam, 4.1° across), then cv::Canny(low 0, high 113 of 255, aperture 3) on the polar image; the
/// obstacle is the first edge pixel along the row. Canny's thresholds apply to the Sobel gradient
/// of the intensities and are given here in dB of intensity (113 of 255 on a 45 dB scale: 19.9 dB).
struct CannyOptions {
  double blur_range_m = 0.029;                                     ///< Gaussian σ along the beam, metres, ≥ 0
  double blur_bearing_rad = 4.1 * 3.14159265358979323846 / 180.0;  ///< Gaussian σ across beams, radians, ≥ 0
  double low_threshold_db = 0.0;                                   ///< hysteresis low threshold, dB, ≥ 0
  double high_threshold_db = 19.9;                                 ///< hysteresis high threshold, dB, ≥ low
  int aperture_size = 3;  ///< Sobel operator's size: 3, 5 or 7 (a discrete stencil, not a length)
};

/// Ours (and the evidence detector's loud echoes): the first echo that rises above what the sweep
/// records at the same range in most bearings, by more than the sweep's own noise allows
/// (calibration.hpp):
///   1. calibrate the sweep: background B(c), threshold T from the speckle model and the
///      false-alarm probability, near field (calibration.hpp);
///   2. the obstacle is the first bin c at or beyond the minimum range that starts a run of
///      min_echo_length_m (at least one bin) with I − B ≥ T(c) all along; within the near field's
///      bound B is at least the beam's own ring-down (SweepCalibration::ring_down raised by the
///      beam's offset: a louder ping rings longer, and its tail is not an echo), and on a beam still
///      in an echo where the minimum range cuts it, at least the lowest level the beam has come down
///      to since (its floor, until it reaches the water's level: the cut's edge and the
///      reverberation that only fades beyond it are no return, an echo rising out of it is);
///   3. its range is the echo's leading edge, the nearest surface within the beam: from the foot of
///      the rise (back from c while the echo stays above T / 2), the centre of the first bin within
///      leading_edge_db of the echo's peak (sought within 0.3 m of c). A wall seen at
///      an angle returns its nearest point from the edge of the −3 dB beam, 6 dB (two-way) below
///      the axis, so the echo's rise mirrors the beam pattern and 6 dB below the peak is the nearest
///      surface within the nominal width; a crossing lower on the rise of a strong echo reaches
///      into the pattern's skirt, beyond that width (at long range, metres of it), one higher lies
///      behind the surface. At normal incidence the rise is the pulse's: 6 dB below its plateau is
///      a quarter of a pulse length behind the surface (docs/accuracy.md measures the result).
/// The constant-range ring (the surface or seabed entering the vertical aperture: CRAS's 1.56 m)
/// is in every bearing and so in B; a wall is at one range in few bearings and is not. Limits:
/// anything at one range in more than (100 − percentile) % of the bearings is background, so a
/// round tank centred on the sonar would vanish; with fewer than `min_beams` rows the background is
/// not estimated and no obstacle is reported (mapSonarLog joins a short sweep to its neighbour).
struct BackgroundOptions {
  CalibrationOptions calibration;   ///< background percentile, contrast, false-alarm rate, near field
  /// Least extent of an echo along the beam, metres, ≥ 0 (≥ 1 bin); never more than the log's
  /// pulse where it records one (Beam::pulse_length_m: a Ping360 at 2 m sends 8 mm).
  double min_echo_length_m = 0.04;
  double leading_edge_db = 6.0;     ///< the leading edge is within this of the echo's peak, dB, ≥ 0
  int min_beams = 20;               ///< fewest rows (beams) to estimate a background, ≥ 1
  /// The evidence detector's water band, metres, ≥ 0 (at least 8 bins): the water's excess
  /// distribution at a range is measured over this much range in front of it and at it.
  double water_band_m = 0.1;
};

/// Options of detectObstacles(); each detector reads its own part. All in physical units,
/// converted with each image's bin length, beam spacing and intensity scale (polar_units.hpp).
struct DetectorOptions {
  Detector kind = Detector::kEvidence;
  /// Bins whose centre is nearer are never reported, metres, ≥ 0 (paper §8.2: "measurements that
  /// are close to the sonar ... are self-reflections"). Unset: the near-field clutter extent
  /// estimated on each sweep (calibration.hpp: CRAS ≈ 0.26 m, the SeaNet sector log ≈ 0.59 m).
  std::optional<double> min_range_m;
  /// dB span of the intensities 0…255, > 0. Unset: the log's (SeaNet's ADspan), else 45 dB.
  std::optional<double> intensity_span_db;
  ThresholdOptions threshold;
  CannyOptions canny;
  BackgroundOptions background;
  /// The evidence detector's local reverberation level and echo span (reverberation.hpp).
  ReverberationOptions reverberation;
  CfarOptions cfar;
  /// Echo onset (BeamDetection::echo_onset_m), whatever the detector: the first window of
  /// max(onset_length_m, 8 bins) at or beyond the minimum range whose mean rise above the sweep's
  /// background B(c) (intensity counts, signed) reaches L = m + (T_dB − m) / √N dB, N the window's
  /// bins, T_dB the sweep's obstacle threshold (calibration.hpp) and m = 2.9 dB the mean of
  /// one-look speckle in dB above its 25th percentile (E[10 log₁₀ X] − 10 log₁₀ q₀.₂₅ for
  /// exponential X): the threshold's margin over the noise, shrunk as averaging N bins shrinks the
  /// noise's spread. Far below an obstacle's threshold: weak, extended returns (a seabed at grazing
  /// incidence, the edge of the beam on a wall) are not obstacles, but they prove the beam met
  /// something there, so the beam-volume model clears no farther.
  double onset_length_m = 0.2;  ///< metres, ≥ 0
  /// The beams' horizontal −3 dB width, radians, in [0, π) (the mapper sets it from
  /// MapperOptions::beam_width_rad): the evidence detector takes a weak return within this of a
  /// beam whose loud return lies at the same range for that surface heard in the pattern's skirt.
  double beam_width_rad = 3.0 * 3.14159265358979323846 / 180.0;

  /// @throws ValueError naming the option when the minimum range, the span, the beam width or the
  ///         chosen detector's options are outside their documented ranges.
  void validate() const;
};

/// Why beams found no obstacle: what a user needs to see when a map comes out empty.
struct DetectionDiagnostics {
  std::size_t beams = 0;      ///< rows searched
  std::size_t obstacles = 0;  ///< rows with an obstacle
  /// Rows without an obstacle whose echo rises above the threshold between the self-reflection
  /// band's end and the minimum range: obstacles the minimum range may hide.
  std::size_t echoes_before_min_range = 0;
  /// Over the sweeps with such echoes, the nearest self-reflection band's end and the farthest
  /// minimum range, metres: where they were hidden (+∞ and 0 when none were).
  double hidden_from_m = std::numeric_limits<double>::infinity();
  double hidden_to_m = 0.0;
  /// Rows without an obstacle with an echo above the threshold shorter than min_echo_length_m.
  std::size_t echoes_too_short = 0;
  double reach_m = 0.0;  ///< the longest row's range (valid bins × bin length), metres

  DetectionDiagnostics& operator+=(const DetectionDiagnostics& other);
};

/// One sweep's detections with the calibration they were made with.
struct SweepDetection {
  std::vector<BeamDetection> detections;  ///< one per row
  SweepCalibration calibration;           ///< background, threshold, near field (calibration.hpp)
  double min_range_m = 0.0;               ///< the minimum range used: the option, or the near-field end
  DetectionDiagnostics diagnostics;
};

/// Calibrates the sweep (calibrateSweep with options.background.calibration) and finds the first
/// obstacle of each row with the detector `options.kind`; the calibration's background and near
/// field serve every detector (the minimum range when unset, the CFAR's floor).
/// @throws ValueError  as detectObstacles().
SweepDetection detectSweep(const PolarImage& polar, const DetectorOptions& options);

/// As above with a calibration made beforehand (e.g. on the image before smoothing, or before the
/// self-reflection band was zeroed): one value per column of `polar`.
/// @throws ValueError  as detectObstacles(), or when the calibration's length differs from the columns.
SweepDetection detectSweep(const PolarImage& polar, const DetectorOptions& options, const SweepCalibration& calibration);

/// As detectSweep with a calibration, for a few beams of a sweep in progress (one is enough: live
/// mapping's provisional beams): `calibration` is one an earlier sweep was detected
/// with (SweepDetection::calibration), its background B(c) used as it is where detectSweep would
/// measure it again over the rows still in water, and min_beams does not apply. On the beams of a
/// sweep it gives what detectSweep gives when the water background of that sweep is the earlier one's.
/// @throws ValueError  as detectSweep with a calibration.
SweepDetection detectRows(const PolarImage& polar, const DetectorOptions& options, const SweepCalibration& calibration);

/// Finds the first obstacle of each row of `polar` with the detector `options.kind`.
///
/// @param polar    CV_8UC1 polar image, beams × bins (e.g. one sweep after removeSelfReflection
///                 and smooth), with bin_length_m > 0 and valid_bins for every row.
/// @param options  detector choice and parameters.
/// @return         polar.rows() detections, in row order.
/// @throws ValueError  when the image is not CV_8UC1, lacks valid_bins, has bin_length_m ≤ 0, or an
///   option is out of its documented range.
std::vector<BeamDetection> detectObstacles(const PolarImage& polar, const DetectorOptions& options);

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
