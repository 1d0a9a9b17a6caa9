// Localization with the heading alone (the "ahrs" navigation class, OdometryNoise::position_measured
// false): a BlueROV2 without a DVL logs its attitude and leaves north and east at 0, and the scans
// must give the position.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/temp_dir.hpp"
#include "slam_fixture.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"
#include "sonarmap/formats/ros_bag_writer.hpp"
#include "sonarmap/eval/trajectory_error.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/slam/localizer.hpp"
#include "sonarmap/slam/scan_forming.hpp"

namespace sonarmap {
namespace {

/// `track` with north and east 0 at every fix: what a vehicle log without a horizontal position gives.
NavTrack headingOnly(NavTrack track) {
  for (NavSample& fix : track) fix.position_ned_m.head<2>().setZero();
  return track;
}

TEST(slamHeadingOnly, TheClassKnowsThePositionIsNotMeasured) {
  const OdometryNoise ahrs = odometryNoiseOf("ahrs");
  EXPECT_FALSE(ahrs.position_measured);
  const double duration_s = 10.0;
  const Eigen::Matrix3d covariance = ahrs.covariance(Pose2{}, duration_s);
  // The position as unknown as without navigation, the heading as the AHRS's.
  const double position_sigma_m = ahrs.unknown_speed_sigma_mps * duration_s;
  EXPECT_NEAR(covariance(0, 0), position_sigma_m * position_sigma_m, 1e-5);
  EXPECT_NEAR(covariance(1, 1), position_sigma_m * position_sigma_m, 1e-5);
  EXPECT_NEAR(covariance(2, 2), ahrs.gyro_walk_rad_per_sqrt_s * ahrs.gyro_walk_rad_per_sqrt_s * duration_s, 1e-6);
  EXPECT_EQ(covariance(0, 1), 0.0);
}

TEST(slamHeadingOnly, ATrackThatNeverMovesIsTakenForTheHeadingAlone) {
  NavTrack track(3);
  for (std::size_t i = 0; i < track.size(); ++i) {
    track[i].time_s = static_cast<double>(i);
    track[i].position_ned_m.z() = 2.0 + static_cast<double>(i);  // the depth may change
    track[i].yaw_rad = 0.3 * static_cast<double>(i);
  }
  EXPECT_EQ(navigationClassOf(track), "ahrs");
  track[2].position_ned_m.x() = 0.01;
  EXPECT_EQ(navigationClassOf(track), "dvl-ahrs");
  EXPECT_EQ(navigationClassOf(NavTrack{}), "dvl-ahrs");
  EXPECT_EQ(navigationClassOf(NavTrack(1)), "dvl-ahrs");
}

TEST(slamHeadingOnly, TheScansGiveThePositionOfAVehicleAlongAHull) {
  // A SeaKing flying the hull loop (186 m) with a drifting heading (1.5° bias, 0.02°/√s walk) and
  // no position: the track believed still is 27 m off; the scans, matched from the last scans'
  // velocity, give the path within a few metres (3.8 m on this seed).
  const MsisSimulation run = testing::missionRun("hull-loop", "seaking-30", 0.0, 1.5, 0.02, 1);
  const NavTrack heading = headingOnly(run.dead_reckoning);
  ASSERT_EQ(navigationClassOf(heading), "ahrs");
  SlamOptions options;
  options.forming.odometry = odometryNoiseOf("ahrs");
  const SlamResult slam = localize(run.log, heading, defaultSonarToBody(), MapperOptions{}, options);
  EXPECT_TRUE(slam.report.heading_only);
  EXPECT_GT(slam.report.matches_accepted, slam.report.scans / 2);
  // Round the hull it comes back to where it started: the scans' own chain finds the loop.
  EXPECT_GT(slam.report.loopClosuresAccepted(), 0U);
  const double still_m = evaluateTrajectory(heading, run.nav).ate_rmse_m;
  const double slam_m = evaluateTrajectory(slam.trajectory, run.nav).ate_rmse_m;
  EXPECT_GT(still_m, 20.0);
  EXPECT_LT(slam_m, 0.25 * still_m) << "still " << still_m << " m";
  // The heading is the AHRS's: the scans do not turn the track.
  for (std::size_t i = 0; i < slam.trajectory.size(); i += 50) {
    EXPECT_LT(std::abs(wrapAngle_rad(slam.trajectory[i].yaw_rad - heading[i].yaw_rad)), 2.0 * std::numbers::pi / 180.0) << i;
  }
  // The same navigation stated as a DVL's with an AHRS: the vehicle is believed still.
  const SlamResult believed = localize(run.log, heading, defaultSonarToBody(), MapperOptions{});
  EXPECT_FALSE(believed.report.heading_only);
  EXPECT_GT(evaluateTrajectory(believed.trajectory, run.nav).ate_rmse_m, 0.8 * still_m);
}

TEST(slamHeadingOnly, AnImuOnlyRosBagIsLocalizedOnItsHeading) {
  // A vehicle without a DVL recording its IMU and depth sensor to a ROS bag: the bag's navigation
  // has no position, "auto" takes it for the ahrs class, and the scans give the path.
  MsisSimulation run = testing::missionRun("hull-loop", "seaking-30", 0.0, 1.5, 0.02, 1);
  for (Beam& beam : run.log.beams) beam.time_s += 1.4e9;  // a recorder's clock
  for (NavSample& fix : run.dead_reckoning) fix.time_s += 1.4e9;
  for (NavSample& fix : run.nav) fix.time_s += 1.4e9;
  const test::TempDir dir;
  writeRosBag(dir.file("imu.bag"), run.log, run.dead_reckoning, {.odometry = false, .raw_sensors = true, .raw_dvl = false});
  const std::optional<RosBagNavigation> read = readRosBagNavigation(dir.file("imu.bag"));
  ASSERT_TRUE(read.has_value());
  ASSERT_EQ(navigationClassOf(read->track), "ahrs");
  SlamOptions options;
  options.forming.odometry = odometryNoiseOf(navigationClassOf(read->track));
  const SlamResult slam = localize(readRosBag(dir.file("imu.bag")), read->track, defaultSonarToBody(), MapperOptions{}, options);
  EXPECT_TRUE(slam.report.heading_only);
  const double still_m = evaluateTrajectory(read->track, run.nav).ate_rmse_m;
  EXPECT_LT(evaluateTrajectory(slam.trajectory, run.nav).ate_rmse_m, 0.25 * still_m) << "still " << still_m << " m";
}

}  // namespace
}  // namespace sonarmap
