// Trajectories of the simulated vehicle: waypoint interpolation (positions, yaw along the shortest
// arc across ±π, clamping, errors) and the missions built from waypoints (lawnmower legs and
// depths, closed rectangle and circle loops).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

NavSample fix(double time_s, const Eigen::Vector3d& position_ned_m, double yaw_rad = 0.0, double roll_rad = 0.0,
              double pitch_rad = 0.0) {
  NavSample sample;
  sample.time_s = time_s;
  sample.position_ned_m = position_ned_m;
  sample.roll_rad = roll_rad;
  sample.pitch_rad = pitch_rad;
  sample.yaw_rad = yaw_rad;
  return sample;
}

/// `a − b` wrapped into [−π, π).
double angleDifference(double a, double b) {
  const double d = a - b;
  return d - 2.0 * kPi * std::floor((d + kPi) / (2.0 * kPi));
}

TEST(simTrajectory, WaypointsAreInterpolatedLinearlyInTime) {
  const Trajectory trajectory = waypointTrajectory({fix(1.0, {0.0, 0.0, 0.0}, 0.0, 0.1, -0.2),
                                                    fix(3.0, {2.0, -4.0, 1.0}, 0.5, 0.3, 0.2),
                                                    fix(4.0, {2.0, -4.0, 3.0}, 0.5)});
  const NavSample mid = trajectory(2.0);
  EXPECT_EQ(mid.time_s, 2.0);
  EXPECT_TRUE(mid.position_ned_m.isApprox(Eigen::Vector3d(1.0, -2.0, 0.5), 1e-12));
  EXPECT_NEAR(mid.roll_rad, 0.2, 1e-12);
  EXPECT_NEAR(mid.pitch_rad, 0.0, 1e-12);
  EXPECT_NEAR(mid.yaw_rad, 0.25, 1e-12);
  const NavSample late = trajectory(3.75);
  EXPECT_TRUE(late.position_ned_m.isApprox(Eigen::Vector3d(2.0, -4.0, 2.5), 1e-12));
  EXPECT_NEAR(late.roll_rad, 0.3 * 0.25, 1e-12);
  // Every waypoint exactly at its own time.
  const NavSample at = trajectory(3.0);
  EXPECT_EQ(at.position_ned_m, Eigen::Vector3d(2.0, -4.0, 1.0));
  EXPECT_EQ(at.yaw_rad, 0.5);
  EXPECT_EQ(at.roll_rad, 0.3);
}

TEST(simTrajectory, YawTakesTheShortestArcAcrossPlusMinusPi) {
  const Trajectory trajectory =
      waypointTrajectory({fix(0.0, Eigen::Vector3d::Zero(), 170.0 * kDegree), fix(2.0, Eigen::Vector3d::Zero(), -170.0 * kDegree),
                          fix(4.0, Eigen::Vector3d::Zero(), 170.0 * kDegree)});
  // 170° → −170° passes through 180°, not 0°.
  EXPECT_NEAR(std::abs(angleDifference(trajectory(1.0).yaw_rad, kPi)), 0.0, 1e-12);
  EXPECT_NEAR(angleDifference(trajectory(0.5).yaw_rad, 175.0 * kDegree), 0.0, 1e-12);
  EXPECT_NEAR(angleDifference(trajectory(1.5).yaw_rad, -175.0 * kDegree), 0.0, 1e-12);
  // And back.
  EXPECT_NEAR(angleDifference(trajectory(2.5).yaw_rad, -175.0 * kDegree), 0.0, 1e-12);
  // Within a half-turn the plain difference: −90° → 45° goes through 0°.
  const Trajectory plain =
      waypointTrajectory({fix(0.0, Eigen::Vector3d::Zero(), -kPi / 2), fix(3.0, Eigen::Vector3d::Zero(), kPi / 4)});
  EXPECT_NEAR(plain(2.0).yaw_rad, 0.0, 1e-12);
}

