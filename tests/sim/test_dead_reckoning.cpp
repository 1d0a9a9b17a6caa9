// Dead reckoning (sim/dead_reckoning.hpp): the believed track of a vehicle whose DVL and compass
// err, and the simulator's run with it.
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/dead_reckoning.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// A straight line north from the origin: `length_m` at 1 m/s, fixes every `dt_s`.
NavTrack straightNorth(double length_m, double dt_s = 0.1) {
  NavTrack track;
  const auto fixes = static_cast<std::size_t>(std::lround(length_m / dt_s));
  for (std::size_t k = 0; k <= fixes; ++k) {
    NavSample fix;
    fix.time_s = static_cast<double>(k) * dt_s;
    fix.position_ned_m = Eigen::Vector3d(fix.time_s, 0.0, 0.5 + 0.01 * fix.time_s);
    fix.roll_rad = 0.01;
    fix.pitch_rad = -0.02;
    track.push_back(fix);
  }
  return track;
}

bool sameBytes(const NavTrack& a, const NavTrack& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double x[7] = {a[k].time_s, a[k].position_ned_m.x(), a[k].position_ned_m.y(), a[k].position_ned_m.z(),
                         a[k].roll_rad, a[k].pitch_rad, a[k].yaw_rad};
    const double y[7] = {b[k].time_s, b[k].position_ned_m.x(), b[k].position_ned_m.y(), b[k].position_ned_m.z(),
                         b[k].roll_rad, b[k].pitch_rad, b[k].yaw_rad};
    if (std::memcmp(x, y, sizeof x) != 0) return false;
  }
  return true;
}

TEST(simDeadReckoning, NoErrorReproducesTheTruthExactly) {
  const NavTrack truth = straightNorth(20.0);
  DeadReckoningOptions options;
  EXPECT_FALSE(options.any());
  EXPECT_TRUE(sameBytes(deadReckon(truth, options), truth));
  EXPECT_TRUE(deadReckon({}, DeadReckoningOptions{0.1, 0.02, 0.01, 0.001, 3}).empty());
}

TEST(simDeadReckoning, ScaleErrorDriftsAlongTrack) {
  const NavTrack truth = straightNorth(100.0);
  DeadReckoningOptions options;
  options.dvl_scale_error = 0.02;
  const NavTrack believed = deadReckon(truth, options);
  ASSERT_EQ(believed.size(), truth.size());
  EXPECT_TRUE(sameBytes({believed.front()}, {truth.front()}));
  const Eigen::Vector3d error = believed.back().position_ned_m - truth.back().position_ned_m;
  EXPECT_NEAR(error.x(), 2.0, 0.02);  // 2 % of 100 m, ±1 %
  EXPECT_NEAR(error.y(), 0.0, 1e-9);
  EXPECT_EQ(error.z(), 0.0);  // depth, roll, pitch, times: the truth's
  for (std::size_t k = 0; k < truth.size(); ++k) {
    EXPECT_EQ(believed[k].time_s, truth[k].time_s);
    EXPECT_EQ(believed[k].roll_rad, truth[k].roll_rad);
    EXPECT_EQ(believed[k].pitch_rad, truth[k].pitch_rad);
    EXPECT_EQ(believed[k].yaw_rad, truth[k].yaw_rad);
  }
}

TEST(simDeadReckoning, HeadingBiasDriftsAcrossTrack) {
  const NavTrack truth = straightNorth(100.0);
  DeadReckoningOptions options;
  options.heading_bias_rad = 1.0 * kDegree;
  const NavTrack believed = deadReckon(truth, options);
  const Eigen::Vector3d error = believed.back().position_ned_m - truth.back().position_ned_m;
  EXPECT_NEAR(error.y(), 100.0 * std::sin(kDegree), 1e-6);  // 1.745 m to starboard (east) heading north
  EXPECT_NEAR(error.y(), 1.75, 0.01);
  EXPECT_NEAR(error.x(), 100.0 * (std::cos(kDegree) - 1.0), 1e-6);
  EXPECT_NEAR(believed.back().yaw_rad, kDegree, 1e-15);
  EXPECT_NEAR(believed.front().yaw_rad, kDegree, 1e-15);  // the bias is the compass's: from the start
  EXPECT_EQ(believed.front().position_ned_m, truth.front().position_ned_m);
}

