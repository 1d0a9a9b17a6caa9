#include "sonarmap/sim/simulation_arguments.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/mounting.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/missions.hpp"
#include "sonarmap/sim/scene_file.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

/// "a, b, c".
std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace

std::vector<std::string> allBuiltinSceneNames() {
  std::vector<std::string> names = builtinSceneNames();
  for (const std::string& name : builtinScene3dNames()) names.push_back(name);
  return names;
}

MsisSimulationOptions toSimulationOptions(const SimulationArguments& args, const std::string& scene) {
  if (args.turns < 1) throw ValueError("--turns must be at least 1");
  if (!std::isfinite(args.speed_mps)) throw ValueError("--speed must be finite");
  if (!std::isfinite(args.heading_deg)) throw ValueError("--heading must be finite");
  if (!(std::isfinite(args.sector_deg) && args.sector_deg > 0.0 && args.sector_deg <= 360.0)) {
    throw ValueError("--sector must be in (0, 360] degrees");
  }
  if (!std::isfinite(args.sector_center_deg)) throw ValueError("--sector-center must be finite");
  const SonarPreset preset = sonarPreset(args.sonar);
  MsisSimulationOptions options;
  options.head = preset.head;
  options.echo = preset.echo;
  options.head.sector_width_rad = args.sector_deg == 360.0 ? 2.0 * std::numbers::pi : args.sector_deg * kRadPerDeg;
  options.head.sector_center_rad = args.sector_center_deg * kRadPerDeg;
  options.turns = args.turns;
  options.seed = args.seed;
  options.nav_rate_hz = args.nav_rate_hz;
  if (args.mission.empty()) {
    if (args.laps != 1) throw ValueError("--laps needs --mission");
    NavSample start;
    start.yaw_rad = args.heading_deg * kRadPerDeg;
    if (std::isinf(args.depth_m)) throw ValueError("--depth must be finite");
    const double scene_depth_m = isBuiltinSceneName(scene) ? builtinSceneDepth_m(scene, options.head.range_m) : 0.0;
    start.position_ned_m.z() = std::isnan(args.depth_m) ? scene_depth_m : args.depth_m;
    const Eigen::Vector3d velocity_ned_mps(args.speed_mps * std::cos(start.yaw_rad),
                                           args.speed_mps * std::sin(start.yaw_rad), 0.0);
    options.trajectory = constantVelocityTrajectory(start, velocity_ned_mps);
  } else {
    if (args.laps < 1) throw ValueError("--laps must be at least 1");
    if (args.speed_mps < 0.0) throw ValueError("--speed must be >= 0 with --mission (0: the mission's default speed)");
    const double range_m = options.head.range_m;
    const double speed_mps = args.speed_mps > 0.0 ? args.speed_mps : defaultMissionSpeed_mps(args.mission, range_m);
    MissionPlan plan = missionPlan(args.mission, range_m, speed_mps, args.laps);
    const double turn_s = static_cast<double>(options.head.beamsPerTurn()) * options.head.beam_period_s;
    options.turns = static_cast<std::size_t>(std::ceil((plan.duration_s + options.head.beam_period_s) / turn_s));
    options.trajectory = waypointTrajectory(std::move(plan.waypoints));
  }
  const std::array<double, 6> mounting = simulationMounting(args);
  options.sonar_to_body = sonarToBodyOfMounting(std::vector<double>(mounting.begin(), mounting.end()));
  auto finite = [](double value, const char* flag) {
    if (!std::isfinite(value)) throw ValueError(std::string(flag) + " must be finite");
  };
  finite(args.dvl_noise_mps, "--dvl-noise");
  finite(args.dvl_scale_error, "--dvl-scale-error");
  finite(args.heading_bias_deg, "--heading-bias");
  finite(args.gyro_walk_deg_per_sqrt_s, "--gyro-walk");
  if (args.dvl_noise_mps < 0.0) throw ValueError("--dvl-noise must be >= 0 m/s");
  if (!(args.dvl_scale_error > -1.0)) throw ValueError("--dvl-scale-error must be > -1");
  if (args.gyro_walk_deg_per_sqrt_s < 0.0) throw ValueError("--gyro-walk must be >= 0 deg/sqrt(s)");
  options.dead_reckoning.dvl_noise_mps = args.dvl_noise_mps;
  options.dead_reckoning.dvl_scale_error = args.dvl_scale_error;
  options.dead_reckoning.heading_bias_rad = args.heading_bias_deg * kRadPerDeg;
  options.dead_reckoning.gyro_walk_rad_per_sqrt_s = args.gyro_walk_deg_per_sqrt_s * kRadPerDeg;
  options.dead_reckoning.seed = args.seed;
  options.validate();
  return options;
}

std::array<double, 6> simulationMounting(const SimulationArguments& args) {
  if (!args.mounting.empty()) {
    sonarToBodyOfMounting(args.mounting);  // throws unless six finite numbers
    std::array<double, 6> mounting{};
    std::copy(args.mounting.begin(), args.mounting.end(), mounting.begin());
    return mounting;
  }
  if (args.mission.empty()) return {};
  return missionPlan(args.mission, kBuiltinSceneReach_m, 1.0).mounting;
}

void checkMissionScene(const SimulationArguments& args, const std::string& scene) {
  if (args.mission.empty()) return;
  const std::string needed = missionPlan(args.mission, kBuiltinSceneReach_m, 1.0).scene;
  if (scene != needed) {
    throw ValueError("--mission " + args.mission + " is drawn for the built-in scene '" + needed + "', not '" + scene +
                     "'");
  }
}

MsisSimulation simulateInMissionScene(const std::string& mission, const MsisSimulationOptions& options) {
  return simulateMsis(sceneOf(missionPlan(mission, options.head.range_m, 1.0).scene, options.head), options);
}

bool isBuiltinSceneName(const std::string& name) {
  const std::vector<std::string> names = allBuiltinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scene sceneOf(const std::string& scene, const MsisHeadOptions& head) {
  if (isBuiltinSceneName(scene)) return builtinScene(scene, head.range_m, head.vertical_beam_width_rad);
  if (!std::filesystem::exists(scene)) {
    throw ValueError("unknown scene '" + scene + "': neither a built-in scene (" + joined(allBuiltinSceneNames()) +
                     ") nor a scene file");
  }
  return readScene(scene);
}

}  // namespace sonarmap
