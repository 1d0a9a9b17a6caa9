// The vehicle's limits where the navigation measures no position (OdometryNoise::max_speed_mps,
// max_turn_rate_radps; the CLI's --max-speed and --max-turn-rate): a match that needs the vehicle to
// move or turn faster is refused and counted, one within them (or within the defaults) is kept, and
// a measured heading's turn is never refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/slam/localizer.hpp"
#include "sonarmap/slam/point_scans.hpp"

namespace sonarmap {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// The walls of a 12 m × 8 m tank (north 0…12 m, east 0…8 m) every 5 cm, as seen from `pose`
/// (NED plane): every point in the body frame at `time_s`, as scan `scan`.
void appendTankScan(std::vector<BodyPoint>& points, std::size_t scan, double time_s, const Pose2& pose) {
  const Eigen::Vector2d corners[] = {{0.0, 0.0}, {12.0, 0.0}, {12.0, 8.0}, {0.0, 8.0}, {0.0, 0.0}};
  const Pose2 ned_to_body = pose.inverse();
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector2d from = corners[side], to = corners[side + 1];
    const int steps = static_cast<int>(std::round((to - from).norm() / 0.05));
    for (int i = 0; i < steps; ++i) {
      points.push_back({scan, time_s, ned_to_body * (from + (to - from) * (static_cast<double>(i) / steps))});
    }
  }
}

/// Two scans of the tank, from `first` at 0 s and from `second` at `duration_s`.
std::vector<BodyPoint> twoScans(const Pose2& first, const Pose2& second, double duration_s) {
  std::vector<BodyPoint> points;
  appendTankScan(points, 0, 0.0, first);
  appendTankScan(points, 1, duration_s, second);
  return points;
}

/// A navigation that measures the heading only (north and east 0, as a BlueROV2's flight log
/// without a DVL): `yaw_rad` at 0 s and `end_yaw_rad` at `duration_s`.
NavTrack headingOnly(double yaw_rad, double end_yaw_rad, double duration_s) {
  NavTrack track(2);
  track[0].yaw_rad = yaw_rad;
  track[1].time_s = duration_s;
  track[1].yaw_rad = end_yaw_rad;
  return track;
}

SlamOptions limited(double max_speed_mps, double max_turn_rate_deg_s, const std::string& navigation_class = "dvl-ahrs") {
  SlamOptions options;
  options.forming.odometry = odometryNoiseOf(navigation_class);
  options.forming.odometry.max_speed_mps = max_speed_mps;
  options.forming.odometry.max_turn_rate_radps = max_turn_rate_deg_s * kDeg;
  return options;
}

TEST(slamMotionLimits, AMoveWithinTheTopSpeedIsFoundAndOneBeyondItIsRefused) {
  // 1.12 m in 10 s: 0.11 m/s.
  const std::vector<BodyPoint> points = twoScans({4.0, 3.0, 0.0}, {5.0, 3.5, 0.0}, 10.0);
  const SlamResult within = localizePointScans(points, NavTrack{}, {}, SlamOptions{});
  EXPECT_EQ(within.report.matches_accepted, 1U);
  EXPECT_EQ(within.report.matches_beyond_limits, 0U);
  EXPECT_NEAR(within.trajectory.back().position_ned_m.x(), 1.0, 0.02);
  EXPECT_NEAR(within.trajectory.back().position_ned_m.y(), 0.5, 0.02);

  const SlamResult beyond = localizePointScans(points, NavTrack{}, {}, limited(0.05, 30.0));
  EXPECT_EQ(beyond.report.matches_accepted, 0U);
  EXPECT_EQ(beyond.report.matches_beyond_limits, 1U);
  EXPECT_EQ(beyond.report.matches_refused, 1U);
  // Where the scans cannot be placed within the limits, the vehicle stays put.
  EXPECT_LT(beyond.trajectory.back().position_ned_m.head<2>().norm(), 0.01);
}

TEST(slamMotionLimits, WithoutNavigationATurnBeyondTheTopTurnRateIsRefused) {
  // 10° in 4 s: 2.5°/s.
  const std::vector<BodyPoint> points = twoScans({4.0, 3.0, 0.0}, {4.0, 3.0, 10.0 * kDeg}, 4.0);
  const SlamResult within = localizePointScans(points, NavTrack{}, {}, SlamOptions{});
  EXPECT_EQ(within.report.matches_accepted, 1U);
  EXPECT_NEAR(within.trajectory.back().yaw_rad, 10.0 * kDeg, 0.2 * kDeg);

  const SlamResult beyond = localizePointScans(points, NavTrack{}, {}, limited(2.0, 1.0));
  EXPECT_EQ(beyond.report.matches_beyond_limits, 1U);
  EXPECT_LT(std::abs(beyond.trajectory.back().yaw_rad), 0.2 * kDeg);
}

