/// @file simulated_mission.cpp
/// The 3D accuracy missions (see simulated_mission.hpp).

#include "sonarmap/eval/simulated_mission.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/missions.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kTruthPoses = 24;

}  // namespace

std::vector<std::string> simulatedMissionNames() {
  std::vector<std::string> names;
  for (const std::string& name : missionNames()) {
    if (missionPlan(name, kBuiltinSceneReach_m, 1.0).scene == "quay3d") names.push_back(name);
  }
  return names;
}

double MissionAccuracy::f1() const {
  const double sum = truth.precision + truth.recall;
  return sum > 0.0 ? 2.0 * truth.precision * truth.recall / sum : 0.0;
}

MissionRun simulateMission(const SimulatedMission& mission) {
  if (mission.mission.empty()) throw ValueError("a simulated mission needs a mission's name");
  SimulationArguments args;  // `sonarmap simulate SCENE --sonar PRESET --mission MISSION --seed SEED`
  args.sonar = mission.preset;
  args.mission = mission.mission;
  args.seed = mission.seed;
  checkMissionScene(args, mission.scene);
  MissionRun run;
  run.options = toSimulationOptions(args, mission.scene);
  run.mounting = simulationMounting(args);
  run.simulation = simulateInMissionScene(mission.mission, run.options);
  return run;
}

GroundTruthOptions missionTruthOptions(const MissionRun& run, double tolerance_m) {
  GroundTruthOptions truth;
  truth.tolerance_m = tolerance_m;
  truth.sensor_positions_m.clear();
  const NavTrack& fixes = run.simulation.nav;
  const std::size_t stride = std::max<std::size_t>(1, fixes.size() / kTruthPoses);
  for (std::size_t i = 0; i < fixes.size(); i += stride) {
    const Eigen::Isometry3d sonar_to_map = sonarToMap(fixes[i], run.options.sonar_to_body);
    truth.sensor_positions_m.push_back(sonar_to_map.translation());
    truth.sensor_orientations.push_back(sonar_to_map.linear());
  }
  truth.vertical_aperture_rad = run.options.head.vertical_beam_width_rad;
  // The truth the sonar could reach, whatever the map: every sensor position grown by the range.
  const double range_m = run.options.head.range_m;
  truth.max_range_m = range_m;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& position : truth.sensor_positions_m) box.extend(position);
  truth.surface_box_m = Eigen::AlignedBox3d(box.min().array() - range_m, box.max().array() + range_m);
  return truth;
}

MissionAccuracy evaluateMission(const SimulatedMission& mission, const MapperOptions& options) {
  return evaluateMission(mission, simulateMission(mission), options);
}

MissionAccuracy evaluateMission(const SimulatedMission& mission, const MissionRun& run, const MapperOptions& options,
                                const MissionMapVisitor& visit) {
  MissionAccuracy result;
  result.mission = mission;
  MapperOptions mapping = options;
  mapping.beam_width_rad = run.options.head.horizontal_beam_width_rad;
  mapping.vertical_aperture_rad = run.options.head.vertical_beam_width_rad;
  const auto start = std::chrono::steady_clock::now();
  const SonarMapper mapper = mapSonarLog(run.simulation.log, run.simulation.nav, run.options.sonar_to_body, mapping);
  result.seconds_mapping = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.resolution_m = mapper.map().resolution_m();
  result.beams = mapper.stats().beams_used;
  result.obstacles = mapper.stats().obstacles;
  result.voxel_updates = mapper.stats().free_updates + mapper.stats().occupied_updates;
  result.truth = evaluateAgainstScene(mapper.map(), run.simulation.scene, missionTruthOptions(run));
  if (visit) visit(mapper.map(), result);
  return result;
}

}  // namespace sonarmap
