#pragma once
/// @file simulated_mission.hpp
/// The 3D accuracy missions of docs/accuracy.md: a simulated head (sonar_presets.hpp)
/// on a moving vehicle over a built-in 3D scene (builtin_scenes.hpp, `quay3d`), mapped with the
/// given MapperOptions and scored in 3D against the scene (ground_truth.hpp) with the head's field
/// of view.
///
/// The missions are the 3D missions of the simulator (sim/missions.hpp: `lawnmower-3d`,
/// `tilted-loop` over `quay3d`), flown once at their default speed with their default mounting,
/// exactly as `sonarmap simulate quay3d --sonar PRESET --mission MISSION --seed SEED` flies them
/// (simulation_arguments.hpp): the same log, navigation and scene.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {

/// A mission to simulate and score; see the file's comment.
struct SimulatedMission {
  std::string preset = "micron";        ///< sonarPresetNames()
  std::string scene = "quay3d";         ///< a built-in scene, built for the preset's range
  std::string mission = "tilted-loop";  ///< simulatedMissionNames()
  std::uint64_t seed = 1;
};

/// The simulator's missions over quay3d (missionNames(), sim/missions.hpp): "lawnmower-3d",
/// "tilted-loop".
std::vector<std::string> simulatedMissionNames();

/// A mission simulated: the log, navigation and scene, and how the sonar was mounted.
struct MissionRun {
  MsisSimulationOptions options;  ///< head, echo model, trajectory and mounting used
  MsisSimulation simulation;      ///< log, navigation fixes, scene
  /// The sonar's mounting as `sonarmap map --mounting` takes it (X, Y, Z metres; roll, pitch, yaw
  /// degrees; simulationMounting, simulation_arguments.hpp): options.sonar_to_body is built from
  /// these numbers, so a map made from them, by the CLI or Python, uses the identical pose.
  std::array<double, 6> mounting{};
};

/// Simulates `mission`: the vehicle flies it once, the head turning throughout.
/// @throws ValueError for an unknown preset or mission, or a scene other than the mission's.
MissionRun simulateMission(const SimulatedMission& mission);

/// The ground-truth options for scoring a map of `run`: 24 sonar poses sampled evenly along its
/// navigation (positions and orientations) and the head's vertical beam width as the field of
/// view, tolerance `tolerance_m`; the head's range as the reach and the box of those positions
/// grown by it as where surfaces are sought (ground_truth.hpp: the truth does not depend on the map).
/// Note: the vertical slab (z) of precision and free accuracy is still the map's own known extent.
GroundTruthOptions missionTruthOptions(const MissionRun& run, double tolerance_m = 0.1);

/// The scores of one mission mapped with one set of options.
struct MissionAccuracy {
  SimulatedMission mission;
  double resolution_m = 0.0;
  std::size_t beams = 0;
  std::size_t obstacles = 0;
  std::size_t voxel_updates = 0;  ///< free and occupied cell updates
  double seconds_mapping = 0.0;   ///< mapSonarLog's wall time
  GroundTruthReport truth;
  /// The harmonic mean of precision and recall (0 when both are 0).
  double f1() const;
};

/// Simulates `mission`, maps it with `options` (the head's horizontal and vertical beam widths
/// replace the options' ones, as a user states their sonar) through mapSonarLog with the
/// simulated navigation and mounting, and scores the map with missionTruthOptions().
/// @throws ValueError for an unknown preset, scene or mission, invalid options, or an empty map.
MissionAccuracy evaluateMission(const SimulatedMission& mission, const MapperOptions& options);

/// Called by evaluateMission with the map it made (map frame) and its scores, before the map is
/// dropped: to score the same map another way (e.g. against the heard surface, heard_surface.hpp).
using MissionMapVisitor = std::function<void(const OcTree16& map, const MissionAccuracy& accuracy)>;

/// As above on `run`, simulateMission(mission)'s result (one simulation serves many options);
/// `visit`, when set, is called once with the map and its scores.
/// @throws ValueError for invalid options or an empty map, and whatever `visit` throws.
MissionAccuracy evaluateMission(const SimulatedMission& mission, const MissionRun& run, const MapperOptions& options,
                                const MissionMapVisitor& visit = {});

}  // namespace sonarmap
