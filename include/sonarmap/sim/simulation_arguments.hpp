#pragma once
/// @file simulation_arguments.hpp
/// A simulated MSIS run as a user asks for it (`sonarmap simulate tank --sonar micron --turns 8`,
/// or the Python module's `simulate("tank", sonar="micron", turns=8)`): a head preset, degrees and
/// metres per second, and their checked conversion into MsisSimulationOptions. Shared by the
/// command-line tool and the Python module so both simulate the same run from the same arguments.

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap {

/// The options of a simulated run in user units; each field's name is the command-line flag's.
struct SimulationArguments {
  std::string sonar = "micron";    ///< a head preset (sonarPresetNames); built-in scenes are built for its range
  double sector_deg = 360.0;       ///< width of the scanned sector, degrees, in (0, 360]; 360: continuous turns
  double sector_center_deg = 0.0;  ///< bearing of the sector's centre, degrees clockwise from the sonar's ahead (beam.hpp)
  std::uint64_t seed = 1;          ///< seed of the speckle and noise
  std::size_t turns = 28;          ///< full turns of the head (passes across a sector), ≥ 1; ignored with a mission
  /// Vehicle speed over ground, metres per second: along the heading without a mission; along the
  /// mission's path with one, where 0 means defaultMissionSpeed_mps(the mission, the head's range)
  /// (missions.hpp).
  double speed_mps = 0.0;
  double heading_deg = 0.0;        ///< vehicle heading, degrees clockwise from north (NED yaw); unused with a mission
  /// Vehicle depth without a mission, metres below the NED origin (the water surface in the 3D
  /// scenes); NaN: the scene's nominal depth (builtinSceneDepth_m: 0 but for the 3D scenes). Unused
  /// with a mission.
  double depth_m = std::numeric_limits<double>::quiet_NaN();
  double nav_rate_hz = 10.0;       ///< navigation fixes per second, ≥ 0; 0: no navigation track
  /// A named mission (missionNames(), missions.hpp) flown in its scene; empty: the constant-velocity
  /// line of speed_mps and heading_deg from the origin.
  std::string mission;
  std::size_t laps = 1;  ///< times the mission is flown, ≥ 1 (1 without a mission)
  /// The sonar's mounting on the vehicle as `--mounting` takes it (mounting.hpp: X, Y, Z metres,
  /// ROLL, PITCH, YAW degrees, sonar frame FRD like the body); empty: the mission's default
  /// (MissionPlan::mounting: the tilted loop's pitch −25), without a mission upright and aligned.
  std::vector<double> mounting;
  // Dead-reckoning errors (dead_reckoning.hpp), in user units; all 0: a perfect navigation.
  double dvl_noise_mps = 0.0;             ///< σ of the DVL's velocity noise per component and fix, m/s, ≥ 0
  double dvl_scale_error = 0.0;           ///< fractional DVL scale error (0.02: reads 2 % fast), > −1
  double heading_bias_deg = 0.0;          ///< constant heading bias, degrees
  double gyro_walk_deg_per_sqrt_s = 0.0;  ///< heading random walk, degrees per √second, ≥ 0
};

/// The simulation options of the arguments: the preset's head and echo model, the sector, the
/// trajectory, the dead-reckoning errors (options.dead_reckoning, degrees turned into radians,
/// seeded with args.seed; its stream differs from the sonar's, dead_reckoning.hpp).
/// Trajectory: without a mission, a constant-velocity line at args.depth_m (NaN: the nominal depth
/// of the built-in scene `scene`, 0 for any other name) from above the NED origin along the heading,
/// for args.turns turns. With a mission, its waypoints (missionPlan for the head's range at
/// speed_mps or the default mission speed, args.laps laps) and as many turns as the head needs to
/// keep scanning until the vehicle has come to the mission's end: turns = ceil((duration + one
/// beam period) / the time of one turn (or sector pass)); args.turns and args.heading_deg are then
/// ignored. The sonar mounted as simulationMounting(args) says (options.sonar_to_body).
/// @throws ValueError naming the option (as its command-line flag) for a value out of range, an
///         unknown preset or mission (listing the names), a negative speed with a mission, or laps
///         other than 1 without one, a depth that is not finite, or a mounting that is not six
///         finite numbers.
MsisSimulationOptions toSimulationOptions(const SimulationArguments& args, const std::string& scene = {});

/// The sonar's mounting the arguments simulate, as `sonarmap map --mounting` takes it (X, Y, Z
/// metres, ROLL, PITCH, YAW degrees): args.mounting when given, else the mission's
/// (MissionPlan::mounting), else all 0. toSimulationOptions builds sonar_to_body from exactly these
/// numbers (sonarToBodyOfMounting), so a map made with them uses the identical pose.
/// @throws ValueError for a mounting that is not six finite numbers, or an unknown mission.
std::array<double, 6> simulationMounting(const SimulationArguments& args);

/// Checks that `scene` is the built-in scene args.mission is drawn for (MissionPlan::scene);
/// nothing to check without a mission.
/// @throws ValueError naming the mission and the scene it needs, for another scene (a scene file
///         included), or an unknown mission.
void checkMissionScene(const SimulationArguments& args, const std::string& scene);

/// `options` (toSimulationOptions of a mission) flown in the built-in scene `mission` is drawn for
/// (MissionPlan::scene), built for options.head's range scale and vertical beam width.
/// @throws ValueError for an unknown mission, or options that simulateMsis refuses.
MsisSimulation simulateInMissionScene(const std::string& mission, const MsisSimulationOptions& options);

/// builtinSceneNames() followed by builtinScene3dNames(): every name sceneOf builds.
std::vector<std::string> allBuiltinSceneNames();

/// True when `name` is one of builtinSceneNames() or builtinScene3dNames().
bool isBuiltinSceneName(const std::string& name);

/// The scene called `scene`: a built-in scene built for `head`'s range scale and vertical beam
/// width (a built-in name wins over a file of the same name: write ./tank for the file), else the
/// scene file of that path (scene_file.hpp).
/// @throws ValueError when `scene` is neither a built-in name nor an existing file (listing the
///         names); FileError as readScene for a bad scene file.
Scene sceneOf(const std::string& scene, const MsisHeadOptions& head);

}  // namespace sonarmap
