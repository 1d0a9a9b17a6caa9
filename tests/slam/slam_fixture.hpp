#pragma once
// Simulated missions for the slam tests: a head flying a named mission (sim/missions.hpp) in its
// built-in scene, with its true navigation and a dead reckoning that drifts (sim/dead_reckoning.hpp).

#include <string>

#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"

namespace sonarmap::testing {

/// `mission` flown by `sonar`, dead reckoning with a DVL scale error of `scale_error`, a heading
/// bias of `heading_bias_deg` and a gyro walk of `gyro_walk_deg_per_sqrt_s`.
inline MsisSimulation missionRun(const std::string& mission, const std::string& sonar = "micron",
                                 double scale_error = 0.03, double heading_bias_deg = 2.0,
                                 double gyro_walk_deg_per_sqrt_s = 0.02, std::uint64_t seed = 1) {
  SimulationArguments args;
  args.sonar = sonar;
  args.mission = mission;
  args.seed = seed;
  args.dvl_scale_error = scale_error;
  args.heading_bias_deg = heading_bias_deg;
  args.gyro_walk_deg_per_sqrt_s = gyro_walk_deg_per_sqrt_s;
  return simulateInMissionScene(mission, toSimulationOptions(args));
}

}  // namespace sonarmap::testing
