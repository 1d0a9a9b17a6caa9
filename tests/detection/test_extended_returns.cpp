// Weak extended returns (extended_returns.hpp): the noise the binary integration compares with is
// measured without the echoes a first pass found (censoring). A static Micron tilted 25° down,
// 2 m over a flat seabed, hears it in the bearings that look the way it tilts (about a third of a
// turn): measured over every bin, those echoes raise the lit level and lengthen the runs taken for
// speckle's looks, so the seabed's own bins stop counting; measured without them, the calibration
// is that of open water and the seabed is found in nearly every beam that hears it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/detection/extended_returns.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sonar/polar.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// One turn of a static Micron tilted 25° down, 2 m over a flat seabed (reflectivity 0.5), or in
/// open water (no surface at all), as a polar image.
PolarImage tiltedTurn(bool seabed) {
  MsisSimulationOptions options;
  options.turns = 1;
  options.sonar_to_body = defaultSonarToBody() * Eigen::AngleAxisd(-25.0 * kDegree, Eigen::Vector3d::UnitY());  // 25° down
  const Scene scene = seabed ? Scene{{Plane{{0.0, 0.0, -2.0}, Eigen::Vector3d::UnitZ(), 0.5}}}
                             : Scene{{Plane{{0.0, 0.0, -500.0}, Eigen::Vector3d::UnitZ(), 0.5}}};
  const MsisSimulation run = simulateMsis(scene, options);
  return makePolarImage(run.log.beams, 0, run.log.beams.size());
}

MapperOptions volume() {
  MapperOptions options;
  options.beam_model = BeamModel::kVolume;
  options.resolution_m = 0.05;
  return options;
}

/// The bins of each row's extended return, as the second pass leaves them out.
std::vector<EchoBins> returnBins(const SweepDetection& sweep, double bin_m) {
  std::vector<EchoBins> echoes(sweep.detections.size());
  for (std::size_t row = 0; row < echoes.size(); ++row) {
    const BeamDetection& beam = sweep.detections[row];
    if (beam.hasExtendedReturn()) {
      echoes[row] = {static_cast<int>(beam.extended_onset_m / bin_m), static_cast<int>(beam.extended_end_m / bin_m) + 1};
    }
  }
  return echoes;
}

TEST(detectionExtendedReturns, TheNoiseIsMeasuredWithoutTheReturnsFound) {
  const SonarMapper mapper(volume());
  PolarImage seabed = tiltedTurn(true), water = tiltedTurn(false);
  const SweepDetection found = mapper.detectSweep(seabed);
  const SweepDetection quiet = mapper.detectSweep(water);
  // The seabed enters the aperture's lower edge (42.5° down) at 2.96 m in the bearing of the tilt;
  // beams within 50° of it meet it within the Micron's 5 m.
  std::size_t facing = 0, facing_found = 0, other_found = 0;
  for (std::size_t row = 0; row < found.detections.size(); ++row) {
    const double off_rad = std::abs(std::remainder(seabed.bearing_rad[row], 2.0 * std::numbers::pi));
    const bool hit = found.detections[row].hasExtendedReturn();
    if (off_rad < 50.0 * kDegree) {
      ++facing;
      facing_found += hit ? 1 : 0;
    } else if (off_rad > 90.0 * kDegree) {
      other_found += hit ? 1 : 0;
    }
  }
  EXPECT_GE(facing_found, facing * 9 / 10) << facing_found << " of " << facing;
  EXPECT_EQ(other_found, 0U);
  for (const BeamDetection& beam : quiet.detections) EXPECT_FALSE(beam.hasExtendedReturn());
  // The calibration with the returns left out is open water's; with them it is not.
  const double bin_m = seabed.bin_length_m;
  const double percentile = volume().detector.background.calibration.background_percentile;
  auto calibrate = [&](const PolarImage& polar, const SweepDetection& sweep, const std::vector<EchoBins>& echoes) {
    return calibrateExtendedReturns(polar, sweep.calibration.background, percentile, sweep.calibration.span_db,
                                    std::max(sweep.min_range_m, sweep.calibration.near_field_end_m), ExtendedReturnOptions{},
                                    echoes);
  };
  const ExtendedReturnCalibration all = calibrate(seabed, found, {});
  const ExtendedReturnCalibration censored = calibrate(seabed, found, returnBins(found, bin_m));
  const ExtendedReturnCalibration open_water = calibrate(water, quiet, {});
  const auto at4m = static_cast<std::size_t>(4.0 / bin_m);
  EXPECT_GT(all.lit_counts[at4m] - open_water.lit_counts[at4m], 4.0F);
  EXPECT_NEAR(censored.lit_counts[at4m], open_water.lit_counts[at4m], 4.0F);
  EXPECT_GT(all.bins_per_look, 1.3 * open_water.bins_per_look);
  EXPECT_NEAR(censored.bins_per_look, open_water.bins_per_look, 0.2 * open_water.bins_per_look);
  std::printf("lit level at 4 m: %.1f counts over every bin, %.1f without the returns, %.1f in open water; bins "
              "per look %.2f, %.2f, %.2f; seabed found in %zu of %zu beams facing it\n",
              all.lit_counts[at4m], censored.lit_counts[at4m], open_water.lit_counts[at4m], all.bins_per_look,
              censored.bins_per_look, open_water.bins_per_look, facing_found, facing);
}

TEST(detectionExtendedReturns, EchoRangesMustNumberOnePerBeam) {
  PolarImage seabed = tiltedTurn(true);
  const SonarMapper mapper(volume());
  const SweepDetection found = mapper.detectSweep(seabed);
  const std::vector<EchoBins> too_few(3);
  EXPECT_THROW(calibrateExtendedReturns(seabed, found.calibration.background, 25.0, found.calibration.span_db, 0.3,
                                        ExtendedReturnOptions{}, too_few),
               ValueError);
}

}  // namespace
}  // namespace sonarmap
