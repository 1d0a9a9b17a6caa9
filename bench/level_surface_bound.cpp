// sonarmap_level_surface_bound: what modelling each kind of surface as what it is can reach on the
// simulated 3D missions (eval/simulated_mission.hpp), before building it. The default --3d map of
// each mission is edited with the truth and scored against the heard surface at 0 dB
// (eval/heard_surface.hpp), as docs/accuracy.md scores maps:
//  - "default": the map as mapped;
//  - "default, nothing off the surfaces": without its occupied voxels farther than the tolerance from
//    every surface — what explaining every loud bin by the surface that returned it would give
//    with the surfaces' recall as mapped;
//  - "level surfaces exact": its voxels nearest a level surface (a plane of the scene: the seabed
//    and the water surface) replaced by exactly the heard voxels of those planes — a perfect
//    height field, everything else (faces, smear in the water) as mapped;
//  - "+ nothing off the surfaces": both;
//  - "+ standing objects heard": also with every heard voxel of the other primitives — recall 1,
//    precision 1 (the check of the scoring).
// The tolerance is the scoring's (missionTruthOptions: 0.1 m, at least √3 voxels). Below the table,
// the default map's voxels off the surfaces by their distance to the nearest one: how many are a
// surface drawn thick (within 0.25 m) and how many lie far from any; and the looks per heard voxel:
// the beams whose −3 dB cone (width × vertical aperture, within the head's range, from the true
// pose) holds its centre, median and 10th percentile, for the level surfaces (the planes) and the
// standing ones.
//
// Usage: sonarmap_level_surface_bound [RESOLUTION_M | auto] [PRESET ...]   (defaults: 0.05, micron)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sonarmap/eval/heard_surface.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sim/scene.hpp"

namespace {

using namespace sonarmap;

/// Index of the primitive of `scene` nearest `point_m`.
std::size_t nearestPrimitive(const Scene& scene, const Eigen::Vector3d& point_m) {
  std::size_t nearest = 0;
  double best_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
    const double distance_m = distanceToSurface(scene.primitives[i], point_m);
    if (distance_m < best_m) {
      best_m = distance_m;
      nearest = i;
    }
  }
  return nearest;
}

bool isLevel(const Primitive& primitive) { return std::holds_alternative<Plane>(primitive); }

/// Occupied voxel centres of `map`.
std::vector<Eigen::Vector3d> occupiedCentres(const OcTree16& map) {
  std::vector<Eigen::Vector3d> centres;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (map.model().classify(leaf.log_odds) != Occupancy::kOccupied) return;
    leaf.forEachVoxel([&](const Key16& key) { centres.push_back(map.coder().centerOf(key)); });
  });
  return centres;
}

/// Sets the voxel at `point_m` occupied (clamped high) or free (clamped low).
void setVoxel(OcTree16& map, const Eigen::Vector3d& point_m, bool occupied) {
  const auto key = map.coder().keyOf(point_m);
  if (!key) return;
  map.updateNode(*key, occupied ? 100.0f : -100.0f, true);
}

/// The q-quantile (0..1) of `values` (sorted here); 0 when empty.
double quantile(std::vector<int>& values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1))];
}

/// Looks per heard voxel (see the file's comment): one count per voxel of `heard_voxels`.
std::vector<int> looksPerVoxel(const MissionRun& run, const std::vector<Eigen::Vector3d>& heard_voxels) {
  std::vector<int> looks(heard_voxels.size(), 0);
  const NavInterpolator nav(run.simulation.nav);
  const double half_width_rad = 0.5 * run.options.head.horizontal_beam_width_rad;
  const double sin_half_aperture = std::sin(0.5 * run.options.head.vertical_beam_width_rad);
  const double range_m = run.options.head.range_m;
  for (const Beam& beam : run.simulation.log.beams) {
    const std::optional<Eigen::Isometry3d> body_to_ned = nav.bodyToNedAt(beam.time_s);
    if (!body_to_ned) continue;
    const Eigen::Isometry3d sonar_to_map = nedToMap() * *body_to_ned * run.options.sonar_to_body;
    const Eigen::Matrix3d map_to_sonar = sonar_to_map.linear().transpose();
    const Eigen::Vector3d origin_m = sonar_to_map.translation();
    for (std::size_t v = 0; v < heard_voxels.size(); ++v) {
      const Eigen::Vector3d d = heard_voxels[v] - origin_m;
      const double r2 = d.squaredNorm();
      if (r2 > range_m * range_m || r2 <= 0.0) continue;
      const Eigen::Vector3d s = map_to_sonar * d;
      if (std::abs(s.z()) > sin_half_aperture * std::sqrt(r2)) continue;
      const double off_rad = std::remainder(std::atan2(s.y(), s.x()) - beam.bearing_rad, 2.0 * M_PI);
      if (std::abs(off_rad) <= half_width_rad) ++looks[v];
    }
  }
  return looks;
}

}  // namespace

