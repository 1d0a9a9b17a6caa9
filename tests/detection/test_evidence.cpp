/// Tests of the water's measured evidence (water_evidence.hpp) and the evidence detector
/// (Detector::kEvidence) on synthetic polar images with real water's traits: clipped at 0 by the
/// receiver's floor, speckled, with walls that are steps into reverberation.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <opencv2/core.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/detection/water_evidence.hpp"

namespace sonarmap {
namespace {

constexpr int kRows = 100;
constexpr int kBins = 300;
constexpr double kBinLength_m = 0.05;  // 15 m of range

/// Water as a Tritech log records it: one-look speckle (exponential power) log-compressed over
/// 45 dB into 0…255, its mean 6 dB under the A/D's floor, so that most bins read 0 and the rest a
/// tail of a few tens of counts.
PolarImage waterSweep(std::uint32_t seed, int rows = kRows, int bins = kBins) {
  PolarImage polar;
  polar.intensities = cv::Mat::zeros(rows, bins, CV_8UC1);
  std::mt19937 random(seed);
  std::exponential_distribution<double> speckle(1.0);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < bins; ++c) {
      const double level_db = -6.0 + 10.0 * std::log10(speckle(random));
      polar.intensities.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(std::clamp(std::lround(level_db * 255.0 / 45.0), 0L, 255L));
    }
    polar.valid_bins.push_back(bins);
    polar.bearing_rad.push_back(2.0 * std::numbers::pi * r / rows);
    polar.time_s.push_back(0.05 * r);
  }
  polar.bin_length_m = kBinLength_m;
  return polar;
}

/// A wall that is a step into reverberation (the shared ROS pool log's signature): from `bin` to the
/// end of the row, intensities drawn uniformly from 30…90 counts (5–16 dB over the floor), never a
/// peak and never the 16.9 dB (96 counts) a bin needs above the background to be a loud echo.
void addStep(PolarImage& polar, int row, int bin, std::mt19937& random) {
  std::uniform_int_distribution<int> tail(30, 90);
  for (int c = bin; c < polar.cols(); ++c) polar.intensities.at<std::uint8_t>(row, c) = static_cast<std::uint8_t>(tail(random));
}

DetectorOptions detector(Detector kind) {
  DetectorOptions options;
  options.kind = kind;
  return options;
}

std::array<std::uint32_t, WaterEvidence::kExcessValues> emptyHistogram() { return {}; }

TEST(detectionWaterEvidence, MatchesTheLikelihoodRatioComputedByHand) {
  auto histogram = emptyHistogram();
  // 1000 samples: 700 at excess 0, 200 at 3, 60 at 10, 40 beyond the body at 20 … 59 (one each).
  histogram[255 + 0] = 700;
  histogram[255 + 3] = 200;
  histogram[255 + 10] = 60;
  for (int e = 20; e < 60; ++e) histogram[static_cast<std::size_t>(255 + e)] = 1;
  const WaterEvidence evidence{std::span<const std::uint32_t>(histogram)};
  ASSERT_EQ(evidence.samples(), 1000u);
  // The 90th percentile (rank round(0.9 · 999) = 899) is excess 3: 700 + 200 samples reach it.
  EXPECT_EQ(evidence.bodyEnd(), 3);
  const double ln_uniform = -std::log(256.0);
  EXPECT_NEAR(evidence.logLikelihoodRatio(0), ln_uniform - std::log(0.7), 1e-5);
  EXPECT_NEAR(evidence.logLikelihoodRatio(3), ln_uniform - std::log(0.2), 1e-5);
  // A gap in the body takes the next louder value's evidence; below every sample, the quietest's.
  EXPECT_FLOAT_EQ(evidence.logLikelihoodRatio(1), evidence.logLikelihoodRatio(3));
  EXPECT_FLOAT_EQ(evidence.logLikelihoodRatio(-40), evidence.logLikelihoodRatio(0));
  // Beyond the body: the exponential tail of the 100 samples beyond excess 3, their mean excess m.
  double excess = 60.0 * (10 - 3);
  for (int e = 20; e < 60; ++e) excess += e - 3;
  const double m = excess / 100.0;
  for (const int e : {4, 10, 30, 100}) {
    const double p = 0.1 * (1.0 - std::exp(-1.0 / m)) * std::exp(-(e - 3 - 1) / m);
    EXPECT_NEAR(evidence.logLikelihoodRatio(e), ln_uniform - std::log(p), 1e-4) << "excess " << e;
  }
  EXPECT_NEAR(evidence.tailScale(), m, 1e-9);
  // Never decreasing in the excess, and bounded by the least probability of water.
  for (int e = -255; e < 255; ++e) EXPECT_LE(evidence.logLikelihoodRatio(e), evidence.logLikelihoodRatio(e + 1));
  EXPECT_LE(evidence.logLikelihoodRatio(255), ln_uniform - std::log(WaterEvidence::kMinProbability) + 1e-4);
  // A narrow tail reaches the floor: no value is impossible in water.
  auto narrow = emptyHistogram();
  narrow[255] = 990;
  narrow[256] = 10;
  const WaterEvidence clipped{std::span<const std::uint32_t>(narrow)};
  EXPECT_NEAR(clipped.logLikelihoodRatio(200), ln_uniform - std::log(WaterEvidence::kMinProbability), 1e-4);
}

