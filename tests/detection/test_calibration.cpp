/// Self-calibration of a sweep (calibration.hpp) and the background detector's use of it
/// (detectors.hpp) on synthetic sweeps of log-compressed speckle whose statistics are known.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <limits>
#include <random>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/detection/calibration.hpp"
#include "sonarmap/detection/detectors.hpp"

namespace sonarmap {
namespace {

constexpr double kSpan_db = 45.0;

/// One-look speckle: exponential power of mean `mean_db`, log-compressed onto 0…255 over kSpan_db
/// from `low_db` (a Micron's ADlow/ADspan mapping), clipped.
class Speckle {
 public:
  explicit Speckle(std::uint64_t seed) : engine_(seed) {}
  std::uint8_t operator()(double mean_db, double low_db = -20.0) {
    const double power = -std::log(1.0 - uniform_(engine_)) * std::pow(10.0, mean_db / 10.0);
    const double counts = 255.0 * (10.0 * std::log10(power) - low_db) / kSpan_db;
    return static_cast<std::uint8_t>(std::clamp(std::lround(counts), 0L, 255L));
  }

 private:
  std::mt19937_64 engine_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
};

/// A sweep of `rows` beams over a full turn, `bins` bins of `bin_m`, every bin speckle of `mean_db`.
PolarImage noiseSweep(int rows, int bins, double bin_m, double mean_db, std::uint64_t seed = 3) {
  PolarImage polar;
  polar.intensities = cv::Mat(rows, bins, CV_8UC1);
  Speckle speckle(seed);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < bins; ++c) polar.intensities.at<std::uint8_t>(r, c) = speckle(mean_db);
    polar.valid_bins.push_back(bins);
    polar.bearing_rad.push_back(2.0 * std::numbers::pi * r / rows);
    polar.time_s.push_back(0.05 * r);
  }
  polar.bin_length_m = bin_m;
  polar.intensity_span_db = kSpan_db;
  return polar;
}

/// Share of the bins from `first` on whose residual above the background reaches the threshold.
double exceedanceRate(const PolarImage& polar, const SweepCalibration& calibration, int first) {
  std::size_t above = 0, total = 0;
  for (int r = 0; r < polar.rows(); ++r) {
    for (int c = first; c < polar.cols(); ++c, ++total) {
      const auto i = static_cast<std::size_t>(c);
      above += polar.intensities.at<std::uint8_t>(r, c) - calibration.background[i] >= calibration.threshold[i];
    }
  }
  return static_cast<double>(above) / static_cast<double>(total);
}

TEST(detectionCalibration, ThresholdFollowsTheSpeckleModel) {
  CalibrationOptions options;  // 25th percentile, Pfa 1e-6
  EXPECT_NEAR(thresholdDb(options), 16.85, 0.05);  // 10 log10(ln 1e-6 / ln 0.75)
  options.false_alarm_probability = 3.2e-5;
  EXPECT_NEAR(thresholdDb(options), 15.6, 0.05);  // 10 log10(ln 3.2e-5 / ln 0.75)
  options.background_percentile = 50.0;
  EXPECT_NEAR(thresholdDb(options), 11.7, 0.05);  // above the median  // 10 log10(ln 3.2e-5 / ln 0.5)
  options.false_alarm_probability = 1e-3;
  EXPECT_NEAR(thresholdDb(options), 10.0, 0.05);
  options.min_contrast_db = 12.0;
  EXPECT_DOUBLE_EQ(thresholdDb(options), 12.0);  // the floor wins
  options = {};
  options.false_alarm_probability = 0.5;
  EXPECT_THROW(thresholdDb(options), ValueError);
  options = {};
  options.background_percentile = 101.0;
  EXPECT_THROW(thresholdDb(options), ValueError);
}

// On one-look speckle the calibrated threshold is crossed by noise at about the design rate, and
// the same whatever the gain: the background follows the noise floor, the threshold is a ratio.
TEST(detectionCalibration, NoiseCrossesTheThresholdAtTheDesignRateWhateverTheGain) {
  CalibrationOptions options;
  options.false_alarm_probability = 1e-3;
  for (const double mean_db : {5.0, 15.0}) {  // two gains, both well inside the AD's span
    const PolarImage polar = noiseSweep(200, 1000, 0.02, mean_db);
    const SweepCalibration calibration = calibrateSweep(polar, options, kSpan_db);
    const double rate = exceedanceRate(polar, calibration, 100);
    EXPECT_GT(rate, 0.3e-3) << mean_db << " dB";  // quantisation to counts moves it a little
    EXPECT_LT(rate, 3e-3) << mean_db << " dB";
    // The background is the noise's 25th percentile: −5.4 dB re its mean for one-look speckle.
    const double expected = 255.0 * (mean_db - 5.4 + 20.0) / kSpan_db;
    EXPECT_NEAR(calibration.background[500], expected, 6.0) << mean_db << " dB";
  }
}

