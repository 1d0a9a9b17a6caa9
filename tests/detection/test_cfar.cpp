/// Tests of CFAR detection along a beam (cfar.hpp) and of Detector::kCfar (detectors.hpp):
/// hand-made beams with known noise estimates, seeded exponential noise against the design
/// formulas, the behaviours Richards ch. 6 (CA, SO, GO) and Rohling 1983 (OS) predict, the
/// detector contract, and the CRAS tank log.

#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/rectangle_fit.hpp"
#include "sonarmap/detection/cfar.hpp"
#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/formats/mat_reader.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/polar_units.hpp"
#include "sonarmap/sonar/preprocess.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {
namespace {

using Beam8 = std::vector<std::uint8_t>;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kTrials = 200;  // beams per statistical test

/// Exponential noise (the power of Rayleigh-distributed amplitude) of the given mean in bins
/// [first, last), rounded and clipped to 0…255. cv::RNG gives the same numbers on every platform.
void fillNoise(Beam8& beam, int first, int last, double mean, cv::RNG& rng) {
  for (int c = first; c < last; ++c) {
    const double x = -mean * std::log(1.0 - rng.uniform(0.0, 1.0));
    beam[static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::min(255.0, std::round(x)));
  }
}

Beam8 noiseBeam(int bins, double mean, cv::RNG& rng) {
  Beam8 beam(static_cast<std::size_t>(bins));
  fillNoise(beam, 0, bins, mean, rng);
  return beam;
}

void setBins(Beam8& beam, int first, int count, std::uint8_t value) {
  std::fill_n(beam.begin() + first, count, value);
}

/// 16 training and 2 guard bins per side, no floor, single-cell runs: the textbook detector.
CfarCells textbook(CfarVariant variant, double scale) {
  CfarCells o;
  o.variant = variant;
  o.training_bins = 16;
  o.guard_bins = 2;
  o.scale = scale;
  o.min_intensity = 0;
  o.min_run_bins = 1;
  return o;
}

// ---------------------------------------------------------------------------------------------
// Noise estimates on hand-made beams
// ---------------------------------------------------------------------------------------------

/// 11 bins, T = 2, G = 1: cell 5 trains on bins 2, 3 (lagging) and 7, 8 (leading).
Beam8 handMadeBeam() { return {0, 0, 10, 20, 0, 0, 0, 40, 60, 0, 0}; }

TEST(sonarCfar, EachVariantEstimatesTheNoiseFromItsTrainingCells) {
  CfarCells o = textbook(CfarVariant::kCellAveraging, 2.0);
  o.training_bins = 2;
  o.guard_bins = 1;
  const Beam8 beam = handMadeBeam();
  const std::pair<CfarVariant, float> expected[] = {
      {CfarVariant::kCellAveraging, 2.0f * 32.5f},     // mean of 10, 20, 40, 60
      {CfarVariant::kSmallestOf, 2.0f * 15.0f},        // min(mean(10, 20), mean(40, 60))
      {CfarVariant::kGreatestOf, 2.0f * 50.0f},        // max of the two means
      {CfarVariant::kOrderedStatistic, 2.0f * 40.0f},  // k = 0.75 × 4 = 3rd smallest of 10, 20, 40, 60
  };
  for (const auto& [variant, threshold] : expected) {
    o.variant = variant;
    EXPECT_FLOAT_EQ(cfarThresholds(beam, o)[5], threshold) << static_cast<int>(variant);
  }
  o.variant = CfarVariant::kOrderedStatistic;
  o.os_rank = 1.0;  // k = n: the largest training cell
  EXPECT_FLOAT_EQ(cfarThresholds(beam, o)[5], 2.0f * 60.0f);
  o.os_rank = 0.01;  // k is at least 1: the smallest
  EXPECT_FLOAT_EQ(cfarThresholds(beam, o)[5], 2.0f * 10.0f);
}

TEST(sonarCfar, NearTheEndsOnlyTheCompleteWindowIsUsed) {
  CfarCells o = textbook(CfarVariant::kCellAveraging, 1.0);
  o.training_bins = 2;
  o.guard_bins = 1;
  const Beam8 beam = handMadeBeam();
  for (CfarVariant variant : {CfarVariant::kCellAveraging, CfarVariant::kSmallestOf, CfarVariant::kGreatestOf}) {
    o.variant = variant;
    const std::vector<float> t = cfarThresholds(beam, o);
    ASSERT_EQ(t.size(), beam.size());
    EXPECT_FLOAT_EQ(t[1], 10.0f) << "cell 1: leading bins 3, 4 only";
    EXPECT_FLOAT_EQ(t[2], 0.0f) << "cell 2: leading bins 4, 5 only";
    EXPECT_FLOAT_EQ(t[9], 20.0f) << "cell 9: lagging bins 6, 7 only";
    EXPECT_FLOAT_EQ(t[10], 50.0f) << "cell 10: lagging bins 7, 8 only";
  }
  o.variant = CfarVariant::kOrderedStatistic;  // k = round(0.75 × 2) = 2 of the one window
  EXPECT_FLOAT_EQ(cfarThresholds(beam, o)[10], 60.0f);
}

TEST(sonarCfar, CellsWithoutACompleteTrainingWindowAreNeverDetected) {
  CfarCells o = textbook(CfarVariant::kCellAveraging, 1.0);
  o.training_bins = 2;
  o.guard_bins = 1;
  const Beam8 beam{0, 0, 200, 0, 0};  // cell 2 would need bins −1…0 or 4…5
  EXPECT_EQ(cfarThresholds(beam, o)[2], kInf);
  EXPECT_EQ(firstCfarBin(beam, 0, o), -1);
  EXPECT_TRUE(cfarThresholds(Beam8{}, o).empty());
  EXPECT_EQ(firstCfarBin(Beam8{}, 0, o), -1);
}

// ---------------------------------------------------------------------------------------------
// Exponential noise: the design false-alarm rate, a target, clutter edges, interfering targets
// ---------------------------------------------------------------------------------------------

/// Share of the cells with both training windows complete whose intensity exceeds the threshold.
double falseAlarmRate(const CfarCells& o, double noise_mean, cv::RNG& rng) {
  const int bins = 400, first = o.training_bins + o.guard_bins, last = bins - first;
  std::size_t alarms = 0, cells = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Beam8 beam = noiseBeam(bins, noise_mean, rng);
    const std::vector<float> t = cfarThresholds(beam, o);
    for (int c = first; c < last; ++c, ++cells) alarms += beam[static_cast<std::size_t>(c)] > t[static_cast<std::size_t>(c)];
  }
  return static_cast<double>(alarms) / static_cast<double>(cells);
}

