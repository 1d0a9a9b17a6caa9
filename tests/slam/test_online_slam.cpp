// Live mapping with localization (slam/online_slam.hpp): fed beam by beam it ends with the batch
// path's trajectory, and its map follows the corrections.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <vector>

#include "octree/octree_testing.hpp"
#include "slam_fixture.hpp"
#include "sonarmap/slam/online_slam.hpp"
#include "sonarmap/slam/slam_mapping.hpp"

namespace sonarmap {
namespace {

using testing::leavesOf;

// Fed beam by beam, showing nothing before a sweep is integrated or each beam at once on the
// provisional layer: the batch's trajectory, exactly when the odometry's period comes from the same
// fixes, and its map leaf for leaf, after finish().
TEST(slamOnline, EndsWithTheBatchTrajectoryAndMap) {
  const MsisSimulation run = testing::missionRun("harbour-loop");
  const NavTrack& drift = run.dead_reckoning;
  MapperOptions options;
  options.resolution_m = 0.05;
  const SlamMapping batch = mapSonarLogWithSlam(run.log, drift, defaultSonarToBody(), options);
  const auto expected = leavesOf(batch.mapper.map());
  ASSERT_GT(expected.size(), 1000U);

  for (const OnlineIntegration integration : {OnlineIntegration::kSweep, OnlineIntegration::kProvisionalBeams}) {
    OnlineSlam live(options, defaultSonarToBody(), true, withNavigationPeriod(SlamOptions{}, drift), integration);
    std::size_t next_fix = 0;
    std::size_t integrated_while_running = 0, shown_before_integrated = 0;
    for (const Beam& beam : run.log.beams) {
      while (next_fix < drift.size() && drift[next_fix].time_s <= beam.time_s) live.addNavFix(drift[next_fix++]);
      live.addBeam(beam);
      integrated_while_running = std::max(integrated_while_running, live.sweepsIntegrated());
      shown_before_integrated += live.beamsUnshown() < live.beamsPending() ? 1 : 0;
    }
    while (next_fix < drift.size()) live.addNavFix(drift[next_fix++]);
    EXPECT_GT(integrated_while_running, 0U);  // the map grows while the vehicle runs
    if (integration == OnlineIntegration::kProvisionalBeams) {
      EXPECT_GT(shown_before_integrated, run.log.beams.size() / 2);
    } else {
      EXPECT_EQ(shown_before_integrated, 0U);
    }
    live.finish();
    EXPECT_EQ(live.beamsPending(), 0U);
    EXPECT_EQ(live.beamsUnshown(), 0U);
    EXPECT_GT(live.rebuilds(), 1U);  // loops closed while running, and the final map
    // Rebuilding costs at most twice the log's integration while running, and once at the end.
    EXPECT_LE(live.sweepsRebuilt(), 3 * live.sweepsIntegrated());
    const NavTrack trajectory = live.trajectory();
    ASSERT_EQ(trajectory.size(), batch.slam.trajectory.size());
    for (std::size_t i = 0; i < trajectory.size(); ++i) {
      ASSERT_EQ(trajectory[i].position_ned_m, batch.slam.trajectory[i].position_ned_m) << i;
      ASSERT_EQ(trajectory[i].yaw_rad, batch.slam.trajectory[i].yaw_rad) << i;
    }
    EXPECT_EQ(leavesOf(live.mapSnapshot()), expected) << "integration " << static_cast<int>(integration);
    EXPECT_EQ(leavesOf(live.shownSnapshot()), expected) << "integration " << static_cast<int>(integration);
  }
}

// With a navigation that gives the heading only (the ahrs class: the position from the scans at
// the last scans' velocity), live ends with the batch's trajectory and map too.
TEST(slamOnline, EndsWithTheBatchTrajectoryOnTheHeadingAlone) {
  const MsisSimulation run = testing::missionRun("hull-loop", "seaking-30", 0.0, 1.5, 0.02, 1);
  NavTrack heading = run.dead_reckoning;
  for (NavSample& fix : heading) fix.position_ned_m.head<2>().setZero();
  SlamOptions slam;
  slam.forming.odometry = odometryNoiseOf("ahrs");
  const SlamMapping batch = mapSonarLogWithSlam(run.log, heading, defaultSonarToBody(), MapperOptions{}, slam);
  ASSERT_TRUE(batch.slam.report.heading_only);
  OnlineSlam live(MapperOptions{}, defaultSonarToBody(), true, slam, OnlineIntegration::kSweep);
  std::size_t next_fix = 0;
  for (const Beam& beam : run.log.beams) {
    while (next_fix < heading.size() && heading[next_fix].time_s <= beam.time_s) live.addNavFix(heading[next_fix++]);
    live.addBeam(beam);
  }
  while (next_fix < heading.size()) live.addNavFix(heading[next_fix++]);
  live.finish();
  const NavTrack trajectory = live.trajectory();
  ASSERT_EQ(trajectory.size(), batch.slam.trajectory.size());
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    ASSERT_NEAR(trajectory[i].position_ned_m.x(), batch.slam.trajectory[i].position_ned_m.x(), 1e-9);
    ASSERT_NEAR(trajectory[i].position_ned_m.y(), batch.slam.trajectory[i].position_ned_m.y(), 1e-9);
  }
  EXPECT_EQ(leavesOf(live.mapSnapshot()), leavesOf(batch.mapper.map()));
}

TEST(slamOnline, RefusesFixesOutOfOrderAndBeamsAfterTheEnd) {
  OnlineSlam live(MapperOptions{}, defaultSonarToBody(), true);
  NavSample fix;
  fix.time_s = 1.0;
  live.addNavFix(fix);
  EXPECT_THROW(live.addNavFix(fix), ValueError);
  live.finish();
  EXPECT_THROW(live.addBeam(Beam{}), ValueError);
  OnlineSlam without(MapperOptions{}, defaultSonarToBody(), false);
  EXPECT_THROW(without.addNavFix(fix), ValueError);
}

}  // namespace
}  // namespace sonarmap
