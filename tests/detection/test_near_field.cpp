/// A beam still in the near field's reverberation where the minimum range cuts it (detector_internal.hpp,
/// RowFloor): the cut's edge and the reverberation fading beyond it are no return, and what rises out
/// of it is, for the background and the evidence detectors, on a synthetic sweep with the shared
/// Ping360 basin log's traits (../shared/data/README.md): a third of the bearings bright from the head
/// to a few metres, where the floor enters the vertical aperture, water clipped at the receiver's
/// floor elsewhere.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <opencv2/core.hpp>

#include "sonarmap/detection/detectors.hpp"

namespace sonarmap {
namespace {

constexpr int kRows = 120;
constexpr int kBins = 300;
constexpr double kBinLength_m = 0.05;  // 15 m of range
constexpr double kSpan_db = 45.0;

/// One-look speckle (exponential power) around `mean_db` over the A/D's floor, log-compressed over
/// 45 dB into 0…255.
std::uint8_t speckle(double mean_db, std::mt19937& random) {
  std::exponential_distribution<double> power(1.0);
  const double level_db = mean_db + 10.0 * std::log10(power(random));
  return static_cast<std::uint8_t>(std::clamp(std::lround(level_db * 255.0 / kSpan_db), 0L, 255L));
}

/// Rows [0, 30): reverberation 36 dB over the floor at the head fading to the water (−6 dB) at 4 m
/// and nothing behind; rows [30, 40): the same, and a wall at 7 m; rows [40, 50): reverberation that
/// ends at 2 m, and a wall at 3 m; rows [60, 70): a wall at 6 m in water; the rest water.
PolarImage nearFieldSweep(std::uint32_t seed) {
  std::mt19937 random(seed);
  PolarImage polar;
  polar.intensities = cv::Mat::zeros(kRows, kBins, CV_8UC1);
  polar.bin_length_m = kBinLength_m;
  polar.intensity_span_db = kSpan_db;
  for (int r = 0; r < kRows; ++r) {
    const double reverb_end_m = r < 40 ? 4.0 : (r < 50 ? 2.0 : 0.0);
    for (int c = 0; c < kBins; ++c) {
      const double range_m = (c + 0.5) * kBinLength_m;
      const double mean_db = range_m < reverb_end_m ? 36.0 - 42.0 * range_m / reverb_end_m : -6.0;
      polar.intensities.at<std::uint8_t>(r, c) = speckle(mean_db, random);
    }
    const double wall_m = r >= 30 && r < 40 ? 7.0 : (r >= 40 && r < 50 ? 3.0 : (r >= 60 && r < 70 ? 6.0 : 0.0));
    if (wall_m > 0.0) {
      const int bin = static_cast<int>(wall_m / kBinLength_m);
      for (int c = bin; c < bin + 3; ++c) polar.intensities.at<std::uint8_t>(r, c) = 230;
    }
    polar.valid_bins.push_back(kBins);
    polar.bearing_rad.push_back(2.0 * std::numbers::pi * r / kRows);
    polar.time_s.push_back(0.05 * r);
  }
  return polar;
}

class detectionNearField : public ::testing::TestWithParam<Detector> {};

// Cut at 1 m: the rows still in reverberation there were detected at the cut's edge (1.0–1.1 m),
// every one of them, by both detectors.
TEST_P(detectionNearField, TheCutsEdgeIsNoReturnAndWhatRisesOutOfTheReverberationIs) {
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const PolarImage polar = nearFieldSweep(seed);
    DetectorOptions options;
    options.kind = GetParam();
    options.min_range_m = 1.0;
    const std::vector<BeamDetection> found = detectSweep(polar, options).detections;
    int in_reverberation = 0, walls_behind = 0, walls_out_of_it = 0, walls_in_water = 0;
    for (int r = 0; r < kRows; ++r) {
      const BeamDetection& d = found[static_cast<std::size_t>(r)];
      if (r < 40 && d.hasObstacle() && d.range_m < 4.0) ++in_reverberation;
      if (r >= 30 && r < 40 && d.hasObstacle() && std::abs(d.range_m - 7.0) < 0.15) ++walls_behind;
      if (r >= 40 && r < 50 && d.hasObstacle() && std::abs(d.range_m - 3.0) < 0.15) ++walls_out_of_it;
      if (r >= 60 && r < 70 && d.hasObstacle() && std::abs(d.range_m - 6.0) < 0.15) ++walls_in_water;
    }
    EXPECT_LE(in_reverberation, 1) << "seed " << seed;
    EXPECT_GE(walls_behind, 9) << "seed " << seed;
    EXPECT_GE(walls_out_of_it, 9) << "seed " << seed;
    EXPECT_EQ(walls_in_water, 10) << "seed " << seed;
  }
}

// A beam in the reverberation at the cut proves no water beyond it: its echo rises above the
// background from the cut on, so the planar model, which clears a beam without an obstacle no
// farther than its echo's onset (detection.hpp), does not clear through the reverberation.
TEST_P(detectionNearField, TheReverberationIsNotWater) {
  const PolarImage polar = nearFieldSweep(7);
  DetectorOptions options;
  options.kind = GetParam();
  options.min_range_m = 1.0;
  const std::vector<BeamDetection> found = detectSweep(polar, options).detections;
  for (int r = 0; r < 30; ++r) {
    const BeamDetection& d = found[static_cast<std::size_t>(r)];
    if (!d.hasObstacle()) EXPECT_LE(d.echo_onset_m, 1.1) << "row " << r;
  }
}

INSTANTIATE_TEST_SUITE_P(detectors, detectionNearField,
                         ::testing::Values(Detector::kBackgroundSubtracted, Detector::kEvidence),
                         [](const ::testing::TestParamInfo<Detector>& info) { return detectorName(info.param); });

}  // namespace
}  // namespace sonarmap