TEST(sonarCfar, FalseAlarmRateOnExponentialNoiseIsTheDesignRateAtAnyNoiseLevel) {
  // CA: Richards ch. 6; OS: Rohling 1983. 2000 beams × 364 cells each; the CUT and training
  // cells are integers (rounded), which the formulas ignore.
  cv::RNG rng(42);
  const double pfa = 1e-2;
  CfarCells ca = textbook(CfarVariant::kCellAveraging, caCfarScale(pfa, 32));
  CfarCells os = textbook(CfarVariant::kOrderedStatistic, osCfarScale(pfa, 32, 24));
  for (double noise_mean : {15.0, 40.0}) {
    // measured: CA 0.0100 and 0.0099, OS 0.0101 and 0.0097
    EXPECT_NEAR(falseAlarmRate(ca, noise_mean, rng), pfa, 0.15 * pfa) << "CA, noise mean " << noise_mean;
    EXPECT_NEAR(falseAlarmRate(os, noise_mean, rng), pfa, 0.15 * pfa) << "OS, noise mean " << noise_mean;
  }
  ca.scale = caCfarScale(1e-3, 32);
  EXPECT_NEAR(falseAlarmRate(ca, 15.0, rng), 1e-3, 0.3e-3);  // measured 0.00104
}

TEST(sonarCfar, CellAveragingFindsATargetInNoise) {
  cv::RNG rng(1);
  const CfarCells o = textbook(CfarVariant::kCellAveraging, caCfarScale(1e-4, 32));  // α ≈ 10.7
  int found = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    Beam8 beam = noiseBeam(300, 10.0, rng);
    setBins(beam, 150, 3, 200);  // a 3-bin echo at 20 times the noise mean, within the guard cells
    found += firstCfarBin(beam, 100, o) == 150;
  }
  EXPECT_GE(found, kTrials * 98 / 100);  // measured 199 of 200
}