TEST(simTrajectory, OutsideTheWaypointsTheEndsHold) {
  const Trajectory trajectory =
      waypointTrajectory({fix(1.0, {1.0, 2.0, 3.0}, 0.1), fix(2.0, {5.0, 6.0, 7.0}, 0.2, 0.05)});
  for (const double t : {-10.0, 0.0, 1.0, std::numeric_limits<double>::quiet_NaN()}) {
    const NavSample early = trajectory(t);
    EXPECT_EQ(early.position_ned_m, Eigen::Vector3d(1.0, 2.0, 3.0)) << t;
    EXPECT_EQ(early.yaw_rad, 0.1) << t;
  }
  for (const double t : {2.0, 2.5, 1e9}) {
    const NavSample late = trajectory(t);
    EXPECT_EQ(late.time_s, t);
    EXPECT_EQ(late.position_ned_m, Eigen::Vector3d(5.0, 6.0, 7.0)) << t;
    EXPECT_EQ(late.roll_rad, 0.05) << t;
  }
  // A single waypoint: a static vehicle.
  const Trajectory still = waypointTrajectory({fix(0.0, {1.0, 1.0, 1.0}, 1.0)});
  EXPECT_EQ(still(5.0).position_ned_m, Eigen::Vector3d(1.0, 1.0, 1.0));
}

TEST(simTrajectory, BadWaypointsThrow) {
  EXPECT_THROW(waypointTrajectory({}), ValueError);
  EXPECT_THROW(waypointTrajectory({fix(0.0, {0, 0, 0}), fix(0.0, {1, 0, 0})}), ValueError);  // same time
  EXPECT_THROW(waypointTrajectory({fix(1.0, {0, 0, 0}), fix(0.5, {1, 0, 0})}), ValueError);  // backwards
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(waypointTrajectory({fix(0.0, {0, 0, 0}), fix(1.0, {nan, 0, 0})}), ValueError);
  EXPECT_THROW(waypointTrajectory({fix(0.0, {0, 0, 0}, HUGE_VAL)}), ValueError);
  EXPECT_THROW(waypointTrajectory({fix(nan, {0, 0, 0})}), ValueError);
  EXPECT_THROW(waypointTrajectory({fix(0.0, {0, 0, 0}, 0.0, 0.0, nan)}), ValueError);
}

/// Checks what every mission must be: strictly increasing times from 0, and between consecutive
/// waypoints the vehicle either turns in place at `turn_rate_radps` or moves straight at
/// `speed_mps` (yaw along the horizontal travel when `yaw_along_travel`).
void expectConstantSpeedPath(const std::vector<NavSample>& points, double speed_mps, double turn_rate_radps,
                             bool yaw_along_travel) {
  ASSERT_FALSE(points.empty());
  EXPECT_EQ(points.front().time_s, 0.0);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const NavSample& a = points[i - 1];
    const NavSample& b = points[i];
    SCOPED_TRACE("waypoint " + std::to_string(i));
    ASSERT_GT(b.time_s, a.time_s);
    EXPECT_EQ(b.roll_rad, 0.0);
    EXPECT_EQ(b.pitch_rad, 0.0);
    const Eigen::Vector3d step = b.position_ned_m - a.position_ned_m;
    if (step.norm() < 1e-12) {  // a turn in place
      EXPECT_NEAR(b.time_s - a.time_s, std::abs(angleDifference(b.yaw_rad, a.yaw_rad)) / turn_rate_radps, 1e-9);
      continue;
    }
    EXPECT_NEAR(b.time_s - a.time_s, step.norm() / speed_mps, 1e-9);
    if (!yaw_along_travel) continue;
    if (step.head<2>().norm() > 1e-9) {
      const double travel_rad = std::atan2(step.y(), step.x());
      EXPECT_NEAR(angleDifference(a.yaw_rad, travel_rad), 0.0, 1e-9);
      EXPECT_NEAR(angleDifference(b.yaw_rad, travel_rad), 0.0, 1e-9);
    } else {
      EXPECT_EQ(a.yaw_rad, b.yaw_rad);  // vertical transit keeps the yaw
    }
  }
}

