// Where no position is measured the scans are the odometry (localizer.hpp): a still head is moved
// only by what the scans prove.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "sonarmap/slam/localizer.hpp"
#include "sonarmap/slam/point_scans.hpp"

namespace sonarmap {
namespace {

/// A wall as a segment in NED's plane.
struct Wall {
  Eigen::Vector2d a, b;
};

/// The range along `direction` from `origin` to the nearest wall within `reach_m`, or NaN.
double rangeTo(const std::vector<Wall>& walls, const Eigen::Vector2d& origin, const Eigen::Vector2d& direction, double reach_m) {
  double best = std::numeric_limits<double>::quiet_NaN();
  for (const Wall& wall : walls) {
    const Eigen::Vector2d edge = wall.b - wall.a;
    Eigen::Matrix2d system;
    system << direction, -edge;
    if (std::abs(system.determinant()) < 1e-12) continue;
    const Eigen::Vector2d solution = system.colPivHouseholderQr().solve(wall.a - origin);
    if (solution.x() <= 0.0 || solution.x() > reach_m || solution.y() < 0.0 || solution.y() > 1.0) continue;
    if (!(solution.x() >= best)) best = solution.x();
  }
  return best;
}

/// A heading-up MSIS turning once per scan (180 beams over 9 s, a scan every 10 s) on a vehicle
/// heading north at `speed_mps`: its points in the body frame, each range with `noise_m`.
std::vector<BodyPoint> pointScans(const std::vector<Wall>& walls, int scans, double speed_mps, double noise_m, unsigned seed) {
  constexpr double kPeriod_s = 10.0, kSweep_s = 9.0, kReach_m = 25.0;
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, noise_m);
  std::vector<BodyPoint> points;
  for (int scan = 0; scan < scans; ++scan) {
    for (int k = 0; k < 180; ++k) {
      const double time_s = kPeriod_s * scan + kSweep_s * k / 180.0;
      const double bearing_rad = 2.0 * std::numbers::pi * k / 180.0;
      const Eigen::Vector2d direction(std::cos(bearing_rad), std::sin(bearing_rad));
      const double range_m = rangeTo(walls, Eigen::Vector2d(speed_mps * time_s, 0.0), direction, kReach_m);
      if (std::isnan(range_m)) continue;
      points.push_back({static_cast<std::size_t>(scan), time_s, (range_m + noise(random)) * direction});
    }
  }
  return points;
}

/// A compass on a vehicle without a DVL: heading north, north and east 0.
NavTrack compassOnly(double duration_s) {
  NavTrack track;
  for (double time_s = 0.0; time_s <= duration_s; time_s += 0.5) {
    NavSample fix;
    fix.time_s = time_s;
    track.push_back(fix);
  }
  return track;
}

TEST(slamScanOdometry, AlongACorridorTheMotionModelCarriesThePosition) {
  // A corridor 6 m wide, closed 8 m behind the start: the end wall gives the first scans' motion,
  // then the two walls measure only across. A vehicle at 0.5 m/s covers 55 m in 11 scans; along
  // the walls the last velocity is held (a vehicle's speed does not jump), so the track reaches
  // as far.
  const std::vector<Wall> walls{{{-8.0, -3.0}, {200.0, -3.0}}, {{-8.0, 3.0}, {200.0, 3.0}}, {{-8.0, -3.0}, {-8.0, 3.0}}};
  const double speed_mps = 0.5;
  const int scans = 12;
  const std::vector<BodyPoint> points = pointScans(walls, scans, speed_mps, 0.02, 1);
  SlamOptions options;
  options.forming.odometry = odometryNoiseOf("ahrs");
  const SlamResult result = localizePointScans(points, compassOnly(10.0 * scans), PointScanOptions{}, options);
  ASSERT_EQ(result.scan_poses.size(), static_cast<std::size_t>(scans));
  const double travelled_m = speed_mps * (result.scan_times_s.back() - result.scan_times_s.front());
  EXPECT_NEAR(result.scan_poses.back().x_m - result.scan_poses.front().x_m, travelled_m, 0.1 * travelled_m);
  // Across the corridor the walls hold it.
  for (const Pose2& pose : result.scan_poses) EXPECT_NEAR(pose.y_m, 0.0, 0.3);
}

TEST(slamScanOdometry, AChannelTravelledWithACompassKeepsItsSpeed) {
  // Three piles, then a channel 12 m wide and 300 m long that the 25 m head never sees the end of
  // (a BlueROV2 at 0.3 m/s, 87 m):
  // the piles give the first scans' motion, then each scan sees the walls farther ahead than the
  // scans before it did, and two parallel walls look alike wherever they are along them. The
  // score surface is flat along the channel, so the match measures only across it and the motion
  // model holds the speed; no scan is taken for an older one.
  const std::vector<Wall> walls{{{12.0, -6.0}, {320.0, -6.0}}, {{12.0, 6.0}, {320.0, 6.0}}, {{2.0, -4.0}, {2.3, -4.0}},
                                {{5.0, 3.5}, {5.3, 3.5}},      {{8.0, -2.5}, {8.3, -2.5}}};
  const double speed_mps = 0.3;
  const int scans = 30;
  const std::vector<BodyPoint> points = pointScans(walls, scans, speed_mps, 0.05, 3);
  SlamOptions options;
  options.forming.odometry = odometryNoiseOf("ahrs");
  const SlamResult result = localizePointScans(points, compassOnly(10.0 * scans), PointScanOptions{}, options);
  ASSERT_EQ(result.scan_poses.size(), static_cast<std::size_t>(scans));
  const double travelled_m = speed_mps * (result.scan_times_s.back() - result.scan_times_s.front());
  EXPECT_NEAR(result.scan_poses.back().x_m - result.scan_poses.front().x_m, travelled_m, 0.05 * travelled_m);
  EXPECT_EQ(result.report.loopClosuresAccepted(), 0U);
  for (const Pose2& pose : result.scan_poses) EXPECT_NEAR(pose.y_m, 0.0, 0.5);
}

TEST(slamScanOdometry, AStillHeadStaysStill) {
  // A head on a tripod in a pool with two posts, no navigation, the ranges noisy: the scans never
  // prove a motion, so the track stays at the start.
  const std::vector<Wall> walls{{{-6.0, -4.0}, {7.0, -4.0}}, {{7.0, -4.0}, {7.0, 5.0}}, {{7.0, 5.0}, {-6.0, 5.0}},
                                {{-6.0, 5.0}, {-6.0, -4.0}}, {{2.0, 1.0}, {2.3, 1.0}},  {{-3.0, -2.0}, {-3.0, -1.7}}};
  const std::vector<BodyPoint> points = pointScans(walls, 20, 0.0, 0.05, 7);
  const SlamResult result = localizePointScans(points, NavTrack{}, PointScanOptions{}, SlamOptions{});
  ASSERT_EQ(result.scan_poses.size(), 20U);
  for (const NavSample& fix : result.trajectory) EXPECT_LT(fix.position_ned_m.head<2>().norm(), 0.1) << fix.time_s;
}

}  // namespace
}  // namespace sonarmap
