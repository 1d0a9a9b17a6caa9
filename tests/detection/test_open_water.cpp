// Open water holds no obstacle, however the transducer rings. A Ping360 at gain 0 (the power-on
// gain: its water clipped to 0 by the A/D, as the shared Ping Viewer logs' gain-0 pings show it)
// rings down over its first metre, and by a level that varies from ping to ping
// (EchoModelOptions::self_reflection_spread_db; the shared logs at 60 m: a 5–6 dB spread beyond
// speckle's). The near field the calibration measures ends where most beams have come down: the
// pings that ring longer must not be taken for echoes standing out of the 0-count water beyond it.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/sweeps.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap {
namespace {

/// Two turns of `preset` in the built-in open water.
SonarLog openWater(MsisSimulationOptions options) {
  options.turns = 2;
  return simulateMsis(builtinScene("open-water", options.head.range_m), options).log;
}

MsisSimulationOptions presetOptions(const std::string& name) {
  const SonarPreset preset = sonarPreset(name);
  MsisSimulationOptions options;
  options.head = preset.head;
  options.echo = preset.echo;
  return options;
}

/// `preset` at gain 0, ringing down in dB from a saturated plateau (to plateau_m) over taper_m,
/// its level spread by spread_db from ping to ping.
MsisSimulationOptions ringingAtGainZero(const std::string& preset, double plateau_m, double taper_m, double spread_db) {
  MsisSimulationOptions options = presetOptions(preset);
  options.echo.ad_low_db = -40.0;  // the ping360-2m and -5m presets' gain 0: the water's noise at 0 counts
  options.echo.self_reflection_end_m = plateau_m;
  options.echo.self_reflection_intensity = 250.0;
  options.echo.self_reflection_taper_m = taper_m;
  options.echo.self_reflection_taper_db = true;
  options.echo.self_reflection_spread_db = spread_db;
  return options;
}

/// Beams with an obstacle when `log` is mapped with the defaults, and the map's occupied updates.
MappingStats mapped(const SonarLog& log) { return mapSonarLog(log).stats(); }

TEST(detectionOpenWater, OpenWaterNoiseAndRingDownGiveNoObstacle) {
  // 50 m: a metre of ring-down (20 counts at about 0.95 m on the mean ping), 6 dB from ping to ping.
  const SonarLog log = openWater(ringingAtGainZero("ping360", 0.15, 0.9, 6.0));
  const MappingStats stats = mapped(log);
  EXPECT_EQ(stats.obstacles, 0U);
  EXPECT_EQ(stats.occupied_updates, 0U);
  EXPECT_GT(stats.free_updates, 0U) << "open water is mapped free";
}

TEST(detectionOpenWater, OpenWaterNoiseAndRingDownGiveNoObstacleAt5m) {
  // 5 m, 4 mm bins: the ring-down over 1 m is 240 bins of a tail the evidence adds up.
  const SonarLog log = openWater(ringingAtGainZero("ping360-5m", 0.10, 0.9, 6.0));
  const MappingStats stats = mapped(log);
  EXPECT_EQ(stats.obstacles, 0U);
  EXPECT_EQ(stats.occupied_updates, 0U);
}

/// Each sweep of `log` detected with the default detector (the evidence detector).
std::vector<SweepDetection> detectedSweeps(const SonarLog& log) {
  std::vector<SweepDetection> sweeps;
  for (const SweepRange& sweep : splitSweeps(log.beams)) {
    sweeps.push_back(detectSweep(makePolarImage(log.beams, sweep.first, sweep.last_exclusive), DetectorOptions{}));
  }
  return sweeps;
}

TEST(detectionOpenWater, OpenWaterNoiseAndRingDownGiveNoReturnByTheirEvidence) {
  // 5 m at gain 0: the water clipped to 0 counts but for blobs of noise and the longer rings, each
  // many bins long. Their evidence is a look per blob, not a look per pulse length: no beam's first
  // return is certain by its evidence (the 2 cm pulse's weighting alone found 26 in two turns).
  const SonarLog log = openWater(ringingAtGainZero("ping360-5m", 0.10, 0.9, 6.0));
  const double pulse_bins = 0.02 / log.beams.front().bin_length_m;
  std::size_t weak = 0;
  for (const SweepDetection& sweep : detectedSweeps(log)) {
    for (const BeamDetection& beam : sweep.detections) weak += beam.hasObstacle() && beam.weak ? 1 : 0;
    // The water's runs, measured: several pulse lengths.
    EXPECT_GT(sweep.calibration.water_bins_per_look, 2.0 * pulse_bins);
  }
  EXPECT_EQ(weak, 0U);
}

TEST(detectionOpenWater, SpeckleAtNormalGainIsALookPerPulse) {
  // The ping360 preset's own gain: speckle whose looks are about the pulse's length (4.8 bins;
  // EchoModelOptions::speckle_looks 5), so the pulse's weighting stands.
  const SonarLog log = openWater(presetOptions("ping360"));
  for (const SweepDetection& sweep : detectedSweeps(log)) {
    EXPECT_GT(sweep.calibration.water_bins_per_look, 2.0);
    EXPECT_LT(sweep.calibration.water_bins_per_look, 0.2 / log.beams.front().bin_length_m);
  }
}

TEST(detectionOpenWater, OpenWaterNoiseAtNormalGainGivesNoObstacle) {
  // The ping360 preset's own gain: a grainy noise floor over the far third of the range, its
  // ringing to 1 m, alike on every ping and spread.
  for (const double spread_db : {0.0, 6.0}) {
    MsisSimulationOptions options = presetOptions("ping360");
    options.echo.self_reflection_spread_db = spread_db;
    const MappingStats stats = mapped(openWater(options));
    EXPECT_EQ(stats.obstacles, 0U) << spread_db;
    EXPECT_EQ(stats.occupied_updates, 0U) << spread_db;
  }
}

}  // namespace
}  // namespace sonarmap
