/// @file simulated_mission.cpp
/// The 3D accuracy missions (see simulated_mission.hpp).

#include "sonarmap/eval/simulated_mission.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {
namespace {

constexpr double kTiltDown_deg = 25.0;
constexpr std::size_t kTruthPoses = 24;

/// The waypoints of `name` at scale s (metres per Micron metre), and the sonar's tilt down.
std::vector<NavSample> missionWaypoints(const std::string& name, double s, double& tilt_deg) {
  const double speed_mps = 0.2 * s;
  if (name == "lawnmower") {
    LawnmowerPattern pattern;
    pattern.legs = 3;
    pattern.leg_length_m = 4.0 * s;
    pattern.leg_spacing_m = 1.5 * s;
    pattern.depths_m = {3.0 * s, 3.5 * s};
    pattern.speed_mps = speed_mps;
    tilt_deg = 0.0;
    return lawnmowerWaypoints(pattern);
  }
  if (name == "tilted-loop") {
    LoopPattern pattern;
    pattern.length_m = 4.0 * s;
    pattern.width_m = 3.0 * s;
    pattern.depths_m = {3.0 * s};
    pattern.speed_mps = speed_mps;
    tilt_deg = kTiltDown_deg;
    return loopWaypoints(pattern);
  }
  std::string known;
  for (const std::string& candidate : simulatedMissionNames()) known += (known.empty() ? "" : ", ") + candidate;
  throw ValueError("unknown mission '" + name + "', expected one of: " + known);
}

}  // namespace

std::vector<std::string> simulatedMissionNames() { return {"lawnmower", "tilted-loop"}; }

double MissionAccuracy::f1() const {
  const double sum = truth.precision + truth.recall;
  return sum > 0.0 ? 2.0 * truth.precision * truth.recall / sum : 0.0;
}

MissionRun simulateMission(const SimulatedMission& mission) {
  const SonarPreset preset = sonarPreset(mission.preset);
  MissionRun run;
  MsisSimulationOptions& options = run.options;
  options.head = preset.head;
  options.echo = preset.echo;
  options.seed = mission.seed;
  const double s = preset.head.range_m / kBuiltinSceneReach_m;
  double tilt_deg = 0.0;
  const std::vector<NavSample> waypoints = missionWaypoints(mission.mission, s, tilt_deg);
  options.trajectory = waypointTrajectory(waypoints);
  // Tilted down: upright and aligned (the identity), pitched down (negative pitch, FRD).
  run.mounting = {0.0, 0.0, 0.0, 0.0, -tilt_deg, 0.0};
  options.sonar_to_body = sonarToBodyOfMounting(std::vector<double>(run.mounting.begin(), run.mounting.end()));
  const double turn_s = options.head.beam_period_s * static_cast<double>(options.head.beamsPerTurn());
  options.turns = static_cast<std::size_t>(std::ceil(waypoints.back().time_s / turn_s));
  const Scene scene = builtinScene(mission.scene, preset.head.range_m, preset.head.vertical_beam_width_rad);
  run.simulation = simulateMsis(scene, options);
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