TEST(simTrajectory, LawnmowerFliesItsLegsAtEachDepth) {
  LawnmowerPattern pattern;
  pattern.center_ne_m = {1.0, -2.0};
  pattern.heading_rad = 0.0;  // legs along north
  pattern.legs = 3;
  pattern.leg_length_m = 6.0;
  pattern.leg_spacing_m = 2.0;  // to the east
  pattern.depths_m = {0.5, 1.5};
  pattern.speed_mps = 0.5;
  pattern.turn_rate_radps = 0.25;
  const std::vector<NavSample> points = lawnmowerWaypoints(pattern);
  expectConstantSpeedPath(points, 0.5, 0.25, true);
  // The distinct places visited, in order: legs at east = −4, −2, 0 from north −2 to 4 and back.
  std::vector<Eigen::Vector3d> places;
  for (const NavSample& point : points) {
    if (places.empty() || (places.back() - point.position_ned_m).norm() > 1e-12) places.push_back(point.position_ned_m);
  }
  const std::vector<Eigen::Vector3d> expected{
      {-2.0, -4.0, 0.5}, {4.0, -4.0, 0.5}, {4.0, -2.0, 0.5}, {-2.0, -2.0, 0.5}, {-2.0, 0.0, 0.5}, {4.0, 0.0, 0.5},
      // descend, then the same legs backwards
      {4.0, 0.0, 1.5}, {-2.0, 0.0, 1.5}, {-2.0, -2.0, 1.5}, {4.0, -2.0, 1.5}, {4.0, -4.0, 1.5}, {-2.0, -4.0, 1.5}};
  ASSERT_EQ(places.size(), expected.size());
  for (std::size_t i = 0; i < places.size(); ++i) {
    EXPECT_TRUE(places[i].isApprox(expected[i], 1e-12) || (places[i] - expected[i]).norm() < 1e-12)
        << i << ": " << places[i].transpose();
  }
  // Legs north (yaw 0), south (π), crossings east (π/2).
  EXPECT_NEAR(points.front().yaw_rad, 0.0, 1e-12);
  EXPECT_NEAR(waypointTrajectory(points)(1.0).yaw_rad, 0.0, 1e-12);  // on the first leg
  // Total time: 2 × (3 legs × 6 m + 2 crossings × 2 m) + 1 m descent, at 0.5 m/s, plus the turns:
  // 4 of 90° per depth, one of 180° at the bottom.
  const double turns_rad = 2 * 4 * (kPi / 2) + kPi;
  EXPECT_NEAR(points.back().time_s, (2 * (18.0 + 4.0) + 1.0) / 0.5 + turns_rad / 0.25, 1e-9);
  // The pattern is centred on center_ne_m.
  Eigen::Vector2d lo = points.front().position_ned_m.head<2>(), hi = lo;
  for (const NavSample& point : points) {
    lo = lo.cwiseMin(point.position_ned_m.head<2>());
    hi = hi.cwiseMax(point.position_ned_m.head<2>());
  }
  EXPECT_TRUE((0.5 * (lo + hi)).isApprox(pattern.center_ne_m, 1e-12));
}

TEST(simTrajectory, LawnmowerTurnsItsLegsWithTheHeadingAndSpacingSign) {
  LawnmowerPattern pattern;
  pattern.heading_rad = kPi / 2;  // first leg east
  pattern.legs = 2;
  pattern.leg_length_m = 4.0;
  pattern.leg_spacing_m = -1.0;  // to port of east: north
  pattern.depths_m = {2.0};
  const std::vector<NavSample> points = lawnmowerWaypoints(pattern);
  expectConstantSpeedPath(points, pattern.speed_mps, pattern.turn_rate_radps, true);
  EXPECT_TRUE(points.front().position_ned_m.isApprox(Eigen::Vector3d(-0.5, -2.0, 2.0), 1e-12));
  EXPECT_NEAR(points.front().yaw_rad, kPi / 2, 1e-12);
  EXPECT_TRUE(points.back().position_ned_m.isApprox(Eigen::Vector3d(0.5, -2.0, 2.0), 1e-12));
  EXPECT_NEAR(angleDifference(points.back().yaw_rad, -kPi / 2), 0.0, 1e-12);  // second leg west
}

TEST(simTrajectory, RectangleLoopClosesAtEachDepth) {
  LoopPattern pattern;
  pattern.shape = LoopShape::kRectangle;
  pattern.center_ne_m = {0.0, 0.0};
  pattern.length_m = 6.0;
  pattern.width_m = 4.0;
  pattern.depths_m = {0.0, 1.0};
  const std::vector<NavSample> points = loopWaypoints(pattern);
  expectConstantSpeedPath(points, pattern.speed_mps, pattern.turn_rate_radps, true);
  // Clockwise from the south-west corner: north, east, south, west.
  const Eigen::Vector3d corner(-3.0, -2.0, 0.0);
  EXPECT_TRUE(points.front().position_ned_m.isApprox(corner, 1e-12));
  for (const NavSample& point : points) {
    EXPECT_NEAR(std::abs(point.position_ned_m.x()), 3.0, 1e-12);  // always on the rectangle
    if (std::abs(std::abs(point.position_ned_m.y()) - 2.0) > 1e-12) ADD_FAILURE() << point.position_ned_m.transpose();
  }
  const Trajectory trajectory = waypointTrajectory(points);
  // The first side runs north along east = −2 (the centre to starboard), the second east.
  EXPECT_TRUE(trajectory(4.0).position_ned_m.isApprox(Eigen::Vector3d(-2.0, -2.0, 0.0), 1e-12));
  // Closed: at each depth the loop ends where it started.
  bool closed_at_first_depth = false;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (points[i].position_ned_m.isApprox(corner, 1e-12) && points[i - 1].position_ned_m.y() > 0.0) {
      closed_at_first_depth = true;
    }
  }
  EXPECT_TRUE(closed_at_first_depth);
  EXPECT_TRUE(points.back().position_ned_m.isApprox(Eigen::Vector3d(-3.0, -2.0, 1.0), 1e-12));
  // Perimeter twice, 1 m of descent, 3 corner turns per loop and one back to the heading between.
  EXPECT_NEAR(points.back().time_s, (2 * 20.0 + 1.0) / 0.25 + 7 * (kPi / 2) / 0.5, 1e-9);
}

