// A head centred in a round tank: a wall at the same range at every bearing is an obstacle. The
// background a wall stands out of is the water's and the seabed's level around it in range
// (reverberation.hpp), not what most bearings return at its range: across bearings the wall is
// at every bearing, so its range's percentile is the wall itself (issue 77, item 2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <random>

#include "sonarmap/detection/calibration.hpp"
#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {
namespace {

constexpr double kWallRange_m = 6.0;
constexpr double kRange_m = 10.0;
constexpr int kBins = 1200;         // a Ping360's samples at 10 m
constexpr int kBeamsPerTurn = 400;  // its 0.9° steps (gradians)

/// Two turns of a Ping360 centred in a round tank: speckle uniform in 0…20 counts, the wall 220
/// over the pulse's length (c·τ/2 with Ping Viewer's τ = 8000·R/c µs: 0.4 % of the range).
SonarLog roundTank(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> speckle(0, 20);
  const double bin_m = kRange_m / kBins;
  const double pulse_m = 0.004 * kRange_m;
  SonarLog log;
  for (int i = 0; i < 2 * kBeamsPerTurn; ++i) {
    Beam beam;
    beam.time_s = 0.05 * i;
    beam.bearing_rad = 2.0 * M_PI * (i % kBeamsPerTurn) / kBeamsPerTurn;
    beam.bin_length_m = bin_m;
    beam.pulse_length_m = pulse_m;
    beam.intensities.resize(kBins);
    for (int b = 0; b < kBins; ++b) {
      const double range_m = (b + 0.5) * bin_m;
      const bool wall = range_m >= kWallRange_m && range_m < kWallRange_m + pulse_m;
      beam.intensities[b] = static_cast<std::uint8_t>(wall ? 220 : speckle(random));
    }
    log.beams.push_back(std::move(beam));
  }
  return log;
}

/// The share of `log`'s beams whose obstacle lies within 0.1 m of the wall, detected with `options`.
double shareOnTheWall(const SonarLog& log, const DetectorOptions& options) {
  const std::vector<SweepRange> sweeps = splitSweeps(log.beams);
  std::size_t beams = 0;
  std::size_t on_wall = 0;
  for (const SweepRange& sweep : sweeps) {
    const SweepDetection detected = detectSweep(makePolarImage(log.beams, sweep.first, sweep.last_exclusive), options);
    for (const BeamDetection& beam : detected.detections) {
      ++beams;
      if (beam.obstacle_bin >= 0 && std::abs(beam.range_m - kWallRange_m) <= 0.1) ++on_wall;
    }
  }
  return beams > 0 ? static_cast<double>(on_wall) / static_cast<double>(beams) : 0.0;
}

TEST(detectionRoundTank, TheWallIsDetectedAtEveryBearing) {
  const SonarLog log = roundTank(7);
  EXPECT_GE(shareOnTheWall(log, DetectorOptions{}), 0.9);
  DetectorOptions local;
  local.reverberation.enabled = true;
  EXPECT_GE(shareOnTheWall(log, local), 0.9) << "the local reverberation level";
}

TEST(detectionRoundTank, TheBackgroundIsTheWaterAroundTheWall) {
  const SonarLog log = roundTank(5);
  const std::vector<SweepRange> sweeps = splitSweeps(log.beams);
  ASSERT_FALSE(sweeps.empty());
  const PolarImage polar = makePolarImage(log.beams, sweeps.front().first, sweeps.front().last_exclusive);
  const SweepCalibration calibration = calibrateSweep(polar, CalibrationOptions{}, 45.0);
  const auto wall = static_cast<std::size_t>(kWallRange_m / polar.bin_length_m + 1.0);
  EXPECT_LE(calibration.background[wall], 20.0f) << "the wall, at every bearing, is not the background";
  EXPECT_LT(calibration.backgroundCap(static_cast<int>(wall)), 20.0f);
  // Elsewhere the background is the speckle's 25th percentile across bearings, uncapped.
  const auto water = static_cast<std::size_t>(3.0 / polar.bin_length_m);
  EXPECT_NEAR(calibration.background[water], 5.0f, 2.0f);
  EXPECT_TRUE(std::isinf(calibration.backgroundCap(static_cast<int>(water))));
}

TEST(detectionRoundTank, TheMapHoldsTheWallAtEveryBearing) {
  const SonarMapper mapper = mapSonarLog(roundTank(11));
  const auto& map = mapper.map();
  int bearings_on_wall = 0;
  for (int i = 0; i < kBeamsPerTurn; ++i) {
    const double bearing_rad = 2.0 * M_PI * i / kBeamsPerTurn;
    bool found = false;
    for (double range_m = kWallRange_m - 0.1; range_m <= kWallRange_m + 0.1 && !found; range_m += 0.01) {
      const auto key = map.coder().keyOf(Eigen::Vector3d(range_m * std::cos(bearing_rad), range_m * std::sin(bearing_rad), 0.0));
      if (!key) continue;
      const std::optional<float> log_odds = map.search(*key);
      found = log_odds && map.model().isOccupied(*log_odds);
    }
    if (found) ++bearings_on_wall;
  }
  EXPECT_GE(bearings_on_wall, static_cast<int>(0.9 * kBeamsPerTurn)) << bearings_on_wall << " of " << kBeamsPerTurn;
  // Nothing occupied well inside the tank: the speckle is water.
  int inside = 0;
  for (int i = 0; i < kBeamsPerTurn; i += 4) {
    const double bearing_rad = 2.0 * M_PI * i / kBeamsPerTurn;
    for (double range_m = 1.5; range_m < kWallRange_m - 0.5; range_m += 0.05) {
      const auto key = map.coder().keyOf(Eigen::Vector3d(range_m * std::cos(bearing_rad), range_m * std::sin(bearing_rad), 0.0));
      const std::optional<float> log_odds = key ? map.search(*key) : std::nullopt;
      if (log_odds && map.model().isOccupied(*log_odds)) ++inside;
    }
  }
  EXPECT_EQ(inside, 0);
}

}  // namespace
}  // namespace sonarmap