TEST(sonarCfar, SmallestOfKeepsATargetBeforeAClutterEdgeThatGreatestOfMasks) {
  // Richards ch. 6: GO takes the brighter window, so clutter in the leading window raises the
  // threshold over the target (masking); SO takes the darker window and keeps it.
  cv::RNG rng(2);
  int so_found = 0, go_found = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    Beam8 beam = noiseBeam(300, 4.0, rng);
    fillNoise(beam, 105, 300, 80.0, rng);  // clutter from 5 bins behind the target on
    setBins(beam, 100, 2, 200);
    so_found += firstCfarBin(beam, 60, textbook(CfarVariant::kSmallestOf, 20.0)) == 100;
    go_found += firstCfarBin(beam, 60, textbook(CfarVariant::kGreatestOf, 20.0)) == 100;
  }
  EXPECT_GE(so_found, kTrials * 95 / 100);  // measured 200 of 200
  EXPECT_LE(go_found, kTrials * 5 / 100);   // measured 0
}

TEST(sonarCfar, GreatestOfStaysQuietAtAClutterEdgeWhereSmallestOfFires) {
  // Richards ch. 6: at the start of a clutter region the lagging window is still dark, so SO's
  // threshold is low and clutter cells pass (a false obstacle before the real one); GO takes the
  // clutter window and reports the target inside the clutter.
  cv::RNG rng(3);
  int so_at_edge = 0, go_at_target = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    Beam8 beam = noiseBeam(300, 1.0, rng);
    fillNoise(beam, 100, 300, 20.0, rng);
    setBins(beam, 110, 3, 250);
    const int so = firstCfarBin(beam, 90, textbook(CfarVariant::kSmallestOf, 8.0));
    so_at_edge += so >= 100 && so < 110;
    go_at_target += firstCfarBin(beam, 90, textbook(CfarVariant::kGreatestOf, 8.0)) == 110;
  }
  EXPECT_GE(so_at_edge, kTrials * 90 / 100);    // measured 192 of 200
  EXPECT_GE(go_at_target, kTrials * 90 / 100);  // measured 198 of 200
}

TEST(sonarCfar, OrderedStatisticIsRobustToAnInterferingTargetInTheTrainingCells) {
  // Rohling 1983: up to n − k bright cells in the training windows leave the k-th smallest a noise
  // sample, while they pull CA's mean up. Same design Pfa (1e-2) for both.
  cv::RNG rng(4);
  const CfarCells ca = textbook(CfarVariant::kCellAveraging, caCfarScale(1e-2, 32));
  const CfarCells os = textbook(CfarVariant::kOrderedStatistic, osCfarScale(1e-2, 32, 24));
  int ca_found = 0, os_found = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    Beam8 beam = noiseBeam(300, 10.0, rng);
    setBins(beam, 100, 1, 180);
    setBins(beam, 105, 4, 255);  // the interfering target: in the leading window of bin 100
    ca_found += beam[100] > cfarThresholds(beam, ca)[100];
    os_found += beam[100] > cfarThresholds(beam, os)[100];
  }
  EXPECT_LE(ca_found, kTrials * 5 / 100);   // measured 0
  EXPECT_GE(os_found, kTrials * 95 / 100);  // measured 200 of 200
}

// ---------------------------------------------------------------------------------------------
// Floor, runs and the design scales
// ---------------------------------------------------------------------------------------------

TEST(sonarCfar, AnObstacleNeedsARunOfCellsAboveBothTheThresholdAndTheFloor) {
  Beam8 beam(200, 10);
  setBins(beam, 60, 2, 200);   // 2 bins: too short for a run of 3
  setBins(beam, 90, 5, 50);    // 5 bins above the CFAR threshold (5 × 10) but below the floor
  setBins(beam, 120, 5, 120);  // the obstacle
  CfarCells o = textbook(CfarVariant::kCellAveraging, 3.0);
  o.min_intensity = 100;
  o.min_run_bins = 3;
  EXPECT_EQ(firstCfarBin(beam, 0, o), 120);
  o.min_run_bins = 1;
  EXPECT_EQ(firstCfarBin(beam, 0, o), 60);
  EXPECT_EQ(firstCfarBin(beam, 62, o), 120);
  o.min_intensity = 0;
  EXPECT_EQ(firstCfarBin(beam, 62, o), 90);
  o.min_intensity = 121;  // "at least": 120 < 121
  EXPECT_EQ(firstCfarBin(beam, 62, o), -1);
}

