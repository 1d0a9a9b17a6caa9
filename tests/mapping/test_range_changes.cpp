// Logs whose range scale or gain changes while the head turns (a Ping360 powers on at about 2 m,
// users turn the range knob while they watch): they map in batch and live, each sweep calibrated on
// beams of one setting, the automatic resolution following the scale most beams use (batch) or
// growing with the range (live), a passing scale counted, not mixed into another's image.
#include <gtest/gtest.h>

#include <cstddef>
#include <tuple>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sonar/range_scales.hpp"

namespace sonarmap {
namespace {

/// `turns` turns of the simulated Micron in the tank at `range_m` with `bins`, from `start_s`.
SonarLog tankTurns(double range_m, int bins, std::size_t turns, double start_s, std::uint64_t seed) {
  MsisSimulationOptions options;
  options.head.range_m = range_m;
  options.head.bins = bins;
  options.turns = turns;
  options.start_time_s = start_s;
  options.nav_rate_hz = 0.0;
  options.seed = seed;
  return simulateMsis(builtinScene("tank"), options).log;
}

void append(SonarLog& log, const SonarLog& more, std::size_t count = 0) {
  const std::size_t n = count == 0 ? more.beams.size() : count;
  log.beams.insert(log.beams.end(), more.beams.begin(), more.beams.begin() + static_cast<std::ptrdiff_t>(n));
}

double lastTime(const SonarLog& log) { return log.beams.back().time_s + 0.05; }

/// One turn at 2.5 m (a power-on range), 5 beams at 10 m (a knob's passing stop), then 3 turns at 5 m;
/// bins of 1, 2 and 1.25 cm (a range scale is a bin length: the bin count alone may differ between
/// beams of one scale, as the CRAS log's last beam).
SonarLog powerOnThenUserRange() {
  SonarLog log = tankTurns(2.5, 250, 1, 0.0, 1);
  append(log, tankTurns(10.0, 500, 1, lastTime(log), 2), 5);
  append(log, tankTurns(5.0, 399, 3, lastTime(log), 3));
  return log;
}

std::vector<std::tuple<Key16, int, float>> leavesOf(const OcTree16& map) {
  std::vector<std::tuple<Key16, int, float>> leaves;
  map.forEachLeaf([&](const LeafView<16>& leaf) { leaves.emplace_back(leaf.key, leaf.depth, leaf.log_odds); });
  return leaves;
}

TEST(mappingRangeChanges, BatchMapsEveryScaleAndCountsAPassingOne) {
  const SonarLog log = powerOnThenUserRange();
  const std::vector<RangeScale> scales = rangeScales(log);
  ASSERT_EQ(scales.size(), 3U);
  EXPECT_EQ(scales[1].beams, 5U);
  const SonarMapper mapper = mapSonarLog(log);
  EXPECT_EQ(mapper.stats().beams_uncalibrated, 5U);  // 10 m: never a whole sweep
  EXPECT_EQ(mapper.stats().beams_used, log.beams.size() - 5);
  EXPECT_EQ(mapper.stats().sweeps, 4U);
  // The automatic resolution follows the 5 m scale (600 of 805 beams), not the 10 m reach.
  EXPECT_DOUBLE_EQ(mapper.map().resolution_m(), 0.02);
  const AutoResolution chosen = autoResolutionForLog(log, MapperOptions{});
  EXPECT_EQ(chosen.scales, 3U);
  EXPECT_EQ(chosen.scale.beams, 600U);
  EXPECT_FALSE(chosen.coarsened);
  // The tank's walls (±2.2 m) are mapped.
  EXPECT_GT(mapper.stats().obstacles, 500U);
}

TEST(mappingRangeChanges, TheAutomaticResolutionIsCoarsenedToFitTheBudgetUpToTheLongestReach) {
  // The longest beams (10 m) set the work per beam: 2 cm does not fit half of what they need at
  // 2 cm, 5 cm (the next of 1, 2, 5) does.
  const SonarLog log = powerOnThenUserRange();
  MapperOptions options;
  options.resolution_m = 0.02;
  const double updates = estimateVoxelUpdatesPerBeam(options, logReach_m(log, options.max_range_m));
  options.resolution_m.reset();
  options.max_voxel_updates_per_beam = 0.5 * updates;
  AutoResolution chosen = autoResolutionForLog(log, options);
  EXPECT_DOUBLE_EQ(chosen.resolution_m, 0.05);
  EXPECT_TRUE(chosen.coarsened);
  EXPECT_NO_THROW(checkWorkBudget(log, options));
  // Never coarser than the longest reach's own (10 m: 5 cm); the budget check then says what fits.
  options.max_voxel_updates_per_beam = 1.0;
  chosen = autoResolutionForLog(log, options);
  EXPECT_DOUBLE_EQ(chosen.resolution_m, 0.05);
  EXPECT_THROW(mapSonarLog(log, options), ValueError);
}

TEST(mappingRangeChanges, APassingStopOfAScaleSeenBeforeUsesThatScalesCalibration) {
  // 2 turns at 5 m, 5 beams at 2.5 m, 5 beams at 5 m again, a turn at 2.5 m: the 5-beam return to
  // 5 m is detected with the 5 m sweeps' calibration; the first 2.5 m stop, before any whole 2.5 m
  // sweep, is not.
  SonarLog log = tankTurns(5.0, 399, 2, 0.0, 1);
  append(log, tankTurns(2.5, 250, 1, lastTime(log), 2), 5);
  append(log, tankTurns(5.0, 399, 1, lastTime(log), 3), 5);
  append(log, tankTurns(2.5, 250, 1, lastTime(log), 4));
  const SonarMapper mapper = mapSonarLog(log);
  EXPECT_EQ(mapper.stats().beams_uncalibrated, 5U);
  EXPECT_EQ(mapper.stats().beams_used, log.beams.size() - 5);
}

TEST(mappingRangeChanges, AGainChangeEndsASweepAsARangeChangeDoes) {
  SonarLog log = tankTurns(5.0, 399, 2, 0.0, 1);
  for (std::size_t i = 300; i < log.beams.size(); ++i) log.beams[i].gain_setting = 2;
  EXPECT_EQ(groupSweeps(log.beams, 20), (std::vector<SweepRange>{{0, 200}, {200, 300}, {300, 400}}));
  const SonarMapper mapper = mapSonarLog(log);
  EXPECT_EQ(mapper.stats().sweeps, 3U);
  EXPECT_EQ(mapper.stats().beams_uncalibrated, 0U);
}

TEST(mappingRangeChanges, LiveMapsEveryScaleAndItsResolutionGrowsWithTheRange) {
  const SonarLog log = powerOnThenUserRange();
  for (const OnlineIntegration integration : {OnlineIntegration::kSweep, OnlineIntegration::kProvisionalBeams}) {
    OnlineMapper online(MapperOptions{}, integration);
    for (const Beam& beam : log.beams) {
      online.addBeam(beam);
      // The map as shown follows the committed map's resolution as it coarsens.
      EXPECT_EQ(online.shownSnapshot().resolution_m(), online.mapSnapshot().resolution_m());
    }
    online.finish();
    const SonarMapper& mapper = online.mapper();
    // The first sweep (2.5 m) fixed 1 cm; the 5 m sweeps coarsened it to 2 cm (the 10 m stop was
    // never calibrated, so never integrated: it changes nothing).
    EXPECT_DOUBLE_EQ(mapper.map().resolution_m(), 0.02);
    EXPECT_EQ(mapper.stats().resolution_changes, 1U);
    EXPECT_EQ(mapper.stats().beams_uncalibrated, 5U);
    EXPECT_EQ(mapper.stats().beams_used, log.beams.size() - 5);
    EXPECT_GT(mapper.stats().obstacles, 500U);
  }
}

TEST(mappingRangeChanges, LiveGivesTheBatchMapAtAGivenResolution) {
  const SonarLog log = powerOnThenUserRange();
  MapperOptions options;
  options.resolution_m = 0.02;
  const SonarMapper batch = mapSonarLog(log, options);
  for (const OnlineIntegration integration : {OnlineIntegration::kSweep, OnlineIntegration::kProvisionalBeams}) {
    OnlineMapper online(options, integration);
    for (const Beam& beam : log.beams) online.addBeam(beam);
    online.finish();
    EXPECT_EQ(leavesOf(online.mapper().map()), leavesOf(batch.map()));
    EXPECT_EQ(leavesOf(online.shownSnapshot()), leavesOf(batch.map()));
  }
}

// Three turns at 5 m, then one at 10 m: a stream that has not ended would map at the 10 m scale's
// 5 cm, the log maps at 2 cm, the scale most of its beams use. Given the log's options
// (mappingOptionsForLog), the online mapper fed its beams gives the batch map, as `live` replaying
// a log does.
TEST(mappingRangeChanges, LiveGivesTheBatchMapWithTheLogsOptions) {
  SonarLog log = tankTurns(5.0, 399, 3, 0.0, 1);
  append(log, tankTurns(10.0, 500, 1, lastTime(log), 2));
  const SonarMapper batch = mapSonarLog(log);
  EXPECT_DOUBLE_EQ(batch.map().resolution_m(), 0.02);
  OnlineMapper streamed(MapperOptions{});
  for (const Beam& beam : log.beams) streamed.addBeam(beam);
  streamed.finish();
  EXPECT_DOUBLE_EQ(streamed.mapper().map().resolution_m(), 0.05);
  const MapperOptions options = mappingOptionsForLog(MapperOptions{}, log);
  ASSERT_TRUE(options.resolution_m.has_value());
  EXPECT_DOUBLE_EQ(*options.resolution_m, 0.02);
  OnlineMapper online(options);
  EXPECT_EQ(online.optionsSnapshot().resolution_m, options.resolution_m);
  for (const Beam& beam : log.beams) online.addBeam(beam);
  online.finish();
  EXPECT_EQ(leavesOf(online.mapper().map()), leavesOf(batch.map()));
  // The budget is checked as mapSonarLog checks it.
  MapperOptions fine;
  fine.resolution_m = 0.001;
  fine.max_voxel_updates_per_beam = 1e4;
  EXPECT_THROW(mappingOptionsForLog(fine, log), ValueError);
}

}  // namespace
}  // namespace sonarmap

