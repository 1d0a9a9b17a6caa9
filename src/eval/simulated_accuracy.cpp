/// @file simulated_accuracy.cpp
/// A simulated run mapped and scored (see simulated_accuracy.hpp).

#include "sonarmap/eval/simulated_accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <variant>

#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr std::size_t kMinVoxelsForOffset = 10;

/// Does the primitive have surface within [z_min, z_max]?
bool crossesSlab(const Primitive& primitive, double z_min_m, double z_max_m) {
  return std::visit(
      [&](const auto& p) -> bool {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, Plane>) {
          const Eigen::Vector3d n = p.normal.normalized();
          if (std::abs(n.z()) < 1.0 - 1e-9) return true;  // not horizontal: crosses every height
          return p.point_m.z() >= z_min_m && p.point_m.z() <= z_max_m;
        } else if constexpr (std::is_same_v<T, Box>) {
          return p.center_m.z() - 0.5 * p.size_m.z() <= z_max_m && p.center_m.z() + 0.5 * p.size_m.z() >= z_min_m;
        } else {
          return p.z_min_m <= z_max_m && p.z_max_m >= z_min_m;
        }
      },
      primitive);
}

MsisSimulationOptions simulationOptions(const SimulatedRun& run) {
  const SonarPreset preset = sonarPreset(run.preset);
  MsisSimulationOptions options;
  options.head = preset.head;
  options.echo = preset.echo;
  options.turns = run.turns;
  options.seed = run.seed;
  if (run.sector_deg < 360.0) {
    options.head.sector_width_rad = run.sector_deg * kDegree;
    options.head.sector_center_rad = 0.0;
  }
  if (run.speed_range_per_min > 0.0) {
    // Along the scenes' quay face (map y; the scenes' structures lie at x > 0), heading the way it
    // goes, the run's middle abreast of the map origin: a vehicle passes the piles and the quay
    // instead of driving through them (the quay is 8 ranges long, the fastest run covers 7.5).
    const double speed_mps = run.speed_range_per_min * preset.head.range_m / 60.0;
    const double duration_s = static_cast<double>(options.turns * options.head.beamsPerTurn()) * options.head.beam_period_s;
    NavSample start;
    start.position_ned_m = Eigen::Vector3d(0.0, 0.5 * speed_mps * duration_s, 0.0);  // map y = −east
    start.yaw_rad = -0.5 * std::numbers::pi;  // body +x to NED −y (west), map +y
    options.trajectory = constantVelocityTrajectory(start, Eigen::Vector3d(0.0, -speed_mps, 0.0));
  }
  return options;
}

}  // namespace

SimulatedAccuracy evaluateSimulatedRun(const SimulatedRun& run, const MapperOptions& options) {
  SimulatedAccuracy result;
  result.run = run;
  const MsisSimulationOptions sim = simulationOptions(run);
  const Scene scene = builtinScene(run.scene, sim.head.range_m, sim.head.vertical_beam_width_rad);
  const MsisSimulation simulation = simulateMsis(scene, sim);
  MapperOptions mapping = options;
  mapping.beam_width_rad = sim.head.horizontal_beam_width_rad;  // the head's, as the user states it
  const auto start = std::chrono::steady_clock::now();
  const bool moving = run.speed_range_per_min > 0.0;
  const SonarMapper mapper = moving ? mapSonarLog(simulation.log, simulation.nav, sim.sonar_to_body, mapping)
                                    : mapSonarLog(simulation.log, mapping);
  result.seconds_mapping = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.resolution_m = mapper.map().resolution_m();
  result.sweeps = mapper.stats().sweeps;
  result.obstacles = mapper.stats().obstacles;
  GroundTruthOptions truth;
  if (moving) {
    truth.sensor_positions_m.clear();
    const auto& fixes = simulation.nav;
    for (std::size_t i = 0; i < fixes.size(); i += std::max<std::size_t>(1, fixes.size() / 10)) {
      truth.sensor_positions_m.push_back((sonarToMap(fixes[i], sim.sonar_to_body)).translation());
    }
  }
  result.truth = evaluateAgainstScene(mapper.map(), scene, truth);
  for (const SurfaceOffset& surface : result.truth.surfaces) {
    if (!crossesSlab(scene.primitives[surface.primitive], result.truth.z_min_m, result.truth.z_max_m)) {
      result.off_plane.push_back(surface);
    } else if (surface.voxels >= kMinVoxelsForOffset) {
      result.worst_offset_m = std::max(result.worst_offset_m, std::abs(surface.median_signed_offset_m));
    }
  }
  return result;
}

}  // namespace sonarmap