TEST(sonarCfar, DesignScalesSolveTheFalseAlarmFormulas) {
  for (int n : {1, 8, 32}) {
    for (double pfa : {1e-2, 1e-4}) {
      const double ca = caCfarScale(pfa, n);
      EXPECT_NEAR(std::pow(1.0 + ca / n, -n), pfa, 1e-9 * pfa + 1e-12) << "N " << n;  // Richards ch. 6
      const int k = std::max(1, 3 * n / 4);
      const double os = osCfarScale(pfa, n, k);
      double p = 1.0;
      for (int i = 0; i < k; ++i) p *= (n - i) / (n - i + os);  // Rohling 1983
      EXPECT_NEAR(p, pfa, 1e-6 * pfa) << "N " << n << " k " << k;
    }
  }
  EXPECT_NEAR(caCfarScale(0.1, 1), 9.0, 1e-9);      // N = 1: Pfa = 1 / (1 + α)
  EXPECT_NEAR(osCfarScale(0.1, 1, 1), 9.0, 1e-6);   // the only cell: the same
  EXPECT_THROW(caCfarScale(0.0, 32), ValueError);
  EXPECT_THROW(caCfarScale(1.0, 32), ValueError);
  EXPECT_THROW(caCfarScale(0.1, 0), ValueError);
  EXPECT_THROW(osCfarScale(0.1, 32, 0), ValueError);
  EXPECT_THROW(osCfarScale(0.1, 32, 33), ValueError);
}

TEST(sonarCfar, InvalidOptionsThrow) {
  const Beam8 beam(100, 10);
  const auto invalid = [&](auto change) {
    CfarCells o;
    change(o);
    EXPECT_THROW(cfarThresholds(beam, o), ValueError);
    EXPECT_THROW(firstCfarBin(beam, 0, o), ValueError);
  };
  invalid([](CfarCells& o) { o.training_bins = 0; });
  invalid([](CfarCells& o) { o.training_bins = 65536; });
  invalid([](CfarCells& o) { o.guard_bins = -1; });
  invalid([](CfarCells& o) { o.guard_bins = 65536; });
  invalid([](CfarCells& o) { o.scale = 0.0; });
  invalid([](CfarCells& o) { o.scale = std::numeric_limits<double>::infinity(); });
  invalid([](CfarCells& o) { o.os_rank = 0.0; });
  invalid([](CfarCells& o) { o.os_rank = 1.5; });
  invalid([](CfarCells& o) { o.min_intensity = 256; });
  invalid([](CfarCells& o) { o.min_run_bins = 0; });
  EXPECT_THROW(firstCfarBin(beam, -1, CfarCells{}), ValueError);
  EXPECT_NO_THROW(CfarCells{}.validate());
}

// ---------------------------------------------------------------------------------------------
// Detector::kCfar: the contract of detectObstacles
// ---------------------------------------------------------------------------------------------

constexpr int kRows = 40;
constexpr int kBins = 200;
constexpr double kBinLength_m = 0.02;