TEST(slamMotionLimits, WithTheHeadingAloneTheSpeedIsLimitedAndTheMeasuredTurnIsNot) {
  const Pose2 first{4.0, 3.0, 0.0};
  const Pose2 second{5.0, 3.5, 10.0 * kDeg};
  const std::vector<BodyPoint> points = twoScans(first, second, 4.0);
  const NavTrack heading = headingOnly(0.0, 10.0 * kDeg, 4.0);
  // 1.12 m in 4 s (0.28 m/s) while the AHRS turns 2.5°/s, beyond a 1°/s turn limit.
  const SlamResult kept = localizePointScans(points, heading, {}, limited(2.0, 1.0, "ahrs"));
  EXPECT_TRUE(kept.report.heading_only);
  EXPECT_EQ(kept.report.matches_accepted, 1U);
  EXPECT_EQ(kept.report.matches_beyond_limits, 0U);
  EXPECT_NEAR(kept.trajectory.back().position_ned_m.x(), 1.0, 0.02);

  const SlamResult refused = localizePointScans(points, heading, {}, limited(0.2, 30.0, "ahrs"));
  EXPECT_EQ(refused.report.matches_beyond_limits, 1U);
  EXPECT_LT(refused.trajectory.back().position_ned_m.head<2>().norm(), 0.01);
}

TEST(slamMotionLimits, ALoopClosureBeyondTheTopSpeedIsRefused) {
  std::vector<BodyPoint> points;
  for (std::size_t scan = 0; scan < 3; ++scan) appendTankScan(points, scan, 10.0 * static_cast<double>(scan), {4.0, 3.0, 0.0});
  Localizer localizer(limited(0.1, 30.0), false);
  for (SonarScan& scan : formPointScans(points, NavTrack{})) localizer.addScan(std::move(scan));
  ASSERT_EQ(localizer.scans().size(), 3U);
  // 3 m in 20 s (0.15 m/s), stated very confidently.
  const Eigen::Matrix3d information = Eigen::Vector3d(1e4, 1e4, 1e6).asDiagonal();
  EXPECT_FALSE(localizer.proposeLoopClosure(0, 2, {3.0, 0.0, 0.0}, information));
  EXPECT_NE(localizer.report().loop_closures.back().reason.find("faster than the vehicle's limits"), std::string::npos);
  EXPECT_TRUE(localizer.proposeLoopClosure(0, 2, {0.01, 0.0, 0.0}, information));
}

/// The largest speed (m/s) and turn rate (rad/s) any two consecutive rows of `track` imply.
std::pair<double, double> fastestStep(const NavTrack& track) {
  double speed_mps = 0.0, turn_radps = 0.0;
  for (std::size_t i = 1; i < track.size(); ++i) {
    const double dt_s = track[i].time_s - track[i - 1].time_s;
    speed_mps = std::max(speed_mps, (track[i].position_ned_m - track[i - 1].position_ned_m).head<2>().norm() / dt_s);
    turn_radps = std::max(turn_radps, std::abs(wrapAngle_rad(track[i].yaw_rad - track[i - 1].yaw_rad)) / dt_s);
  }
  return {speed_mps, turn_radps};
}

TEST(slamMotionLimits, WithoutNavigationTheWrittenTrackStaysWithinTheLimitsBetweenScans) {
  // Three turns of 7.8 s, 8 s apart, each seen from 0.5 m further north and turned 5° more: within
  // the limits (0.06 m/s, 0.6°/s). A scan's points are spread over its turn, so the last row of one
  // scan and the first of the next are 0.2 s apart: a pose held over each scan would jump 0.5 m
  // (2.5 m/s) and 5° (25°/s) there.
  std::vector<BodyPoint> points;
  for (std::size_t k = 0; k < 3; ++k) {
    std::vector<BodyPoint> scan;
    const double reference_s = 4.0 + 8.0 * static_cast<double>(k);
    appendTankScan(scan, k, reference_s, {4.0 + 0.5 * static_cast<double>(k), 3.0, 5.0 * kDeg * static_cast<double>(k)});
    for (std::size_t i = 0; i < scan.size(); ++i) {
      scan[i].time_s = reference_s - 3.9 + 7.8 * static_cast<double>(i) / static_cast<double>(scan.size() - 1);
    }
    points.insert(points.end(), scan.begin(), scan.end());
  }
  const SlamResult result = localizePointScans(points, NavTrack{}, {}, SlamOptions{});
  ASSERT_EQ(result.report.matches_accepted, 2U);
  ASSERT_GT(result.trajectory.size(), 3U);
  EXPECT_NEAR(result.trajectory.back().position_ned_m.x(), 1.0, 0.05);
  const auto [speed_mps, turn_radps] = fastestStep(result.trajectory);
  const OdometryNoise limits;
  EXPECT_LE(speed_mps, limits.max_speed_mps);
  EXPECT_LE(turn_radps, limits.max_turn_rate_radps);
  // Spread evenly between the scans' reference times: 0.5 m and 5° in 8 s.
  EXPECT_NEAR(speed_mps, 0.5 / 8.0, 0.01);
  EXPECT_NEAR(turn_radps, 5.0 * kDeg / 8.0, 0.2 * kDeg);
}

TEST(slamMotionLimits, LimitsMustBePositive) {
  for (const double bad : {0.0, -1.0, std::nan("")}) {
    OdometryNoise noise;
    noise.max_speed_mps = bad;
    EXPECT_THROW(noise.validate(), ValueError);
    noise = OdometryNoise{};
    noise.max_turn_rate_radps = bad;
    EXPECT_THROW(noise.validate(), ValueError);
  }
}

}  // namespace
}  // namespace sonarmap
