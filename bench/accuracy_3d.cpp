// sonarmap_accuracy_3d: the 3D accuracy table of docs/accuracy.md (issue 11). Each simulated
// mission (eval/simulated_mission.hpp) mapped with the planar model and with the beam-volume model
// under each arc-evidence rule, at 5 cm voxels, scored in 3D against the scene with the head's
// field of view: precision, recall, F1, surface error (median, 90th percentile), erosion, free
// accuracy; obstacles, voxel updates and mapping time.
//
// Usage: sonarmap_accuracy_3d [RESOLUTION_M] [PRESET ...]   (defaults: 0.05, micron)
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/mapping/mapper_options.hpp"

namespace {

using namespace sonarmap;

struct Model {
  const char* name;
  BeamModel beam;
  ArcEvidence evidence;
};

}  // namespace

int main(int argc, char** argv) {
  const double resolution_m = argc > 1 ? std::atof(argv[1]) : 0.05;
  std::vector<std::string> presets;
  for (int i = 2; i < argc; ++i) presets.emplace_back(argv[i]);
  if (presets.empty()) presets = {"micron"};
  const Model models[] = {{"planar", BeamModel::kPlanar, ArcEvidence::kWholeArc},
                          {"volume, whole arc", BeamModel::kVolume, ArcEvidence::kWholeArc},
                          {"volume, uniform spread", BeamModel::kVolume, ArcEvidence::kSpreadUniform},
                          {"volume, beam pattern", BeamModel::kVolume, ArcEvidence::kBeamPattern}};
  std::printf("| head | mission | model | occupied | precision | recall | F1 | surface error median / p90 (m) | "
              "erosion | free accuracy | obstacles | voxel updates | mapping (s) |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& preset : presets) {
    for (const std::string& mission : simulatedMissionNames()) {
      for (const Model& model : models) {
        MapperOptions options;
        options.resolution_m = resolution_m;
        options.beam_model = model.beam;
        options.arc_evidence = model.evidence;
        try {
          const MissionAccuracy a = evaluateMission(SimulatedMission{preset, "quay3d", mission}, options);
          const GroundTruthReport& t = a.truth;
          std::printf("| %s | %s | %s | %zu | %.3f | %.3f | %.3f | %.3f / %.3f | %.4f | %.3f | %zu | %.3g | %.2f |\n",
                      preset.c_str(), mission.c_str(), model.name, t.occupied_voxels, t.precision, t.recall, a.f1(),
                      t.surface_error_median_m, t.surface_error_p90_m, t.erosion, t.free_accuracy, a.obstacles,
                      static_cast<double>(a.voxel_updates), a.seconds_mapping);
        } catch (const std::exception& error) {
          std::printf("| %s | %s | %s | %s |\n", preset.c_str(), mission.c_str(), model.name, error.what());
        }
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