// In open water the default detector reports nothing: no false obstacle in a sweep of noise.
TEST(detectionCalibration, OpenWaterHasNoFalseObstacle) {
  for (const double bin_m : {0.0125, 0.1}) {
    const PolarImage polar = noiseSweep(200, 400, bin_m, 10.0, 11);
    std::size_t obstacles = 0;
    for (const BeamDetection& d : detectObstacles(polar, DetectorOptions{})) obstacles += d.hasObstacle();
    EXPECT_EQ(obstacles, 0U) << bin_m;
  }
}

// The self-reflection band ends where the median profile falls half-way to the far level; clutter
// seen in more than a tenth of the bearings just after it (the vehicle's own body) extends the
// near field, a return at one range in every bearing (reverberation, a ring) does not.
TEST(detectionCalibration, NearFieldIsTheBandAndTheClutterNextToIt) {
  PolarImage polar = noiseSweep(200, 400, 0.0125, -10.0, 5);  // 5 m of clipped, dark water
  polar.intensities.colRange(0, 24).setTo(200);               // the band: 0–0.30 m
  for (int r = 0; r < 40; ++r) polar.intensities.row(r).colRange(32, 64).setTo(150);  // 20 % of bearings, 0.4–0.8 m
  polar.intensities.colRange(120, 128).setTo(120);            // a ring at 1.5 m in every bearing
  const SweepCalibration calibration = calibrateSweep(polar, CalibrationOptions{}, kSpan_db);
  EXPECT_NEAR(calibration.band_end_m, 0.30, 0.02);
  EXPECT_NEAR(calibration.near_field_end_m, 0.80, 0.02);
  // Without the clutter the near field is the band; a wall in 8 % of the bearings is no clutter.
  PolarImage clean = noiseSweep(200, 400, 0.0125, -10.0, 5);
  clean.intensities.colRange(0, 24).setTo(200);
  for (int r = 0; r < 16; ++r) clean.intensities.row(r).colRange(40, 60).setTo(150);
  EXPECT_NEAR(calibrateSweep(clean, CalibrationOptions{}, kSpan_db).near_field_end_m, 0.30, 0.02);
}

// A floor seen down a slope in a third of the bearings, from just past the band to the end of a
// 10 m scale (the shared Ping360 basin log): clutter by its share of bearings, but no vehicle is
// that long. The near field stops at max_near_field_m and the detector finds the floor's rise in
// the bearings where it rises farther out.
TEST(detectionCalibration, NearFieldClutterEndsWithinTheVehiclesReach) {
  PolarImage polar = noiseSweep(300, 1200, 0.0083, -10.0, 7);  // 10 m of dark water
  polar.intensities.colRange(0, 60).setTo(230);                 // the band: 0–0.5 m
  const auto rise = [](int r) { return r < 100 ? 62 + r % 20 : 360 + 2 * (r - 100); };  // 0.51–0.68, 3.0–4.6 m
  for (int r = 0; r < 200; ++r) polar.intensities.row(r).colRange(rise(r), 1200).setTo(160);
  CalibrationOptions options;
  const SweepCalibration calibration = calibrateSweep(polar, options, kSpan_db);
  EXPECT_NEAR(calibration.band_end_m, 0.50, 0.02);
  EXPECT_NEAR(calibration.near_field_end_m, 2.0, 0.01);
  DetectorOptions detector;
  const std::vector<BeamDetection> found = detectObstacles(polar, detector);
  for (int r = 100; r < 200; ++r) EXPECT_NEAR(found[static_cast<std::size_t>(r)].range_m, (rise(r) + 0.5) * 0.0083, 0.02) << r;
  // Unbounded, the clutter rule takes the whole scale for the vehicle's and finds nothing.
  options.max_near_field_m = std::numeric_limits<double>::infinity();
  EXPECT_GT(calibrateSweep(polar, options, kSpan_db).near_field_end_m, 9.9);
  detector.background.calibration = options;
  for (const BeamDetection& d : detectObstacles(polar, detector)) EXPECT_FALSE(d.hasObstacle());
  options.max_near_field_m = -1.0;
  EXPECT_THROW(options.validate(), ValueError);
}

