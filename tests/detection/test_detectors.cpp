/// Tests of the obstacle detectors on synthetic polar images.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <vector>

#include <opencv2/core.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/sonar/preprocess.hpp"

namespace sonarmap {
namespace {

constexpr int kRows = 60;
constexpr int kBins = 200;
constexpr double kBinLength_m = 0.02;  // 4 m of range

PolarImage emptySweep(int rows = kRows, int bins = kBins) {
  PolarImage polar;
  polar.intensities = cv::Mat::zeros(rows, bins, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(polar.intensities, cv::RNG::UNIFORM, 0, 11);  // speckle 0…10
  for (int r = 0; r < rows; ++r) {
    polar.valid_bins.push_back(bins);
    polar.bearing_rad.push_back(2.0 * std::numbers::pi * r / rows);
    polar.time_s.push_back(0.1 * r);
  }
  polar.bin_length_m = kBinLength_m;
  polar.intensity_span_db = 255.0;  // one count per dB: thresholds in dB read as counts
  return polar;
}

/// First bin of the synthetic wall in row r: bins 100…157 (2.0…3.2 m), a different range per bearing.
int wallBin(int r) { return 100 + (3 * r) % 58; }

/// Adds a 10-bin wall echo of `value` at wallBin(r) in every row.
void addWall(PolarImage& polar, std::uint8_t value) {
  for (int r = 0; r < polar.rows(); ++r) polar.intensities.row(r).colRange(wallBin(r), wallBin(r) + 10).setTo(value);
}

/// Adds the constant-range return: bins 78…81 (≈1.56…1.64 m) in every row.
void addRing(PolarImage& polar, std::uint8_t value) { polar.intensities.colRange(78, 82).setTo(value); }

DetectorOptions optionsFor(Detector kind) {
  DetectorOptions options;
  options.kind = kind;
  return options;
}

TEST(sonarDetectors, ThresholdFindsTheFirstRiseAboveTheThreshold) {
  PolarImage polar = emptySweep();
  addWall(polar, 150);
  const auto found = detectObstacles(polar, optionsFor(Detector::kThreshold));
  ASSERT_EQ(found.size(), static_cast<std::size_t>(kRows));
  for (int r = 0; r < kRows; ++r) {
    EXPECT_EQ(found[r].obstacle_bin, wallBin(r)) << "row " << r;
    EXPECT_EQ(found[r].intensity, 150);
  }
  DetectorOptions high = optionsFor(Detector::kThreshold);
  high.threshold.min_rise_db = 150.0;  // the rise is at most 150 − 0: "exceeds" means strictly more
  for (const auto& d : detectObstacles(polar, high)) EXPECT_FALSE(d.hasObstacle());
}

/// Canny with the paper's thresholds (0 and 113 of 255: the synthetic sweeps count one dB per count).
DetectorOptions paperCanny() {
  DetectorOptions options = optionsFor(Detector::kCanny);
  options.canny.low_threshold_db = 0.0;
  options.canny.high_threshold_db = 113.0;
  return options;
}

TEST(sonarDetectors, CannyFindsTheStepEdge) {
  PolarImage polar = emptySweep();
  for (int r = 0; r < kRows; ++r) polar.intensities.row(r).colRange(120, kBins).setTo(200);
  const auto found = detectObstacles(polar, paperCanny());
  for (int r = 0; r < kRows; ++r) {
    ASSERT_TRUE(found[r].hasObstacle()) << "row " << r;
    EXPECT_NEAR(found[r].obstacle_bin, 120, 1) << "row " << r;
  }
}

TEST(sonarDetectors, CannyFindsASlopedWallEdge) {
  // Canny runs on the 2D image: a wall that moves 1 bin per beam gives one clean edge along it.
  PolarImage polar = emptySweep();
  for (int r = 0; r < kRows; ++r) polar.intensities.row(r).colRange(100 + r, 110 + r).setTo(200);
  const auto found = detectObstacles(polar, paperCanny());
  int near = 0;
  for (int r = 0; r < kRows; ++r) near += found[r].hasObstacle() && std::abs(found[r].obstacle_bin - (100 + r)) <= 2;
  EXPECT_GE(near, kRows * 9 / 10);
}

TEST(sonarDetectors, DetectorsDoNotChangeTheirInput) {
  PolarImage polar = emptySweep();
  addRing(polar, 90);
  addWall(polar, 150);
  const cv::Mat before = polar.intensities.clone();
  for (Detector kind : {Detector::kThreshold, Detector::kCanny, Detector::kBackgroundSubtracted}) {
    detectObstacles(polar, optionsFor(kind));
    EXPECT_EQ(cv::countNonZero(polar.intensities != before), 0) << detectorName(kind);
  }
}

TEST(sonarDetectors, BackgroundSubtractedFindsTheWallLeadingEdge) {
  PolarImage polar = emptySweep();
  addWall(polar, 150);
  const auto found = detectObstacles(polar, optionsFor(Detector::kBackgroundSubtracted));
  for (int r = 0; r < kRows; ++r) {
    EXPECT_EQ(found[r].obstacle_bin, wallBin(r)) << "row " << r;
    EXPECT_EQ(found[r].intensity, 150);
  }
}

TEST(sonarDetectors, AnEchoAsShortAsTheLogsPulseIsAnObstacle) {
  // A Ping360 at 2 m: 1.65 mm samples and an 8.25 mm pulse (11 µs); a wall at normal incidence
  // returns an echo of about the pulse, 5 samples, far shorter than the 4 cm default echo length.
  PolarImage polar = emptySweep(kRows, 1200);
  polar.bin_length_m = 0.00165;
  for (int r = 0; r < kRows; ++r) polar.intensities.row(r).colRange(500 + r, 505 + r).setTo(150);
  const DetectorOptions options = optionsFor(Detector::kBackgroundSubtracted);
  for (const BeamDetection& found : detectObstacles(polar, options)) EXPECT_EQ(found.obstacle_bin, -1);
  polar.pulse_length_m = 0.00825;
  const auto found = detectObstacles(polar, options);
  for (int r = 0; r < kRows; ++r) EXPECT_EQ(found[r].obstacle_bin, 500 + r) << "row " << r;
  // speckle of one or two samples stays below the pulse's length and is no obstacle
  PolarImage speckle = emptySweep(kRows, 1200);
  speckle.bin_length_m = 0.00165;
  speckle.pulse_length_m = 0.00825;
  for (int r = 0; r < kRows; ++r) speckle.intensities.row(r).colRange(500 + r, 502 + r).setTo(150);
  for (const BeamDetection& spike : detectObstacles(speckle, options)) EXPECT_EQ(spike.obstacle_bin, -1);
  // the pulse only lowers the echo length asked for: a longer pulse leaves the 4 cm rule as it is
  polar.pulse_length_m = 0.2;
  for (const BeamDetection& none : detectObstacles(polar, options)) EXPECT_EQ(none.obstacle_bin, -1);
}

// A loud echo ends where it falls below half the threshold over the background for the echo length
// (2 bins of 2 cm): a one-bin speckle dip inside it does not end it, a two-bin one does, and a weak
// tail behind it (9 counts at one count per dB, under half of the 16.8 dB threshold over the
// background: a seabed behind a quay's foot) is not part of it. Beams without an obstacle have no end.
TEST(sonarDetectors, TheEchoEndsWhereItFallsBelowHalfTheThreshold) {
  PolarImage polar = emptySweep();
  for (int r = 0; r < kRows; ++r) {
    if (r % 10 == 0) continue;  // no obstacle
    cv::Mat row = polar.intensities.row(r);
    row.colRange(wallBin(r), wallBin(r) + 12).setTo(150);
    row.colRange(wallBin(r) + 12, wallBin(r) + 32).setTo(9);  // the weak tail
    row.colRange(wallBin(r) + 4, wallBin(r) + (r % 2 == 0 ? 6 : 5)).setTo(0);  // a dip of 2 or 1 bins
  }
  const std::vector<BeamDetection> found = detectObstacles(polar, optionsFor(Detector::kBackgroundSubtracted));
  for (int r = 0; r < kRows; ++r) {
    if (r % 10 == 0) {
      EXPECT_FALSE(found[r].hasObstacle()) << "row " << r;
      EXPECT_TRUE(std::isnan(found[r].echo_end_m)) << "row " << r;
      continue;
    }
    ASSERT_EQ(found[r].obstacle_bin, wallBin(r)) << "row " << r;
    const int last = r % 2 == 0 ? wallBin(r) + 3 : wallBin(r) + 11;
    EXPECT_NEAR(found[r].echo_end_m, (last + 0.5) * kBinLength_m, 1e-9) << "row " << r;
  }
}

TEST(sonarDetectors, ConstantRangeRingIsIgnoredButTheWallBehindIsFound) {
  PolarImage polar = emptySweep();
  addRing(polar, 90);
  addWall(polar, 150);
  // The paper's threshold stops at the ring in every beam (rise 90 − ≤10 > 70)…
  for (const auto& d : detectObstacles(polar, optionsFor(Detector::kThreshold))) EXPECT_EQ(d.obstacle_bin, 78);
  // …the background-subtracted detector sees through it, raw or after the paper's Gaussian.
  const auto raw = detectObstacles(polar, optionsFor(Detector::kBackgroundSubtracted));
  PolarImage smoothed = polar;
  smooth(smoothed, SmoothingOptions{Smoothing::kGaussian});
  const auto after = detectObstacles(smoothed, optionsFor(Detector::kBackgroundSubtracted));
  for (int r = 0; r < kRows; ++r) {
    EXPECT_EQ(raw[r].obstacle_bin, wallBin(r)) << "row " << r;
    ASSERT_TRUE(after[r].hasObstacle()) << "row " << r;
    // The blur across beams (σ 4.1°, 0.7 rows here) brings a neighbour's nearer wall into the row:
    // the detection lies between the nearest wall of the neighbours and the row's own.
    const int nearest = std::min({wallBin((r + kRows - 1) % kRows), wallBin(r), wallBin((r + 1) % kRows)});
    EXPECT_GE(after[r].obstacle_bin, nearest - 5) << "row " << r;  // σ 2.9 cm = 1.45 bins along
    EXPECT_LE(after[r].obstacle_bin, wallBin(r) + 5) << "row " << r;
  }
}

TEST(sonarDetectors, MinRangeAndValidBinsAreHonoured) {
  for (Detector kind : {Detector::kThreshold, Detector::kCanny, Detector::kBackgroundSubtracted}) {
    PolarImage polar = emptySweep();
    for (int r = 0; r < kRows; r += 2) polar.intensities.row(r).colRange(20, 30).setTo(200);  // 0.4 m, half the rows
    addWall(polar, 200);
    polar.valid_bins[1] = 90;  // row 1 ends before its wall
    DetectorOptions options = optionsFor(kind);
    options.min_range_m = 1.0;  // bin 50
    const auto found = detectObstacles(polar, options);
    for (int r = 0; r < kRows; ++r) {
      if (found[r].hasObstacle()) {
        EXPECT_GE(found[r].obstacle_bin, 50) << detectorName(kind) << " row " << r;
      }
    }
    EXPECT_FALSE(found[1].hasObstacle()) << detectorName(kind);
    options.min_range_m = 0.3;
    EXPECT_NEAR(detectObstacles(polar, options)[0].obstacle_bin, 20, 2) << detectorName(kind);
  }
}

TEST(sonarDetectors, BackgroundNeedsEnoughBeams) {
  PolarImage polar = emptySweep(5);
  for (int r = 0; r < 5; ++r) polar.intensities.row(r).colRange(60 + 25 * r, 70 + 25 * r).setTo(200);
  for (const auto& d : detectObstacles(polar, optionsFor(Detector::kBackgroundSubtracted))) {
    EXPECT_FALSE(d.hasObstacle());  // 5 < min_beams = 20: no background, no obstacle
  }
  DetectorOptions options = optionsFor(Detector::kBackgroundSubtracted);
  options.background.min_beams = 5;
  const auto found = detectObstacles(polar, options);
  for (int r = 0; r < 5; ++r) EXPECT_EQ(found[r].obstacle_bin, 60 + 25 * r) << "row " << r;
}

TEST(sonarDetectors, InvalidOptionsAndImagesThrow) {
  const PolarImage polar = emptySweep();
  DetectorOptions options;
  options.min_range_m = -1.0;
  EXPECT_THROW(detectObstacles(polar, options), ValueError);
  options = optionsFor(Detector::kCanny);
  options.canny.aperture_size = 4;
  EXPECT_THROW(detectObstacles(polar, options), ValueError);
  options = optionsFor(Detector::kBackgroundSubtracted);
  options.background.min_echo_length_m = -0.01;
  EXPECT_THROW(detectObstacles(polar, options), ValueError);
  options = optionsFor(Detector::kThreshold);
  options.threshold.min_rise_db = -1.0;
  EXPECT_THROW(detectObstacles(polar, options), ValueError);
  PolarImage missing = polar;
  missing.valid_bins.pop_back();
  EXPECT_THROW(detectObstacles(missing, DetectorOptions{}), ValueError);
}

TEST(sonarDetectors, DetectorNamesRoundTrip) {
  for (Detector kind : {Detector::kThreshold, Detector::kCanny, Detector::kBackgroundSubtracted}) {
    EXPECT_EQ(parseDetector(detectorName(kind)), kind);
  }
  EXPECT_EQ(detectorName(Detector::kBackgroundSubtracted), "background");
  EXPECT_THROW(parseDetector("cfar"), ValueError);
  EXPECT_EQ(DetectorOptions{}.kind, Detector::kEvidence);
  EXPECT_EQ(parseDetector("evidence"), Detector::kEvidence);
}

}  // namespace
}  // namespace sonarmap