TEST(simDeadReckoning, NoiseIsSeededAndGrowsAsARandomWalk) {
  const NavTrack truth = straightNorth(100.0);  // 1000 intervals of 0.1 s
  DeadReckoningOptions options;
  options.dvl_noise_mps = 0.05;
  options.seed = 4;
  EXPECT_TRUE(sameBytes(deadReckon(truth, options), deadReckon(truth, options)));
  DeadReckoningOptions other = options;
  other.seed = 5;
  EXPECT_FALSE(sameBytes(deadReckon(truth, options), deadReckon(truth, other)));
  // σ · dt · √N per axis = 0.05 · 0.1 · √1000 = 0.158 m; the spread over 200 seeds within ±25 %.
  const double expected_m = 0.05 * 0.1 * std::sqrt(1000.0);
  double sum_sq_north = 0.0, sum_sq_east = 0.0;
  const int seeds = 200;
  for (int seed = 1; seed <= seeds; ++seed) {
    options.seed = static_cast<std::uint64_t>(seed);
    const Eigen::Vector3d error = deadReckon(truth, options).back().position_ned_m - truth.back().position_ned_m;
    sum_sq_north += error.x() * error.x();
    sum_sq_east += error.y() * error.y();
  }
  EXPECT_NEAR(std::sqrt(sum_sq_north / seeds), expected_m, 0.25 * expected_m);
  EXPECT_NEAR(std::sqrt(sum_sq_east / seeds), expected_m, 0.25 * expected_m);
}

TEST(simDeadReckoning, GyroWalkTurnsTheHeadingAsItsRate) {
  const NavTrack truth = straightNorth(100.0);  // 100 s
  DeadReckoningOptions options;
  options.gyro_walk_rad_per_sqrt_s = 0.01;
  double sum_sq_rad = 0.0;
  const int seeds = 200;
  for (int seed = 1; seed <= seeds; ++seed) {
    options.seed = static_cast<std::uint64_t>(seed);
    sum_sq_rad += std::pow(deadReckon(truth, options).back().yaw_rad, 2);
  }
  EXPECT_NEAR(std::sqrt(sum_sq_rad / seeds), 0.01 * std::sqrt(100.0), 0.025);  // q · √t = 0.1 rad
}

TEST(simDeadReckoning, InvalidOptionsNameTheField) {
  const NavTrack truth = straightNorth(1.0);
  auto message = [&](const DeadReckoningOptions& options) {
    try {
      deadReckon(truth, options);
    } catch (const ValueError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(DeadReckoningOptions{-0.1, 0, 0, 0, 1}).find("dvl_noise_mps"), std::string::npos);
  EXPECT_NE(message(DeadReckoningOptions{0, -1.0, 0, 0, 1}).find("dvl_scale_error"), std::string::npos);
  EXPECT_NE(message(DeadReckoningOptions{0, 0, NAN, 0, 1}).find("heading_bias_rad"), std::string::npos);
  EXPECT_NE(message(DeadReckoningOptions{0, 0, 0, -1.0, 1}).find("gyro_walk_rad_per_sqrt_s"), std::string::npos);
}

TEST(simDeadReckoning, SimulatorKeepsTheBeamsAndTheTrueNav) {
  MsisSimulationOptions options;
  options.turns = 1;
  options.seed = 3;
  NavSample start;
  start.yaw_rad = 0.5 * std::numbers::pi;
  options.trajectory = constantVelocityTrajectory(start, Eigen::Vector3d(0.0, 0.25, 0.0));
  const Scene scene = builtinScene("harbour");
  const MsisSimulation plain = simulateMsis(scene, options);
  EXPECT_TRUE(plain.dead_reckoning.empty());
  options.dead_reckoning = DeadReckoningOptions{0.02, 0.02, 1.0 * kDegree, 0.001, 3};
  const MsisSimulation drifting = simulateMsis(scene, options);
  ASSERT_EQ(drifting.log.beams.size(), plain.log.beams.size());
  for (std::size_t i = 0; i < plain.log.beams.size(); ++i) {
    EXPECT_EQ(drifting.log.beams[i].intensities, plain.log.beams[i].intensities) << i;
  }
  EXPECT_TRUE(sameBytes(drifting.nav, plain.nav));  // nav stays the truth
  ASSERT_EQ(drifting.dead_reckoning.size(), plain.nav.size());
  EXPECT_TRUE(sameBytes(drifting.dead_reckoning, deadReckon(plain.nav, options.dead_reckoning)));
  EXPECT_GT((drifting.dead_reckoning.back().position_ned_m - plain.nav.back().position_ned_m).norm(), 0.01);
  options.nav_rate_hz = 0.0;
  EXPECT_TRUE(simulateMsis(scene, options).dead_reckoning.empty());
}

}  // namespace
}  // namespace sonarmap
