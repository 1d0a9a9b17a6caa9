// sonarmap_mission_reach: what the 3D accuracy missions can reach. For each simulated
// mission of sonarmap_accuracy_3d, the surface its beams could hear (eval/heard_surface.hpp: every
// surface point a fine grid of rays across each beam meets, kept where its primitive's mean echo is
// at least L dB over the receiver's floor), scored as sonarmap_accuracy_3d scores a map: recall,
// the F1 bound 2R / (1 + R) a map with that recall cannot pass, and recall by surface. Rows: the
// geometry alone (every point a ray meets, L = −∞) and L = −6, 0, 6 and 16.9 dB (16.9: the CRAS
// tank's obstacle threshold over its background, accuracy.md).
//
// Usage: sonarmap_mission_reach [RESOLUTION_M | auto] [PRESET ...]   (defaults: 0.05, micron;
// auto: each log's automatic resolution, as sonarmap_accuracy_3d auto)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/eval/heard_surface.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/mapping/mapper_options.hpp"

int main(int argc, char** argv) {
  using namespace sonarmap;
  const bool automatic = argc > 1 && std::string(argv[1]) == "auto";
  const double fixed_resolution_m = argc > 1 && !automatic ? std::atof(argv[1]) : 0.05;
  std::vector<std::string> presets;
  for (int i = 2; i < argc; ++i) presets.emplace_back(argv[i]);
  if (presets.empty()) presets = {"micron"};
  const double kLevels_db[] = {-std::numeric_limits<double>::infinity(), -6.0, 0.0, 6.0, 16.9};
  std::printf("| head | mission | heard: echo over the floor | occupied | precision | recall | F1 bound 2R/(1+R) | "
              "recall by surface (primitive: recall of its visible voxels) | voxel (m) |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---|---:|\n");
  for (const std::string& preset : presets) {
    for (const std::string& mission : simulatedMissionNames()) {
      try {
        const MissionRun run = simulateMission(SimulatedMission{preset, "quay3d", mission});
        const double resolution_m =
            automatic ? autoResolutionForLog(run.simulation.log, MapperOptions{}).resolution_m : fixed_resolution_m;
        const GroundTruthOptions truth = missionTruthOptions(run);
        for (const double level_db : kLevels_db) {
          const OcTree16 heard = heardSurfaceMap(run, HeardSurfaceOptions{resolution_m, level_db});
          const GroundTruthReport t = evaluateAgainstScene(heard, run.simulation.scene, truth);
          std::string by_surface;
          for (const SurfaceRecall& surface : t.recall_by_surface) {
            char cell[64];
            std::snprintf(cell, sizeof cell, "%s%zu: %.3f", by_surface.empty() ? "" : ", ", surface.primitive,
                          static_cast<double>(surface.found_voxels) / static_cast<double>(surface.visible_voxels));
            by_surface += cell;
          }
          char level[32];
          if (std::isinf(level_db)) {
            std::snprintf(level, sizeof level, "any (geometry)");
          } else {
            std::snprintf(level, sizeof level, "≥ %.1f dB", level_db);
          }
          std::printf("| %s | %s | %s | %zu | %.3f | %.3f | %.3f | %s | %.3g |\n", preset.c_str(), mission.c_str(), level,
                      t.occupied_voxels, t.precision, t.recall, 2.0 * t.recall / (1.0 + t.recall), by_surface.c_str(),
                      resolution_m);
          std::fflush(stdout);
        }
      } catch (const std::exception& error) {
        std::printf("| %s | %s | %s |\n", preset.c_str(), mission.c_str(), error.what());
      }
    }
  }
  return 0;
}
