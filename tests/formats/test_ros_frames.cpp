/// Tests of ROS poses turned into NED fixes (src/formats/ros_frames.hpp, private to formats): ROS's
/// ENU world with a forward-left-up body (REP 103) against the NED world with a forward-right-down
/// body of navigation.hpp, on poses whose answer is known by hand.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "formats/ros_frames.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Quaterniond about(const Eigen::Vector3d& axis, double angle_rad) { return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, axis)); }

TEST(formatsRosFrames, EnuPositionAndHeadingTurnIntoNed) {
  // 2 m east, 1 m north, 3 m down; the body's x (forward) along ENU's y: heading north.
  const NavSample north = rosPoseToNed(5.0, {2.0, 1.0, -3.0}, about(Eigen::Vector3d::UnitZ(), kPi / 2), false);
  EXPECT_EQ(north.time_s, 5.0);
  EXPECT_LT((north.position_ned_m - Eigen::Vector3d(1.0, 2.0, 3.0)).norm(), 1e-12);
  EXPECT_NEAR(north.yaw_rad, 0.0, 1e-12);
  EXPECT_NEAR(north.pitch_rad, 0.0, 1e-12);
  EXPECT_NEAR(north.roll_rad, 0.0, 1e-12);
  // Facing east (ENU yaw 0) is NED yaw +90°: compass headings grow clockwise, ENU yaws anticlockwise.
  EXPECT_NEAR(rosPoseToNed(0.0, {}, Eigen::Quaterniond::Identity(), false).yaw_rad, kPi / 2, 1e-12);
  EXPECT_NEAR(rosPoseToNed(0.0, {}, about(Eigen::Vector3d::UnitZ(), kPi / 6), false).yaw_rad, kPi / 3, 1e-12);
}

TEST(formatsRosFrames, EnuPitchAndRollKeepTheirMeaning) {
  // A turn about FLU's y (left) by −0.2 rad lifts the nose: NED pitch +0.2 raises the bow.
  const NavSample nose_up = rosPoseToNed(0.0, {}, about(Eigen::Vector3d::UnitY(), -0.2), false);
  EXPECT_NEAR(nose_up.pitch_rad, 0.2, 1e-12);
  EXPECT_NEAR(nose_up.roll_rad, 0.0, 1e-12);
  // A turn about FLU's x by +0.3 rad lifts the left side: NED roll +0.3 lowers starboard.
  const NavSample rolled = rosPoseToNed(0.0, {}, about(Eigen::Vector3d::UnitX(), 0.3), false);
  EXPECT_NEAR(rolled.roll_rad, 0.3, 1e-12);
  EXPECT_NEAR(rolled.pitch_rad, 0.0, 1e-12);
}

TEST(formatsRosFrames, NedPosesAreTakenAsTheyAreAndRoundTrip) {
  NavSample fix;
  fix.time_s = 1.0;
  fix.position_ned_m = {4.0, -1.0, 2.5};
  fix.roll_rad = 0.1;
  fix.pitch_rad = -0.25;
  fix.yaw_rad = 2.0;
  const NavSample ned = rosPoseToNed(1.0, fix.position_ned_m, Eigen::Quaterniond(bodyToNed(fix).linear()), true);
  Eigen::Vector3d enu;
  Eigen::Quaterniond flu_to_enu;
  nedToRosEnu(fix, enu, flu_to_enu);
  const NavSample back = rosPoseToNed(1.0, enu, flu_to_enu, false);
  for (const NavSample& read : {ned, back}) {
    EXPECT_LT((read.position_ned_m - fix.position_ned_m).norm(), 1e-12);
    EXPECT_NEAR(read.roll_rad, fix.roll_rad, 1e-12);
    EXPECT_NEAR(read.pitch_rad, fix.pitch_rad, 1e-12);
    EXPECT_NEAR(read.yaw_rad, fix.yaw_rad, 1e-12);
  }
  EXPECT_TRUE(namesNedFrame("odom_NED"));
  EXPECT_FALSE(namesNedFrame("odom"));
}

TEST(formatsRosFrames, AQuaternionThatIsNoRotationIsAnError) {
  EXPECT_THROW(rosPoseToNed(0.0, {}, Eigen::Quaterniond(0, 0, 0, 0), false), Error);
  EXPECT_THROW(rosPoseToNed(0.0, {}, Eigen::Quaterniond(2, 0, 0, 0), true), Error);
}

}  // namespace
}  // namespace sonarmap::detail