TEST(simTrajectory, CircleLoopIsClosedWithYawAlongTheTangent) {
  for (const bool clockwise : {true, false}) {
    SCOPED_TRACE(clockwise ? "clockwise" : "counter-clockwise");
    LoopPattern pattern;
    pattern.shape = LoopShape::kCircle;
    pattern.center_ne_m = {1.0, 1.0};
    pattern.radius_m = 2.0;
    pattern.heading_rad = 0.0;
    pattern.clockwise = clockwise;
    pattern.circle_vertices = 36;
    pattern.depths_m = {0.2, 0.8};
    const std::vector<NavSample> points = loopWaypoints(pattern);
    expectConstantSpeedPath(points, pattern.speed_mps, pattern.turn_rate_radps, false);
    ASSERT_EQ(points.size(), 2U * 36U + 2U);  // start, 36 vertices, descent, 36 vertices
    // Clockwise heading north: the centre lies to the east (starboard).
    const Eigen::Vector3d start(1.0, clockwise ? -1.0 : 3.0, 0.2);
    EXPECT_TRUE(points.front().position_ned_m.isApprox(start, 1e-12));
    EXPECT_EQ(points[36].position_ned_m, start);  // closed exactly
    EXPECT_EQ(points.back().position_ned_m, Eigen::Vector3d(start.x(), start.y(), 0.8));
    for (const NavSample& point : points) {
      const Eigen::Vector2d radial = point.position_ned_m.head<2>() - pattern.center_ne_m;
      EXPECT_NEAR(radial.norm(), 2.0, 1e-12);
      // Yaw along the tangent of the direction of travel: 90° clockwise (or counter-) from radial.
      const double tangent_rad = std::atan2(radial.y(), radial.x()) + (clockwise ? kPi / 2 : -kPi / 2);
      EXPECT_NEAR(angleDifference(point.yaw_rad, tangent_rad), 0.0, 1e-9);
    }
    // The first step goes the right way round: clockwise heading north from the west side turns east.
    EXPECT_GT(points[1].position_ned_m.x(), 1.0);
    EXPECT_EQ(points[1].position_ned_m.y() > start.y(), clockwise);
  }
}

TEST(simTrajectory, BadPatternsThrow) {
  LawnmowerPattern lawnmower;
  lawnmower.legs = 0;
  EXPECT_THROW(lawnmowerWaypoints(lawnmower), ValueError);
  lawnmower = {};
  lawnmower.leg_spacing_m = 0.0;
  EXPECT_THROW(lawnmowerWaypoints(lawnmower), ValueError);
  lawnmower = {};
  lawnmower.depths_m.clear();
  EXPECT_THROW(lawnmowerWaypoints(lawnmower), ValueError);
  lawnmower = {};
  lawnmower.speed_mps = 0.0;
  EXPECT_THROW(lawnmowerWaypoints(lawnmower), ValueError);
  lawnmower = {};
  lawnmower.leg_length_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(lawnmowerWaypoints(lawnmower), ValueError);
  EXPECT_NO_THROW(lawnmowerWaypoints({}));
  LoopPattern loop;
  loop.width_m = -1.0;
  EXPECT_THROW(loopWaypoints(loop), ValueError);
  loop = {};
  loop.shape = LoopShape::kCircle;
  loop.circle_vertices = 2;
  EXPECT_THROW(loopWaypoints(loop), ValueError);
  loop = {};
  loop.turn_rate_radps = 0.0;
  EXPECT_THROW(loopWaypoints(loop), ValueError);
  loop = {};
  loop.depths_m = {0.0, HUGE_VAL};
  EXPECT_THROW(loopWaypoints(loop), ValueError);
  EXPECT_NO_THROW(loopWaypoints({}));
}

