/// @file heard_surface.cpp
/// The surface a mission's beams could hear, as a map (see heard_surface.hpp).

#include "sonarmap/eval/heard_surface.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sim/echo_levels.hpp"

namespace sonarmap {
namespace {

/// Ray angles spanning `span_rad` centred on 0, at most `step_rad` apart, each in the middle of its cell.
std::vector<double> rayAngles(double span_rad, double step_rad) {
  const int count = std::max(1, static_cast<int>(std::ceil(span_rad / step_rad)));
  std::vector<double> angles(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) angles[static_cast<std::size_t>(i)] = -0.5 * span_rad + (i + 0.5) * span_rad / count;
  return angles;
}

}  // namespace

void HeardSurfaceOptions::validate() const {
  if (!(std::isfinite(resolution_m) && resolution_m > 0.0)) {
    throw ValueError("heard surface: resolution_m must be a finite number > 0, got " + std::to_string(resolution_m));
  }
  if (std::isnan(min_level_db) || min_level_db == std::numeric_limits<double>::infinity()) {
    throw ValueError("heard surface: min_level_db must be a number below +infinity");
  }
}

OcTree16 heardSurfaceMap(const MissionRun& run, const HeardSurfaceOptions& options, HeardSurfaceStats* stats) {
  options.validate();
  const MsisSimulationOptions& simulation = run.options;
  const MsisHeadOptions& head = simulation.head;
  const Scene& scene = run.simulation.scene;
  const EchoLevels levels(scene, head, simulation.echo);
  const SceneRayCaster caster(scene);
  // Rays at most a voxel apart at the head's range.
  const double step_rad = options.resolution_m / head.range_m;
  const std::vector<double> across = rayAngles(simulation.echo.horizontal.extent * head.horizontal_beam_width_rad, step_rad);
  const std::vector<double> up = rayAngles(simulation.echo.vertical.extent * head.vertical_beam_width_rad, step_rad);
  OcTree16 map(options.resolution_m);
  std::size_t marked_voxels = 0;
  HeardSurfaceStats counts;
  std::vector<std::vector<double>> levels_db;
  const double bin_m = head.binLength_m();
  for (const Beam& beam : run.simulation.log.beams) {
    NavSample fix = simulation.trajectory(beam.time_s);
    fix.time_s = beam.time_s;
    const Eigen::Isometry3d sonar_to_map = sonarToMap(fix, simulation.sonar_to_body);
    levels.levels(sonar_to_map, beam.bearing_rad, levels_db);
    ++counts.beams;
    for (const double horizontal_rad : across) {
      const double azimuth_rad = beam.bearing_rad + horizontal_rad;
      for (const double elevation_rad : up) {
        const Eigen::Vector3d direction =
            sonar_to_map.linear() * Eigen::Vector3d(std::cos(elevation_rad) * std::cos(azimuth_rad),
                                                    std::cos(elevation_rad) * std::sin(azimuth_rad), std::sin(elevation_rad));
        ++counts.rays;
        const std::optional<SceneHit> hit = caster.firstHit(sonar_to_map.translation(), direction, head.range_m);
        if (!hit) continue;
        ++counts.surface_hits;
        const auto bin = static_cast<std::size_t>(hit->surface.range_m / bin_m);
        const std::vector<double>& level = levels_db[hit->primitive];
        if (bin >= level.size() || !(level[bin] >= options.min_level_db)) continue;
        ++counts.heard_hits;
        const std::optional<Key16> key = map.coder().keyOf(sonar_to_map.translation() + hit->surface.range_m * direction);
        if (key && !map.search(*key)) {  // one hit per voxel
          map.integrate(*key, true);
          ++marked_voxels;
        }
      }
    }
  }
  if (stats) *stats = counts;
  if (marked_voxels == 0) {
    throw ValueError("heard surface: no surface point is heard " + std::to_string(options.min_level_db) +
                     " dB over the floor");
  }
  return map;
}

}  // namespace sonarmap
