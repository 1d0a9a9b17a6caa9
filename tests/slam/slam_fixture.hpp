#pragma once
// Simulated missions for the slam tests: a head on a vehicle flying a loop in a built-in scene, its
// true navigation, and a dead reckoning that drifts.

#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap::testing {

/// A dead reckoning of `truth` with a constant heading bias and DVL scale error, integrated from the
/// true start (no noise: the drift is exact and known).
inline NavTrack driftingTrack(const NavTrack& truth, double scale_error, double heading_bias_rad) {
  NavTrack believed;
  believed.push_back(truth.front());
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Eigen::Vector3d step = truth[i].position_ned_m - truth[i - 1].position_ned_m;
    const double c = std::cos(heading_bias_rad), s = std::sin(heading_bias_rad);
    const Eigen::Vector3d turned(c * step.x() - s * step.y(), s * step.x() + c * step.y(), step.z());
    NavSample fix = truth[i];
    fix.position_ned_m = believed.back().position_ned_m + (1.0 + scale_error) * turned;
    fix.yaw_rad = truth[i].yaw_rad + heading_bias_rad;
    believed.push_back(fix);
  }
  return believed;
}

/// The Micron (or `preset`) flying a rectangle `length_m` × `width_m` (north × east) from the origin
/// in `scene`, clockwise, at its default speed, `laps` times.
inline MsisSimulation loopMission(const std::string& scene_name, const std::string& preset_name, double north0_m,
                                  double east0_m, double length_m, double width_m, double speed_mps,
                                  std::uint64_t seed = 1) {
  const SonarPreset preset = sonarPreset(preset_name);
  LoopPattern loop;
  loop.center_ne_m = Eigen::Vector2d(north0_m, east0_m);
  loop.heading_rad = std::numbers::pi / 2.0;
  loop.length_m = length_m;
  loop.width_m = width_m;
  loop.depths_m = {0.0};
  loop.speed_mps = speed_mps;
  const std::vector<NavSample> waypoints = loopWaypoints(loop);
  MsisSimulationOptions options;
  options.head = preset.head;
  options.echo = preset.echo;
  options.seed = seed;
  options.trajectory = waypointTrajectory(waypoints);
  const double turn_s = options.head.beam_period_s * static_cast<double>(options.head.beamsPerTurn());
  options.turns = static_cast<std::size_t>(std::ceil(waypoints.back().time_s / turn_s));
  const Scene scene = builtinScene(scene_name, preset.head.range_m, preset.head.vertical_beam_width_rad);
  return simulateMsis(scene, options);
}

}  // namespace sonarmap::testing