TEST(detectionWaterEvidence, ALeastTailScaleBoundsTheEvidenceOfWaterSeenClipped) {
  // Water clipped at the receiver's floor: every sample at excess 0. Its measured tail (one
  // pseudo-sample, a count wide) makes two 12-count bins certain evidence of a return; the
  // least tail (speckle's 1.41 dB, 8 counts on a 45 dB span) keeps it to a few nats.
  auto histogram = emptyHistogram();
  histogram[255] = 1600;
  const WaterEvidence measured{std::span<const std::uint32_t>(histogram)};
  const double least_counts = 1.4067 * 255.0 / 45.0;
  const WaterEvidence bounded{std::span<const std::uint32_t>(histogram), least_counts};
  EXPECT_DOUBLE_EQ(measured.tailScale(), 1.0);
  EXPECT_DOUBLE_EQ(bounded.tailScale(), least_counts);
  const double ln_uniform = -std::log(256.0);
  const double p = (1.0 / 1600.0) * (1.0 - std::exp(-1.0 / least_counts)) * std::exp(-11.0 / least_counts);
  EXPECT_NEAR(bounded.logLikelihoodRatio(12), ln_uniform - std::log(p), 1e-4);
  EXPECT_GT(2.0 * measured.logLikelihoodRatio(12), 13.8);  // ln(1 / 1e-6): certain in two bins
  EXPECT_LT(bounded.logLikelihoodRatio(12), 6.0);
  // A measured tail heavier than the least is kept; the body is unchanged by the bound.
  auto wide = emptyHistogram();
  wide[255] = 900;
  for (int e = 1; e <= 100; ++e) wide[static_cast<std::size_t>(255 + e)] = 1;
  const WaterEvidence heavy{std::span<const std::uint32_t>(wide), least_counts};
  EXPECT_NEAR(heavy.tailScale(), 50.5, 1e-9);
  EXPECT_FLOAT_EQ(heavy.logLikelihoodRatio(0), WaterEvidence{std::span<const std::uint32_t>(wide)}.logLikelihoodRatio(0));
  EXPECT_THROW(WaterEvidence(std::span<const std::uint32_t>(wide), std::nan("")), ValueError);
}

