// A log's sweeps detected once (mapping/detected_log.hpp): integrating the detected sweeps gives
// mapSonarLog's map leaf for leaf, the sweeps are the mapper's (short groups detected with their
// setting's calibration, a passing range scale counted), and misuse is refused.
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "octree/octree_testing.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/detected_log.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {
namespace {

using testing::leavesOf;

/// `turns` turns of the simulated Micron in the tank at `range_m` in 400 bins, moving north at 0.1 m/s.
MsisSimulation tankRun(double range_m, std::size_t turns, double start_s, std::uint64_t seed) {
  MsisSimulationOptions options;
  options.head.range_m = range_m;
  options.head.bins = 400;  // a range scale is a bin length: 1.25, 2.5 and 1 cm
  options.turns = turns;
  options.start_time_s = start_s;
  options.seed = seed;
  options.trajectory = constantVelocityTrajectory(NavSample{}, Eigen::Vector3d(0.1, 0.0, 0.0), 0.02);
  return simulateMsis(builtinScene("tank"), options);
}

/// Two turns at 5 m, 6 beams at 10 m (a range knob's passing stop), two turns at 4 m and the
/// first 20 beams of a third (a group cut short by the end of the log), with the navigation of
/// the whole span.
MsisSimulation rangeChanges() {
  MsisSimulation run = tankRun(5.0, 2, 0.0, 1);
  const auto append = [&run](const MsisSimulation& more, std::size_t count) {
    run.log.beams.insert(run.log.beams.end(), more.log.beams.begin(),
                         more.log.beams.begin() + static_cast<std::ptrdiff_t>(count));
  };
  const MsisSimulation passing = tankRun(10.0, 1, run.log.beams.back().time_s + 0.05, 2);
  append(passing, 6);
  const MsisSimulation last = tankRun(4.0, 3, run.log.beams.back().time_s + 0.05, 3);
  append(last, 2 * last.log.beams.size() / 3 + 20);
  run.nav = tankRun(5.0, 8, 0.0, 4).nav;  // the same motion over a longer span
  return run;
}

MapperOptions atTwoCentimetres() {
  MapperOptions options;
  options.resolution_m = 0.02;
  return options;
}

TEST(mappingDetectedLog, IntegratingTheDetectedSweepsGivesTheBatchMap) {
  const MsisSimulation run = rangeChanges();
  const Eigen::Isometry3d mounting = defaultSonarToBody();
  const SonarMapper batch = mapSonarLog(run.log, run.nav, mounting, atTwoCentimetres());
  const DetectedLog detected = detectSonarLog(run.log, atTwoCentimetres());
  std::size_t progress_calls = 0;
  const SonarMapper mapped =
      mapDetectedLog(detected, run.nav, mounting, [&](std::size_t, std::size_t) { ++progress_calls; });
  const auto expected = leavesOf(batch.map());
  ASSERT_GT(expected.size(), 1000U);
  EXPECT_EQ(leavesOf(mapped.map()), expected);
  EXPECT_EQ(mapped.stats().sweeps, batch.stats().sweeps);
  EXPECT_EQ(mapped.stats().beams_used, batch.stats().beams_used);
  EXPECT_EQ(mapped.stats().obstacles, batch.stats().obstacles);
  EXPECT_EQ(mapped.stats().beams_uncalibrated, batch.stats().beams_uncalibrated);
  EXPECT_EQ(mapped.stats().detection.beams, batch.stats().detection.beams);
  EXPECT_EQ(progress_calls, detected.sweeps.size());
}

TEST(mappingDetectedLog, TheSweepsAreTheMappersAndCoverTheLog) {
  const MsisSimulation run = rangeChanges();
  const DetectedLog detected = detectSonarLog(run.log, atTwoCentimetres());
  EXPECT_EQ(detected.beams_uncalibrated, 6U);  // the 10 m stop: never a whole sweep of its own
  ASSERT_GE(detected.sweeps.size(), 4U);
  std::size_t next = 0, skipped = 0;
  for (const DetectedSweep& sweep : detected.sweeps) {
    ASSERT_GE(sweep.first_beam, next);
    skipped += sweep.first_beam - next;  // beams not detected: uncalibrated
    next = sweep.first_beam;
    ASSERT_EQ(sweep.detection.detections.size(), static_cast<std::size_t>(sweep.polar.rows()));
    for (int row = 0; row < sweep.polar.rows(); ++row) {
      EXPECT_EQ(sweep.polar.time_s[static_cast<std::size_t>(row)], run.log.beams[next + static_cast<std::size_t>(row)].time_s);
    }
    next += static_cast<std::size_t>(sweep.polar.rows());
  }
  EXPECT_EQ(next, run.log.beams.size());
  EXPECT_EQ(skipped, detected.beams_uncalibrated);
  // The cut-short last group is detected with its setting's calibration: the background measured
  // on the 4 m sweep before it, not on its own 20 bearings.
  const DetectedSweep& last = detected.sweeps.back();
  const DetectedSweep& before = detected.sweeps[detected.sweeps.size() - 2];
  EXPECT_EQ(last.setting, before.setting);
  EXPECT_EQ(last.detection.calibration.background, before.detection.calibration.background);
  EXPECT_FALSE(detected.options.resolution_m == std::nullopt);  // resolved for the log
}

TEST(mappingDetectedLog, MisuseIsRefused) {
  OnlineMapper live(atTwoCentimetres(), OnlineIntegration::kProvisionalBeams);
  EXPECT_THROW(live.detectOnly([](DetectedSweep&&) {}), ValueError);
  OnlineMapper empty_sink(atTwoCentimetres());
  EXPECT_THROW(empty_sink.detectOnly({}), ValueError);

  const MsisSimulation run = tankRun(5.0, 1, 0.0, 5);
  OnlineMapper started(atTwoCentimetres());
  started.addBeam(run.log.beams.front());
  EXPECT_THROW(started.detectOnly([](DetectedSweep&&) {}), ValueError);  // after the first beam

  const DetectedLog detected = detectSonarLog(run.log, atTwoCentimetres());
  ASSERT_FALSE(detected.sweeps.empty());
  OnlineMapper detecting(atTwoCentimetres());
  detecting.detectOnly([](DetectedSweep&&) {});
  EXPECT_THROW(detecting.addDetectedSweep(detected.sweeps.front()), ValueError);

  DetectedSweep broken = detected.sweeps.front();
  broken.detection.detections.pop_back();
  OnlineMapper mapping(atTwoCentimetres());
  EXPECT_THROW(mapping.addDetectedSweep(broken), ValueError);  // rows and detections differ
  EXPECT_THROW(mapDetectedLog(detected, NavTrack{}, defaultSonarToBody()), ValueError);  // no navigation
}

}  // namespace
}  // namespace sonarmap
