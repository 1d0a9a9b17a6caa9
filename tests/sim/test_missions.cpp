// The named missions (sim/missions.hpp) and `sonarmap simulate --mission`'s arguments.
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/mounting.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/missions.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {
namespace {

/// Whether `primitive` crosses the sonar's plane z = 0 (planes: only vertical ones).
bool crossesZ0(const Primitive& primitive) {
  if (const auto* plane = std::get_if<Plane>(&primitive)) return std::abs(plane->normal.z()) < 1e-9;
  if (const auto* box = std::get_if<Box>(&primitive)) {
    return std::abs(box->center_m.z()) <= 0.5 * box->size_m.z();
  }
  const auto& cylinder = std::get<Cylinder>(primitive);
  return cylinder.z_min_m <= 0.0 && cylinder.z_max_m >= 0.0;
}

/// Smallest distance from the path (sampled every 1 cm · s) to a primitive that crosses z = 0, in
/// the map frame (NWU: map y = −east).
double clearance_m(const MissionPlan& plan, const Scene& scene) {
  double nearest_m = INFINITY;
  const std::vector<NavSample>& points = plan.waypoints;
  for (std::size_t k = 1; k < points.size(); ++k) {
    const Eigen::Vector3d a = points[k - 1].position_ned_m, b = points[k].position_ned_m;
    const int steps = 1 + static_cast<int>((b - a).norm() / 0.01);
    for (int i = 0; i <= steps; ++i) {
      const Eigen::Vector3d ned = a + (b - a) * (static_cast<double>(i) / steps);
      const Eigen::Vector3d map(ned.x(), -ned.y(), -ned.z());
      for (const Primitive& primitive : scene.primitives) {
        if (crossesZ0(primitive)) nearest_m = std::min(nearest_m, distanceToSurface(primitive, map));
      }
    }
  }
  return nearest_m;
}

TEST(simMissions, NamesLengthsAndDurations) {
  EXPECT_EQ(missionNames(), (std::vector<std::string>{"harbour-loop", "harbour-lawnmower", "harbour-featureless",
                                                       "hull-loop", "lawnmower-3d", "tilted-loop"}));
  struct Expected {
    const char* name;
    const char* scene;
    double length_s;  // in units of s = R / 5 m
    double turns_rad;  // turning in place at 0.5 rad/s
  };
  const double quarter = 0.5 * std::numbers::pi;
  for (const Expected& e : {Expected{"harbour-loop", "harbour", 34.0, 3 * quarter},
                            Expected{"harbour-lawnmower", "harbour", 49.0, 4 * quarter},
                            Expected{"harbour-featureless", "harbour", 40.0, 0.0},
                            Expected{"hull-loop", "hull", 31.0, 3 * quarter}}) {
    for (const double range_m : {5.0, 30.0}) {
      const double s = range_m / 5.0, speed_mps = defaultMissionSpeed_mps(e.name, range_m);
      const MissionPlan plan = missionPlan(e.name, range_m, speed_mps);
      EXPECT_EQ(plan.mounting, (std::array<double, 6>{})) << e.name;  // upright and aligned
      EXPECT_EQ(plan.name, e.name);
      EXPECT_EQ(plan.scene, e.scene);
      EXPECT_NEAR(plan.length_m, e.length_s * s, 1e-9) << e.name;
      EXPECT_NEAR(plan.duration_s, e.length_s * s / speed_mps + e.turns_rad / 0.5, 1e-9) << e.name;
      EXPECT_EQ(plan.waypoints.front().time_s, 0.0);
      EXPECT_EQ(plan.waypoints.back().time_s, plan.duration_s);
      for (const NavSample& point : plan.waypoints) EXPECT_EQ(point.position_ned_m.z(), 0.0);  // planar
    }
  }
  EXPECT_DOUBLE_EQ(defaultMissionSpeed_mps("harbour-loop", 5.0), 0.25);  // Micron
  EXPECT_DOUBLE_EQ(defaultMissionSpeed_mps("harbour-loop", 30.0), 0.5);  // SeaKing-30
  EXPECT_DOUBLE_EQ(defaultMissionSpeed_mps("hull-loop", 50.0), 0.5);
  EXPECT_NEAR(missionPlan("harbour-loop", 30.0, 1.5).length_m, 204.0, 1e-9);
}

// The 3D missions over quay3d, sized by the head's range: the tilted loop (4 s × 3 s at 3 s depth,
// the sonar pitched 25° down) and the lawnmower (three 4 s legs 1.5 s apart at 3 s, back at 3.5 s).
TEST(simMissions, The3dMissionsFlyAtDepthOverQuay3dWithTheirMounting) {
  for (const double range_m : {5.0, 50.0}) {
    const double s = range_m / 5.0;
    EXPECT_DOUBLE_EQ(defaultMissionSpeed_mps("tilted-loop", range_m), 0.2 * s);
    const MissionPlan loop = missionPlan("tilted-loop", range_m, 0.2 * s, 2);
    EXPECT_EQ(loop.scene, "quay3d");
    EXPECT_EQ(loop.mounting, (std::array<double, 6>{0.0, 0.0, 0.0, 0.0, -25.0, 0.0}));
    EXPECT_NEAR(loop.length_m, 2 * 14.0 * s, 1e-9);  // two laps at the same depth
    for (const NavSample& point : loop.waypoints) EXPECT_NEAR(point.position_ned_m.z(), 3.0 * s, 1e-12);
    const MissionPlan mower = missionPlan("lawnmower-3d", range_m, 0.2 * s);
    EXPECT_EQ(mower.scene, "quay3d");
    EXPECT_EQ(mower.mounting, (std::array<double, 6>{}));
    EXPECT_NEAR(mower.length_m, (2 * (3 * 4.0 + 2 * 1.5) + 0.5) * s, 1e-9);
    EXPECT_NEAR(mower.waypoints.front().position_ned_m.z(), 3.0 * s, 1e-12);
    EXPECT_NEAR(mower.waypoints.back().position_ned_m.z(), 3.5 * s, 1e-12);
  }
  // The mounting given overrides the mission's; the options are built from those numbers.
  SimulationArguments args;
  args.mission = "tilted-loop";
  EXPECT_EQ(simulationMounting(args), (std::array<double, 6>{0.0, 0.0, 0.0, 0.0, -25.0, 0.0}));
  args.mounting = {0.3, 0.0, 0.2, 0.0, -45.0, 30.0};
  EXPECT_EQ(simulationMounting(args), (std::array<double, 6>{0.3, 0.0, 0.2, 0.0, -45.0, 30.0}));
  EXPECT_TRUE(toSimulationOptions(args).sonar_to_body.isApprox(sonarToBodyOfMounting(args.mounting), 0.0));
  args.mounting = {0.0, 0.0, 0.0};
  EXPECT_THROW(toSimulationOptions(args), ValueError);
  EXPECT_THROW(defaultMissionSpeed_mps("lake-loop", 5.0), ValueError);
}

TEST(simMissions, StartsAndLoopsCloseWhereTheyBegin) {
  const MissionPlan loop = missionPlan("harbour-loop", 5.0, 0.25, 3);
  EXPECT_NEAR(loop.length_m, 3 * 34.0, 1e-9);
  EXPECT_TRUE(loop.waypoints.front().position_ned_m.isApprox(Eigen::Vector3d(0.0, -8.0, 0.0)));
  EXPECT_NEAR(loop.waypoints.front().yaw_rad, 0.5 * std::numbers::pi, 1e-12);  // heading east
  // Its corners in order: east along north 0, then south, west, north (clockwise from above).
  EXPECT_TRUE(loop.waypoints[1].position_ned_m.isApprox(Eigen::Vector3d(0.0, 8.0, 0.0)));
  EXPECT_NEAR((loop.waypoints.back().position_ned_m - loop.waypoints.front().position_ned_m).norm(), 0.0, 1e-9);
  const MissionPlan hull = missionPlan("hull-loop", 5.0, 0.25, 2);
  EXPECT_TRUE(hull.waypoints.front().position_ned_m.isApprox(Eigen::Vector3d(-4.5, 0.0, 0.0)));
  EXPECT_NEAR((hull.waypoints.back().position_ned_m - hull.waypoints.front().position_ned_m).norm(), 0.0, 1e-9);
  const MissionPlan mower = missionPlan("harbour-lawnmower", 5.0, 0.25);
  EXPECT_TRUE(mower.waypoints.front().position_ned_m.isApprox(Eigen::Vector3d(0.0, -8.0, 0.0)));
  EXPECT_TRUE(mower.waypoints.back().position_ned_m.isApprox(Eigen::Vector3d(-1.0, 8.0, 0.0)));
  const MissionPlan line = missionPlan("harbour-featureless", 10.0, 0.5, 2);  // s = 2; there and back
  EXPECT_NEAR(line.waypoints.front().position_ned_m.norm(), 0.0, 1e-12);
  EXPECT_NEAR(line.length_m, 2 * 80.0, 1e-9);
  EXPECT_NEAR(line.waypoints.back().position_ned_m.norm(), 0.0, 1e-9);
  // waypointTrajectory takes them (times strictly increasing).
  EXPECT_NO_THROW(waypointTrajectory(loop.waypoints));
}

TEST(simMissions, KeepClearOfWhatCrossesTheSonarPlane) {
  for (const std::string& name : missionNames()) {
    if (missionPlan(name, 5.0, 1.0).scene == "quay3d") continue;  // no plane: it flies at depth, tilted
    for (const char* preset : {"micron", "seaking-30"}) {
      const MsisHeadOptions head = sonarPreset(preset).head;
      const double s = head.range_m / 5.0;
      const MissionPlan plan = missionPlan(name, head.range_m, defaultMissionSpeed_mps(name, head.range_m), 1);
      const Scene scene = builtinScene(plan.scene, head.range_m, head.vertical_beam_width_rad);
      EXPECT_GT(clearance_m(plan, scene), 0.5 * s) << name << " " << preset;
    }
  }
}

TEST(simMissions, BadArgumentsAreNamed) {
  EXPECT_THROW(missionPlan("lake-loop", 5.0, 0.25), ValueError);
  EXPECT_THROW(missionPlan("harbour-loop", 0.0, 0.25), ValueError);
  EXPECT_THROW(missionPlan("harbour-loop", 5.0, -1.0), ValueError);
  EXPECT_THROW(missionPlan("harbour-loop", 5.0, 0.25, 0), ValueError);
  EXPECT_THROW(defaultMissionSpeed_mps("harbour-loop", NAN), ValueError);
}

TEST(simMissions, SimulationArgumentsFlyTheMission) {
  SimulationArguments args;
  args.mission = "harbour-loop";
  args.laps = 2;
  args.dvl_scale_error = 0.02;
  args.heading_bias_deg = 1.0;
  args.gyro_walk_deg_per_sqrt_s = 0.1;
  args.dvl_noise_mps = 0.01;
  args.seed = 5;
  const MsisSimulationOptions options = toSimulationOptions(args);
  const MissionPlan plan = missionPlan("harbour-loop", 5.0, 0.25, 2);
  const double turn_s = 200 * 0.043;
  EXPECT_EQ(options.turns, static_cast<std::size_t>(std::ceil((plan.duration_s + 0.043) / turn_s)));
  EXPECT_GE(static_cast<double>(options.turns * 200 - 1) * 0.043, plan.duration_s);  // scans to the end
  const NavSample end = options.trajectory(plan.duration_s);
  EXPECT_NEAR((end.position_ned_m - plan.waypoints.front().position_ned_m).norm(), 0.0, 1e-9);
  EXPECT_NEAR(options.trajectory(plan.waypoints[1].time_s).position_ned_m.y(), 8.0, 1e-9);
  EXPECT_DOUBLE_EQ(options.dead_reckoning.dvl_scale_error, 0.02);
  EXPECT_NEAR(options.dead_reckoning.heading_bias_rad, std::numbers::pi / 180.0, 1e-15);
  EXPECT_NEAR(options.dead_reckoning.gyro_walk_rad_per_sqrt_s, 0.1 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_DOUBLE_EQ(options.dead_reckoning.dvl_noise_mps, 0.01);
  EXPECT_EQ(options.dead_reckoning.seed, 5U);
  args.speed_mps = 0.5;  // an explicit speed
  EXPECT_NEAR(toSimulationOptions(args).trajectory(plan.waypoints[1].time_s / 2.0).position_ned_m.y(), 8.0, 1e-9);

  EXPECT_NO_THROW(checkMissionScene(args, "harbour"));
  EXPECT_THROW(checkMissionScene(args, "hull"), ValueError);
  EXPECT_NO_THROW(checkMissionScene(SimulationArguments{}, "hull"));
  SimulationArguments bad = args;
  bad.mission = "lake";
  EXPECT_THROW(toSimulationOptions(bad), ValueError);
  bad = {};
  bad.laps = 2;  // --laps without --mission
  EXPECT_THROW(toSimulationOptions(bad), ValueError);
  bad = args;
  bad.speed_mps = -1.0;
  EXPECT_THROW(toSimulationOptions(bad), ValueError);
  bad = args;
  bad.dvl_noise_mps = -0.1;
  EXPECT_THROW(toSimulationOptions(bad), ValueError);
  bad = args;
  bad.dvl_scale_error = -1.0;
  EXPECT_THROW(toSimulationOptions(bad), ValueError);
  bad = args;
  bad.gyro_walk_deg_per_sqrt_s = -1.0;
  EXPECT_THROW(toSimulationOptions(bad), ValueError);
}

}  // namespace
}  // namespace sonarmap