TEST(detectionWaterEvidence, TheBodyAndTailAreThoseOfTheSamplesCountedOneByOne) {
  // Random bands, sparse and dense, against the 90th percentile and the tail's mean excess found
  // by listing every sample.
  std::mt19937 rng(11);
  for (int band = 0; band < 200; ++band) {
    std::array<std::uint32_t, WaterEvidence::kExcessValues> counts{};
    std::vector<int> samples;
    const int centre = std::uniform_int_distribution<int>(0, 510)(rng);
    const int spread = std::uniform_int_distribution<int>(0, 120)(rng);
    const int n = std::uniform_int_distribution<int>(1, 3000)(rng);
    std::normal_distribution<double> excess(centre, spread + 0.5);
    for (int k = 0; k < n; ++k) {
      const int i = std::clamp(static_cast<int>(std::lround(excess(rng))), 0, 510);
      ++counts[static_cast<std::size_t>(i)];
      samples.push_back(i);
    }
    std::sort(samples.begin(), samples.end());
    const int q = samples[static_cast<std::size_t>(std::llround(0.9 * (n - 1)))];
    double tail = 0.0;
    int beyond = 0;
    for (const int i : samples) {
      if (i > q) tail += i - q, ++beyond;
    }
    const WaterEvidence evidence{std::span<const std::uint32_t>(counts), 1.0};
    EXPECT_EQ(evidence.samples(), static_cast<std::uint64_t>(n));
    EXPECT_EQ(evidence.bodyEnd(), q - 255);
    EXPECT_EQ(evidence.tailScale(), beyond > 0 ? std::max(1.0, tail / beyond) : 1.0) << "band " << band;
  }
}

TEST(detectionWaterEvidence, AnEmptyBandGivesNoEvidenceAndAWrongSizeThrows) {
  const auto histogram = emptyHistogram();
  const WaterEvidence evidence{std::span<const std::uint32_t>(histogram)};
  for (const int e : {-255, 0, 255}) EXPECT_EQ(evidence.logLikelihoodRatio(e), 0.0f);
  const std::vector<std::uint32_t> short_histogram(256, 1);
  EXPECT_THROW(WaterEvidence{std::span<const std::uint32_t>(short_histogram)}, ValueError);
}

TEST(detectionEvidenceDetector, SpeckleDoesNotAccumulateIntoReturns) {
  // Water alone, sweep after sweep: the evidence of its bins must not add up to a return.
  std::size_t false_returns = 0;
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    for (const BeamDetection& found : detectObstacles(waterSweep(seed), detector(Detector::kEvidence))) {
      false_returns += found.hasObstacle() ? 1 : 0;
    }
  }
  EXPECT_EQ(false_returns, 0u) << "of " << 5 * kRows << " beams of water";
}

TEST(detectionEvidenceDetector, FindsStepShapedWallsThatThePeakDetectorMisses) {
  PolarImage polar = waterSweep(11);
  std::mt19937 random(3);
  // A third of the bearings meet a step at 5.8 m, the others see water to the end (the shared pool
  // log's sweep: a wall that is a step into reverberation, not a peak).
  const int step = static_cast<int>(5.8 / kBinLength_m);
  std::vector<int> stepped;
  for (int r = 0; r < kRows; r += 3) {
    addStep(polar, r, step, random);
    stepped.push_back(r);
  }
  const auto evidence = detectObstacles(polar, detector(Detector::kEvidence));
  const auto peaks = detectObstacles(polar, detector(Detector::kBackgroundSubtracted));
  std::size_t found_by_peaks = 0;
  for (const int r : stepped) {
    ASSERT_TRUE(evidence[static_cast<std::size_t>(r)].hasObstacle()) << "row " << r;
    EXPECT_NEAR(evidence[static_cast<std::size_t>(r)].range_m, (step + 0.5) * kBinLength_m, 2.0 * kBinLength_m) << "row " << r;
    found_by_peaks += peaks[static_cast<std::size_t>(r)].hasObstacle() ? 1 : 0;
  }
  EXPECT_EQ(found_by_peaks, 0u) << "no bin of a step is a loud echo";
  for (int r = 0; r < kRows; ++r) {
    if (r % 3 != 0) EXPECT_FALSE(evidence[static_cast<std::size_t>(r)].hasObstacle()) << "row " << r;
  }
}