int main(int argc, char** argv) {
  const bool automatic = argc > 1 && std::string(argv[1]) == "auto";
  const double resolution_m = argc > 1 && !automatic ? std::atof(argv[1]) : 0.05;
  std::vector<std::string> presets;
  for (int i = 2; i < argc; ++i) presets.emplace_back(argv[i]);
  if (presets.empty()) presets = {"micron"};
  std::printf("| head | mission | map | occupied | precision | heard recall | heard F1 | voxel (m) |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|\n");
  std::string distances;   // the default maps' voxels off the surfaces by distance
  std::string looks_rows;  // looks per heard voxel
  for (const std::string& preset : presets) {
    for (const std::string& mission : simulatedMissionNames()) {
      try {
        const SimulatedMission simulated{preset, "quay3d", mission};
        const MissionRun run = simulateMission(simulated);
        const Scene& scene = run.simulation.scene;
        std::size_t off_surface[3] = {0, 0, 0};  // within 0.25 m, 0.25–1 m, farther
        std::vector<int> level_looks, standing_looks;  // looks per heard voxel of each kind
        MapperOptions options;
        if (!automatic) options.resolution_m = resolution_m;
        options.beam_model = BeamModel::kVolume;
        evaluateMission(simulated, run, options, [&](const OcTree16& mapped, const MissionAccuracy& scored) {
          const double res_m = mapped.resolution_m();
          const OcTree16 heard = heardSurfaceMap(run, HeardSurfaceOptions{res_m, 0.0});
          const std::vector<Eigen::Vector3d> heard_voxels = occupiedCentres(heard);
          const std::vector<int> looks = looksPerVoxel(run, heard_voxels);
          for (std::size_t v = 0; v < heard_voxels.size(); ++v) {
            (isLevel(scene.primitives[nearestPrimitive(scene, heard_voxels[v])]) ? level_looks : standing_looks).push_back(looks[v]);
          }
          const GroundTruthOptions truth_options = missionTruthOptions(run);
          const double tolerance_m = std::max(truth_options.tolerance_m, std::sqrt(3.0) * res_m);
          auto row = [&](const char* name, const OcTree16& map) {
            OcTree16 scored_map = map;
            scored_map.updateInnerOccupancy();
            const GroundTruthReport truth = evaluateAgainstScene(scored_map, scene, truth_options);
            const HeardSurfaceScore score = scoreAgainstHeardSurface(scored_map, truth, heard);
            std::printf("| %s | %s | %s | %zu | %.3f | %.3f | %.3f | %.3g |\n", preset.c_str(), mission.c_str(), name,
                        truth.occupied_voxels, truth.precision, score.recall, score.f1, res_m);
            std::fflush(stdout);
          };
          row("default", mapped);
          for (const OccupiedVoxelError& voxel : scored.truth.occupied_errors) {
            if (voxel.distance_m <= tolerance_m) continue;
            ++off_surface[voxel.distance_m <= 0.25 ? 0 : (voxel.distance_m <= 1.0 ? 1 : 2)];
          }
          OcTree16 default_dry = mapped;
          for (const Eigen::Vector3d& centre : occupiedCentres(mapped)) {
            if (distanceToSurface(scene, centre) > tolerance_m) setVoxel(default_dry, centre, false);
          }
          row("default, nothing off the surfaces", default_dry);
          OcTree16 level = mapped;
          for (const Eigen::Vector3d& centre : occupiedCentres(mapped)) {
            if (isLevel(scene.primitives[nearestPrimitive(scene, centre)]) && distanceToSurface(scene, centre) <= tolerance_m) {
              setVoxel(level, centre, false);
            }
          }
          for (const Eigen::Vector3d& centre : heard_voxels) {
            if (isLevel(scene.primitives[nearestPrimitive(scene, centre)])) setVoxel(level, centre, true);
          }
          row("level surfaces exact", level);
          OcTree16 dry = level;
          for (const Eigen::Vector3d& centre : occupiedCentres(level)) {
            if (distanceToSurface(scene, centre) > tolerance_m) setVoxel(dry, centre, false);
          }
          row("+ nothing off the surfaces", dry);
          for (const Eigen::Vector3d& centre : heard_voxels) setVoxel(dry, centre, true);
          row("+ standing objects heard", dry);
        });
        char line[200];
        std::snprintf(line, sizeof line, "| %s | %s | %zu | %zu | %zu |\n", preset.c_str(), mission.c_str(), off_surface[0],
                      off_surface[1], off_surface[2]);
        distances += line;
        std::snprintf(line, sizeof line, "| %s | %s | %.0f / %.0f | %.0f / %.0f |\n", preset.c_str(), mission.c_str(),
                      quantile(level_looks, 0.5), quantile(level_looks, 0.1), quantile(standing_looks, 0.5),
                      quantile(standing_looks, 0.1));
        looks_rows += line;
      } catch (const std::exception& error) {
        std::printf("| %s | %s | %s |\n", preset.c_str(), mission.c_str(), error.what());
      }
    }
  }
  std::printf("\nThe default maps' occupied voxels off the surfaces (farther than the tolerance) by distance to the "
              "nearest surface:\n\n| head | mission | ≤ 0.25 m | 0.25–1 m | > 1 m |\n|---|---|---:|---:|---:|\n%s",
              distances.c_str());
  std::printf("\nLooks per heard voxel (beams whose −3 dB cone holds it), median / 10th percentile:\n\n| head | "
              "mission | level surfaces | standing surfaces |\n|---|---|---:|---:|\n%s",
              looks_rows.c_str());
  return 0;
}