/// Range of the strongest bin of `beam` in [from_m, to_m).
double peakRange(const Beam& beam, double from_m, double to_m) {
  int best = -1;
  double best_m = -1.0;
  for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
    const double range_m = (static_cast<double>(i) + 0.5) * beam.bin_length_m;
    if (range_m >= from_m && range_m < to_m && beam.intensities[i] > best) {
      best = beam.intensities[i];
      best_m = range_m;
    }
  }
  return best_m;
}

TEST(simTrajectory, WaypointMissionsDriveTheSimulatorOverTheQuay) {
  // A rectangle loop at 3 m depth (2 m above the seabed) with the sonar tilted 25° down (how an AUV maps the seabed
  // with an MSIS), its first side heading south, up the seabed's slope.
  LoopPattern loop;
  loop.center_ne_m = {0.0, 1.0};
  loop.heading_rad = kPi;
  loop.length_m = 3.0;
  loop.width_m = 2.0;
  loop.depths_m = {3.0};
  const std::vector<NavSample> points = loopWaypoints(loop);
  MsisSimulationOptions options;
  options.turns = 2;
  options.echo.speckle_looks = 0;
  options.echo.noise_level_db = -300.0;
  options.trajectory = waypointTrajectory(points);
  const double tilt_rad = 25.0 * kDegree;  // pitched down: negative about the sonar's y (starboard) axis
  options.sonar_to_body = defaultSonarToBody() * Eigen::AngleAxisd(-tilt_rad, Eigen::Vector3d::UnitY());
  const MsisSimulation run = simulateMsis(builtinScene("quay3d"), options);
  ASSERT_FALSE(run.nav.empty());
  const Trajectory expected = waypointTrajectory(points);
  for (const NavSample& fix : run.nav) {
    EXPECT_TRUE(fix.position_ned_m.isApprox(expected(fix.time_s).position_ned_m, 1e-12) ||
                (fix.position_ned_m - expected(fix.time_s).position_ned_m).norm() < 1e-12);
  }
  // The vehicle starts at the loop's corner (1.5, 2) m NED, 3 m deep: map (1.5, −2, −3),
  // heading south. The first beam (bearing 0) looks south 25° down and meets the seabed
  // z = −5 − x / 8 where −3 − t sin 25° = −5 − (1.5 − t cos 25°) / 8: t = 4.08 m.
  const Eigen::Isometry3d pose = sonarToMap(run.nav.front(), options.sonar_to_body);
  EXPECT_TRUE(pose.translation().isApprox(Eigen::Vector3d(1.5, -2.0, -3.0), 1e-12));
  const Beam& first = run.log.beams.front();
  ASSERT_NEAR(first.bearing_rad, 0.0, 1e-9);
  const Eigen::Vector3d down_south = pose.linear() * Eigen::Vector3d::UnitX();
  EXPECT_TRUE(down_south.isApprox(Eigen::Vector3d(-std::cos(tilt_rad), 0.0, -std::sin(tilt_rad)), 1e-12));
  const auto truth = firstHit(run.scene, pose.translation(), down_south, 5.0);
  ASSERT_TRUE(truth);
  EXPECT_EQ(truth->primitive, 1U);  // the seabed
  EXPECT_NEAR(truth->surface.range_m, (2.0 + 1.5 / 8.0) / (std::sin(tilt_rad) + std::cos(tilt_rad) / 8.0), 1e-9);
  // The beam is 35° tall: its lower edge, 42.5° down, meets the seabed first (2.85 m); the echo
  // peaks between that range and the axis's.
  // (the sonar frame's z is down: FRD)
  const Eigen::Vector3d lower_edge = pose.linear() * Eigen::Vector3d(std::cos(17.5 * kDegree), 0.0, std::sin(17.5 * kDegree));
  const auto nearest = firstHit(run.scene, pose.translation(), lower_edge, 5.0);
  ASSERT_TRUE(nearest);
  EXPECT_EQ(nearest->primitive, 1U);
  const double peak_m = peakRange(first, 1.0, 5.0);
  EXPECT_GE(peak_m, nearest->surface.range_m - 0.05);
  EXPECT_LE(peak_m, truth->surface.range_m);
}

}  // namespace
}  // namespace sonarmap