// Beams of a sweep in progress, one at a time (live mapping), judged against the water the last
// whole sweep measured (SweepCalibration::water_evidence and water_level): the step walls of the
// next sweep are found beam by beam, and its water beams stay water.
TEST(detectionEvidenceDetector, SingleBeamsAreJudgedAgainstTheLastSweepsWater) {
  std::mt19937 random(5);
  const int step = static_cast<int>(5.8 / kBinLength_m);
  PolarImage last = waterSweep(21);
  for (int r = 0; r < kRows; r += 3) addStep(last, r, step, random);
  const SweepDetection calibrating = detectSweep(last, detector(Detector::kEvidence));
  const SweepCalibration& kept = calibrating.calibration;
  ASSERT_EQ(kept.water_evidence.size(), static_cast<std::size_t>(kBins));
  ASSERT_EQ(kept.water_level.size(), static_cast<std::size_t>(kBins));
  PolarImage next = waterSweep(22);
  for (int r = 1; r < kRows; r += 3) addStep(next, r, step, random);
  std::size_t walls = 0, false_walls = 0;
  for (int r = 0; r < kRows; ++r) {
    PolarImage beam = next;
    beam.intensities = next.intensities.row(r).clone();
    beam.time_s = {next.time_s[static_cast<std::size_t>(r)]};
    beam.bearing_rad = {next.bearing_rad[static_cast<std::size_t>(r)]};
    beam.valid_bins = {next.valid_bins[static_cast<std::size_t>(r)]};
    const BeamDetection found = detectRows(beam, detector(Detector::kEvidence), kept).detections.front();
    if (r % 3 == 1) {
      ASSERT_TRUE(found.hasObstacle()) << "row " << r;
      EXPECT_NEAR(found.range_m, (step + 0.5) * kBinLength_m, 2.0 * kBinLength_m) << "row " << r;
      ++walls;
    } else {
      false_walls += found.hasObstacle() ? 1 : 0;
    }
  }
  EXPECT_EQ(walls, 33U);
  EXPECT_EQ(false_walls, 0U);
  // Without the kept water (a calibration from elsewhere) one beam finds no weak return.
  SweepCalibration bare = kept;
  bare.water_evidence.clear();
  bare.water_level.clear();
  PolarImage beam = next;
  beam.intensities = next.intensities.row(1).clone();
  beam.time_s = {next.time_s[1]};
  beam.bearing_rad = {next.bearing_rad[1]};
  beam.valid_bins = {next.valid_bins[1]};
  EXPECT_FALSE(detectRows(beam, detector(Detector::kEvidence), bare).detections.front().hasObstacle());
}

TEST(detectionEvidenceDetector, TheWaterIsMeasuredWithoutTheReturnsInItsBeams) {
  // The same steps at one range in a growing share of the bearings: the water at that range is
  // measured on the rows still in water, not on those inside a return, so the steps stand out as
  // long as they are a minority; once they are in most bearings they are what the water looks like
  // there (a level surface entering the cone: the CRAS tank's water surface at 1.5 m).
  const int step = 120;
  for (const int every : {10, 4, 2}) {
    PolarImage polar = waterSweep(21);
    std::mt19937 random(5);
    std::size_t stepped = 0, found = 0;
    for (int r = 0; r < kRows; r += every, ++stepped) addStep(polar, r, step, random);
    const auto detections = detectObstacles(polar, detector(Detector::kEvidence));
    for (int r = 0; r < kRows; r += every) found += detections[static_cast<std::size_t>(r)].hasObstacle() ? 1 : 0;
    EXPECT_EQ(found, stepped) << "steps in 1 of " << every << " bearings";
  }
  PolarImage everywhere = waterSweep(21);
  std::mt19937 random(5);
  for (int r = 0; r < kRows; ++r) addStep(everywhere, r, step, random);
  std::size_t found = 0;
  for (const BeamDetection& d : detectObstacles(everywhere, detector(Detector::kEvidence))) found += d.hasObstacle() ? 1 : 0;
  EXPECT_LT(found, static_cast<std::size_t>(kRows / 10)) << "a step in every bearing is the water's level there";
}