namespace sonarmap {
namespace {

TEST(mappingRangeChanges, ASweepCutShortIsDetectedWithItsSettingsLastWholeSweep) {
  // Two turns at 5 m, one at 10 m, then 40 beams at 5 m (a fifth of a turn) in which a bright
  // return fills 0.3–2 m in every beam (a seabed close under the head) and the log ends. Calibrated
  // on its own, those 40 beams would take the bright stretch, present in all of them, for the
  // vehicle's self-reflection band and detect nothing before 2 m; a fifth of a turn is detected
  // with the calibration of the last whole 5 m turn instead.
  SonarLog log = tankTurns(5.0, 399, 2, 0.0, 1);
  append(log, tankTurns(10.0, 500, 1, lastTime(log), 2));
  const SonarLog last = tankTurns(5.0, 399, 1, lastTime(log), 3);
  append(log, last, 40);
  for (std::size_t i = log.beams.size() - 40; i < log.beams.size(); ++i) {
    std::vector<std::uint8_t>& bins = log.beams[i].intensities;
    for (std::size_t c = 0; c < bins.size(); ++c) {
      const double range_m = (static_cast<double>(c) + 0.5) * log.beams[i].bin_length_m;
      if (range_m > 0.3 && range_m < 2.0) bins[c] = 180;
    }
  }
  const SonarMapper mapper = mapSonarLog(log);
  EXPECT_EQ(mapper.stats().beams_uncalibrated, 0U);
  EXPECT_EQ(mapper.stats().beams_used, log.beams.size());
  // The last detection (the 40 beams) used the whole turn's band and near field, not 2 m.
  EXPECT_LT(mapper.stats().calibration.band_end_m, 0.5);
  EXPECT_LT(mapper.stats().calibration.min_range_m, 1.0);
  // Most of the 40 beams find an obstacle (the bright stretch's start or the wall before it).
  SonarLog whole = log;
  whole.beams.resize(log.beams.size() - 40);
  EXPECT_GE(mapper.stats().obstacles, mapSonarLog(whole).stats().obstacles + 35);
}

}  // namespace
}  // namespace sonarmap