/// Rows of noise 0…10 with a 10-bin echo of 150 at bin 100 + 2r (2.0…3.6 m).
PolarImage sweepWithWall() {
  PolarImage polar;
  polar.intensities = cv::Mat::zeros(kRows, kBins, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(polar.intensities, cv::RNG::UNIFORM, 0, 11);
  for (int r = 0; r < kRows; ++r) {
    polar.intensities.row(r).colRange(100 + 2 * r, 110 + 2 * r).setTo(150);
    polar.valid_bins.push_back(kBins);
    polar.bearing_rad.push_back(2.0 * std::numbers::pi * r / kRows);
    polar.time_s.push_back(0.1 * r);
  }
  polar.bin_length_m = kBinLength_m;
  return polar;
}

DetectorOptions cfarDetector(CfarVariant variant) {
  DetectorOptions options;
  options.kind = Detector::kCfar;
  options.cfar.variant = variant;
  return options;
}

TEST(sonarCfar, DetectorFindsTheFirstObstacleOfEveryRowWithEachVariant) {
  const PolarImage polar = sweepWithWall();
  const cv::Mat before = polar.intensities.clone();
  for (CfarVariant variant : {CfarVariant::kCellAveraging, CfarVariant::kSmallestOf, CfarVariant::kGreatestOf,
                              CfarVariant::kOrderedStatistic}) {
    const auto found = detectObstacles(polar, cfarDetector(variant));
    ASSERT_EQ(found.size(), static_cast<std::size_t>(kRows));
    for (int r = 0; r < kRows; ++r) {
      EXPECT_EQ(found[r].obstacle_bin, 100 + 2 * r) << "variant " << static_cast<int>(variant) << " row " << r;
      EXPECT_EQ(found[r].intensity, 150);
    }
  }
  EXPECT_EQ(cv::countNonZero(polar.intensities != before), 0) << "the detector changed its input";
}

TEST(sonarCfar, DetectorHonoursMinRangeAndValidBins) {
  PolarImage polar = sweepWithWall();
  polar.intensities.row(0).colRange(20, 30).setTo(150);  // 0.4 m, before the minimum range
  polar.valid_bins[1] = 100;                             // row 1 ends before its wall (bin 102)
  polar.valid_bins[2] = 112;                             // row 2 ends inside it: lagging window only
  polar.intensities.row(3).setTo(5);                     // row 3: flat, nothing to find
  DetectorOptions options = cfarDetector(CfarVariant::kCellAveraging);
  options.min_range_m = 1.0;  // bin 50
  const auto found = detectObstacles(polar, options);
  EXPECT_EQ(found[0].obstacle_bin, 100);
  EXPECT_FALSE(found[1].hasObstacle());
  EXPECT_EQ(found[1].obstacle_bin, -1);
  EXPECT_EQ(found[2].obstacle_bin, 104);
  EXPECT_FALSE(found[3].hasObstacle());
  options.min_range_m = 0.3;
  EXPECT_EQ(detectObstacles(polar, options)[0].obstacle_bin, 20);
  options.min_range_m = 4.0;  // beyond the last bin
  for (const BeamDetection& d : detectObstacles(polar, options)) EXPECT_FALSE(d.hasObstacle());
}

TEST(sonarCfar, DetectorRejectsInvalidCfarOptions) {
  DetectorOptions options = cfarDetector(CfarVariant::kOrderedStatistic);
  options.cfar.os_rank = 0.0;
  EXPECT_THROW(detectObstacles(sweepWithWall(), options), ValueError);
  options = cfarDetector(CfarVariant::kCellAveraging);
  options.cfar.training_m = 0.0;
  EXPECT_THROW(detectObstacles(sweepWithWall(), options), ValueError);
  options = cfarDetector(CfarVariant::kCellAveraging);
  options.cfar.min_contrast_db = -1.0;
  EXPECT_THROW(detectObstacles(sweepWithWall(), options), ValueError);
}

TEST(sonarCfar, DetectorNamesSelectTheVariant) {
  const std::pair<const char*, CfarVariant> names[] = {{"cfar-ca", CfarVariant::kCellAveraging},
                                                       {"cfar-so", CfarVariant::kSmallestOf},
                                                       {"cfar-go", CfarVariant::kGreatestOf},
                                                       {"cfar-os", CfarVariant::kOrderedStatistic}};
  for (const auto& [name, variant] : names) {
    DetectorOptions options;
    options.cfar.scale = 3.0;
    selectDetector(options, name);
    EXPECT_EQ(options.kind, Detector::kCfar) << name;
    EXPECT_EQ(options.cfar.variant, variant) << name;
    EXPECT_EQ(options.cfar.scale, 3.0) << "selectDetector changes only the kind and the variant";
    EXPECT_EQ(detectorName(options), name);
    EXPECT_EQ(parseDetector(name), Detector::kCfar);
  }
  for (const char* name : {"threshold", "canny", "background"}) {
    DetectorOptions options;
    options.cfar.variant = CfarVariant::kGreatestOf;
    selectDetector(options, name);
    EXPECT_EQ(detectorName(options), name);
    EXPECT_EQ(options.cfar.variant, CfarVariant::kGreatestOf);
  }
  EXPECT_EQ(detectorName(Detector::kCfar), "cfar-ca");
  DetectorOptions options;
  for (const char* bad : {"cfar", "cfar-", "cfar-xx", "CFAR-CA", ""}) EXPECT_THROW(selectDetector(options, bad), ValueError) << bad;
  EXPECT_EQ(options.kind, DetectorOptions{}.kind) << "a bad name changes nothing";
}

}  // namespace
}  // namespace sonarmap