// A wall far away in few bearings, behind the multipath and reverberation of nearer walls in all
// the others: the background over all bearings at its range is that clutter and would hide it; the
// detector measures the background over the beams still in water there (detectors.hpp).
TEST(detectionCalibration, FarWallBehindNearerWallsClutterIsFound) {
  PolarImage polar = noiseSweep(200, 400, 0.0125, -10.0, 7);
  Speckle speckle(8);
  // 20 % of the bearings see their wall at 3.0 m; the others at 1.2–1.8 m (a wall's range changes
  // with bearing; one range in most bearings would be background), with reverberation behind it.
  auto wallBin = [](int r) { return r % 5 == 0 ? 240 : 96 + (7 * r) % 48; };
  for (int r = 0; r < 200; ++r) {
    const int wall = wallBin(r);
    polar.intensities.row(r).colRange(wall, wall + 8).setTo(200);
    if (r % 5 != 0) {
      for (int c = wall + 8; c < 400; ++c) polar.intensities.at<std::uint8_t>(r, c) = speckle(12.0);
    }
  }
  const std::vector<BeamDetection> found = detectObstacles(polar, DetectorOptions{});
  for (int r = 0; r < 200; ++r) {
    ASSERT_TRUE(found[static_cast<std::size_t>(r)].hasObstacle()) << "row " << r;
    EXPECT_NEAR(found[static_cast<std::size_t>(r)].range_m, (wallBin(r) + 0.5) * 0.0125, 0.013) << "row " << r;
  }
  // Over all bearings the far wall's range is the reverberation: its background there is far higher.
  const SweepCalibration all = calibrateSweep(polar, CalibrationOptions{}, kSpan_db);
  const SweepDetection water = detectSweep(polar, DetectorOptions{});
  EXPECT_GT(all.background[239], water.calibration.background[239] + 40.0f);
  EXPECT_GT(all.background[239] + all.threshold[239], 200.0f);  // it would have hidden the wall
}

// A housing (or the transducer's ring-down) returns at the same ranges, at nearly the same level,
// in every beam whatever the bearing (a fixed reflector, not speckle), while the scene's echoes
// move with bearing: the near field ends at the band's outer edge, found by how many beams hold
// echo at each range, even when the band is too faint for the median's band rule (the shared pool
// bag's Micron: 40–90 counts over black water). Without a band the cut stays at the head.
TEST(detectionCalibration, HousingBandIsFoundByItsPersistenceOverTheBeams) {
  constexpr double kBin_m = 0.025;
  // Walls whose range moves with bearing (a rectangular tank seen from off its centre), 0.9–4.5 m.
  const auto wallBin = [](int r) { return 36 + (r * 7) % 144; };
  // Clipped dark water, and the noise of a high gain; the band 14 dB over the water's mean level,
  // under the threshold (16.9 dB over the 25th percentile) the median's band rule needs.
  for (const double water_db : {-25.0, 0.0}) {
    const double band_counts = std::max(0.0, 255.0 * (water_db + 14.0 + 20.0) / kSpan_db);
    for (const int edge_bins : {12, 20, 31}) {  // housing bands 0.30, 0.50, 0.775 m
      PolarImage polar = noiseSweep(200, 240, kBin_m, water_db, 21);
      for (int r = 0; r < 200; ++r) {
        for (int c = 2; c < edge_bins; ++c) {
          polar.intensities.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(band_counts - 8.0 + (r * 5 + c * 3) % 17);
        }
        polar.intensities.row(r).colRange(wallBin(r), wallBin(r) + 4).setTo(220);
      }
      const SweepCalibration calibration = calibrateSweep(polar, CalibrationOptions{}, kSpan_db);
      const double edge_m = edge_bins * kBin_m;
      EXPECT_NEAR(calibration.near_field_end_m, edge_m, 2.0 * kBin_m) << water_db << " dB, edge " << edge_m << " m";
      EXPECT_NEAR(calibration.housing_end_m, edge_m, 2.0 * kBin_m) << water_db << " dB, edge " << edge_m << " m";
      // The same sweep without the band: nothing at the head is the housing.
      PolarImage bare = noiseSweep(200, 240, kBin_m, water_db, 21);
      for (int r = 0; r < 200; ++r) bare.intensities.row(r).colRange(wallBin(r), wallBin(r) + 4).setTo(220);
      const SweepCalibration none = calibrateSweep(bare, CalibrationOptions{}, kSpan_db);
      EXPECT_LE(none.housing_end_m, kBin_m) << water_db << " dB";
      EXPECT_LE(none.near_field_end_m, kBin_m) << water_db << " dB";
    }
  }
}