// A weak return's range is where its echo has risen (within the leading-edge level of the echo's
// level, at least half of it), for a step and for a slow rise alike: a step at its first bin; an
// echo rising over 0.5 m (a face at oblique incidence, lit first by the pattern's skirt) within
// its rise, behind where its first weak bins began to add evidence.
TEST(detectionEvidenceDetector, AWeakReturnsRangeIsWhereItsEchoHasRisen) {
  PolarImage polar = waterSweep(7);
  std::mt19937 random(11);
  addStep(polar, 10, 100, random);  // a step at 5 m
  // A rise from 0 to 60–90 counts over bins 150–160 (7.5 → 8.0 m), then a plateau.
  for (int c = 150; c < kBins; ++c) {
    const double share = std::min(1.0, (c - 150) / 10.0);
    polar.intensities.at<std::uint8_t>(40, c) = static_cast<std::uint8_t>(share * std::uniform_int_distribution<int>(60, 90)(random));
  }
  const SweepDetection sweep = detectSweep(polar, detector(Detector::kEvidence));
  const BeamDetection& step = sweep.detections[10];
  const BeamDetection& rise = sweep.detections[40];
  ASSERT_TRUE(step.hasObstacle());
  ASSERT_TRUE(rise.hasObstacle());
  EXPECT_TRUE(step.weak);
  EXPECT_TRUE(rise.weak);
  EXPECT_NEAR(step.range_m, 5.0 + 0.5 * kBinLength_m, 0.5 * kBinLength_m);  // the step's bin
  EXPECT_GE(rise.range_m, 7.65);  // where its evidence started: 7.575 m; half its rise: 7.75 m
  EXPECT_LE(rise.range_m, 8.0);
  EXPECT_GE(rise.rise_m, 0.0);
  // The loud echoes are the background detector's; the weak returns lie where it found none.
  const SweepDetection background = detectSweep(polar, detector(Detector::kBackgroundSubtracted));
  for (std::size_t r = 0; r < background.detections.size(); ++r) {
    const BeamDetection& found = sweep.detections[r];
    EXPECT_EQ(found.weak, !background.detections[r].hasObstacle() && found.hasObstacle()) << r;
    if (!found.weak) EXPECT_EQ(found.obstacle_bin, background.detections[r].obstacle_bin) << r;
  }
}

TEST(detectionEvidenceDetector, LoudReturnsKeepThePeakDetectorsRanges) {
  // A peaked wall echo: both detectors place it at its leading edge, the same bin.
  PolarImage polar = waterSweep(31);
  for (int r = 0; r < kRows; ++r) polar.intensities.row(r).colRange(150 + r % 40, 156 + r % 40).setTo(220);
  const auto evidence = detectObstacles(polar, detector(Detector::kEvidence));
  const auto peaks = detectObstacles(polar, detector(Detector::kBackgroundSubtracted));
  for (int r = 0; r < kRows; ++r) {
    ASSERT_TRUE(peaks[static_cast<std::size_t>(r)].hasObstacle());
    EXPECT_EQ(evidence[static_cast<std::size_t>(r)].obstacle_bin, peaks[static_cast<std::size_t>(r)].obstacle_bin) << "row " << r;
  }
  EXPECT_EQ(parseDetector("evidence"), Detector::kEvidence);
  EXPECT_EQ(detectorName(Detector::kEvidence), "evidence");
}

}  // namespace
}  // namespace sonarmap
