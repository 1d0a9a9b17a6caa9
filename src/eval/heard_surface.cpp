/// @file heard_surface.cpp
/// The surface a log's beams could hear, as a map, and a map scored against it (see heard_surface.hpp).

#include "sonarmap/eval/heard_surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sim/echo_levels.hpp"
#include "occupied_near.hpp"

namespace sonarmap {
namespace {

/// Ray angles spanning `span_rad` centred on 0, at most `step_rad` apart, each in the middle of its cell.
std::vector<double> rayAngles(double span_rad, double step_rad) {
  const int count = std::max(1, static_cast<int>(std::ceil(span_rad / step_rad)));
  std::vector<double> angles(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) angles[static_cast<std::size_t>(i)] = -0.5 * span_rad + (i + 0.5) * span_rad / count;
  return angles;
}

/// The occupied finest voxels of `map` whose centre z lies in [z_min_m, z_max_m].
detail::KeySet occupiedKeys(const OcTree16& map, double z_min_m, double z_max_m) {
  detail::KeySet keys;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (map.model().classify(leaf.log_odds) != Occupancy::kOccupied) return;
    leaf.forEachVoxel([&](const Key16& key) {
      const double z_m = map.coder().centerOf(key[2]);
      if (z_m >= z_min_m && z_m <= z_max_m) keys.insert(key);
    });
  });
  return keys;
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

OcTree16 heardSurfaceMap(const SonarLog& log, const NavTrack& true_nav, const Eigen::Isometry3d& sonar_to_body,
                         const Scene& scene, const MsisHeadOptions& head, const EchoModelOptions& echo,
                         const HeardSurfaceOptions& options, HeardSurfaceStats* stats,
                         const ProgressCallback& progress) {
  options.validate();
  const EchoLevels levels(scene, head, echo);
  const SceneRayCaster caster(scene);
  std::optional<NavInterpolator> nav;
  if (!true_nav.empty()) nav.emplace(true_nav);  // checks the track once
  const Eigen::Isometry3d ned_to_map = nedToMap();
  // Rays at most a voxel apart at the head's range.
  const double step_rad = options.resolution_m / head.range_m;
  const std::vector<double> across = rayAngles(echo.horizontal.extent * head.horizontal_beam_width_rad, step_rad);
  const std::vector<double> up = rayAngles(echo.vertical.extent * head.vertical_beam_width_rad, step_rad);
  OcTree16 map(options.resolution_m);
  HeardSurfaceStats counts;
  std::vector<std::vector<double>> levels_db;
  const double bin_m = head.binLength_m();
  for (std::size_t i = 0; i < log.beams.size(); ++i) {
    const Beam& beam = log.beams[i];
    if (progress) progress(i + 1, log.beams.size());
    if (!(std::abs(beam.bin_length_m - bin_m) <= 1e-6 * bin_m)) {
      char message[200];
      std::snprintf(message, sizeof message,
                    "heard surface: beam %zu has %.6g m bins, the head records %.6g m (%g m in %d bins): the log was "
                    "not recorded by this head",
                    i, beam.bin_length_m, bin_m, head.range_m, head.bins);
      throw ValueError(message);
    }
    Eigen::Isometry3d sonar_to_map = staticSonarToMap();  // static: at the map origin (navigation.hpp)
    if (nav) {
      const std::optional<Eigen::Isometry3d> body_to_ned = nav->bodyToNedAt(beam.time_s);
      if (!body_to_ned) {
        ++counts.beams_without_nav;
        continue;
      }
      sonar_to_map = ned_to_map * *body_to_ned * sonar_to_body;
    }
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
          ++counts.voxels;
        }
      }
    }
  }
  if (stats) *stats = counts;
  if (counts.voxels == 0) {
    throw ValueError("heard surface: no surface point is heard " + std::to_string(options.min_level_db) +
                     " dB over the floor");
  }
  return map;
}

OcTree16 heardSurfaceMap(const MissionRun& run, const HeardSurfaceOptions& options, HeardSurfaceStats* stats) {
  const MsisSimulationOptions& simulation = run.options;
  return heardSurfaceMap(run.simulation.log, run.simulation.nav, simulation.sonar_to_body, run.simulation.scene,
                         simulation.head, simulation.echo, options, stats);
}

HeardSurfaceScore scoreAgainstHeardSurface(const OcTree16& map, const GroundTruthReport& truth, const OcTree16& heard) {
  const double res_m = map.resolution_m();
  if (heard.resolution_m() != res_m) {
    throw ValueError("heard recall: the heard surface's voxels (" + std::to_string(heard.resolution_m()) +
                     " m) differ from the map's (" + std::to_string(res_m) + " m)");
  }
  if (!(std::isfinite(truth.tolerance_m) && truth.tolerance_m > 0.0)) {
    throw ValueError("heard recall: the tolerance must be a finite number > 0, got " +
                     std::to_string(truth.tolerance_m));
  }
  const detail::KeySet mapped = occupiedKeys(map, truth.z_min_m, truth.z_max_m);
  const detail::KeySet heard_keys =
      occupiedKeys(heard, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  if (heard_keys.empty()) throw ValueError("heard recall: the heard surface holds no occupied voxel");
  HeardSurfaceScore score;
  score.heard_voxels = heard_keys.size();
  for (const Key16& key : heard_keys) {
    score.heard_voxels_found += detail::occupiedNear(mapped, key, truth.tolerance_m, res_m) ? 1 : 0;
  }
  score.recall = static_cast<double>(score.heard_voxels_found) / static_cast<double>(score.heard_voxels);
  score.precision = truth.precision;
  const double sum = score.precision + score.recall;
  score.f1 = sum > 0.0 ? 2.0 * score.precision * score.recall / sum : 0.0;
  return score;
}

}  // namespace sonarmap