TEST(detectionCalibration, InvalidInputThrows) {
  PolarImage polar = noiseSweep(10, 20, 0.01, 0.0);
  EXPECT_THROW(calibrateSweep(polar, CalibrationOptions{}, 0.0), ValueError);
  CalibrationOptions options;
  options.clutter_share = 0.0;
  EXPECT_THROW(calibrateSweep(polar, options, kSpan_db), ValueError);
  options = {};
  options.max_gap_m = -1.0;
  EXPECT_THROW(calibrateSweep(polar, options, kSpan_db), ValueError);
  polar.valid_bins.pop_back();
  EXPECT_THROW(calibrateSweep(polar, CalibrationOptions{}, kSpan_db), ValueError);
}

}  // namespace
}  // namespace sonarmap

namespace sonarmap {
namespace {

/// A sweep whose row r holds, over clipped dark water, the echo of a wall at surface_m(r): its
/// power rises linearly over the pulse (each bin sums the pulse length before it, as a receiver
/// does), then holds a plateau 30 dB above the AD's low level for `plateau_m`.
template <class SurfaceOf>
PolarImage wallEchoes(int rows, double bin_m, double pulse_m, SurfaceOf surface_m) {
  const int bins = static_cast<int>(std::lround(6.0 / bin_m));
  PolarImage polar = noiseSweep(rows, bins, bin_m, -30.0, 9);
  for (int r = 0; r < rows; ++r) {
    const double d = surface_m(r);
    for (int c = 0; c < bins; ++c) {
      // Energy of [d, d + plateau) received within this bin's pulse window ((c + 1) L − pulse, (c + 1) L].
      const double window_end = (c + 1) * bin_m, window_start = window_end - pulse_m;
      const double overlap = std::max(0.0, std::min(window_end, d + 0.3) - std::max(window_start, d));
      if (overlap <= 0.0) continue;
      const double level_db = 30.0 + 10.0 * std::log10(overlap / pulse_m);
      const double counts = 255.0 * (level_db - 0.0) / kSpan_db;
      polar.intensities.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(std::clamp(std::lround(counts), 0L, 255L));
    }
  }
  return polar;
}

// The obstacle's range is the echo's leading edge: not moved nearer (as smoothing would), not
// farther to the peak a pulse later; in metres the same whatever the bin length.
TEST(detectionLeadingEdge, RangeIsTheLeadingEdgeWhateverTheBinLength) {
  for (const double bin_m : {0.0125, 0.0417, 0.1}) {
    for (const double pulse_in_bins : {1.0, 4.0}) {
      const double pulse_m = pulse_in_bins * bin_m;
      // Surfaces at every fraction of a bin, 1.5–4.5 m, a different range per bearing.
      auto surface = [&](int r) { return 1.5 + 3.0 * r / 200.0 + 0.37 * bin_m * (r % 7) / 7.0; };
      const PolarImage polar = wallEchoes(200, bin_m, pulse_m, surface);
      const std::vector<BeamDetection> found = detectObstacles(polar, DetectorOptions{});
      std::vector<double> errors;
      for (int r = 0; r < 200; ++r) {
        ASSERT_TRUE(found[static_cast<std::size_t>(r)].hasObstacle()) << bin_m << " row " << r;
        errors.push_back(found[static_cast<std::size_t>(r)].range_m - surface(r));
      }
      std::nth_element(errors.begin(), errors.begin() + 100, errors.end());
      const double median = errors[100];
      // 6 dB below the plateau is a quarter pulse behind the surface; the bin's centre adds ±½ bin.
      EXPECT_GE(median, -0.5 * bin_m - 1e-9) << bin_m << " m bins, pulse " << pulse_m;
      EXPECT_LE(median, 0.25 * pulse_m + 0.5 * bin_m + 1e-9) << bin_m << " m bins, pulse " << pulse_m;
      EXPECT_LT(median, pulse_m) << "not the peak";
    }
  }
}

}  // namespace
}  // namespace sonarmap
