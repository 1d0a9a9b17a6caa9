// sonarmap_accuracy_3d: the 3D accuracy table of docs/accuracy.md. Each simulated
// mission (eval/simulated_mission.hpp) mapped with the planar model, the beam-volume model, and the
// beam-volume model without the water surface's depth, at 5 cm voxels, scored in 3D against the scene with the head's
// field of view: precision, recall, F1, surface error (median, 90th percentile), erosion, free
// accuracy; obstacles, voxel updates, mapping time and the real-time factor (the mission's length over it). Each map is also scored against the surface
// its log's beams heard (eval/heard_surface.hpp) at 0 dB and at −6 dB over the receiver's
// floor: heard recall and heard F1 (with the precision above). The heard surface is computed once
// per mission, level and voxel size, not once per model.
//
// With a log (an argument ending in .mat, .V4LOG or .csv, e.g. the CRAS tank), that log is mapped
// in 3D with the defaults at RESOLUTION_M instead, and its occupied voxels are tabled by horizontal
// range from the sonar (0.25 m rings): count and height extent against 2 r tan(aperture / 2), the
// vertical band a static head must give (docs/mapping.md).
//
// Usage: sonarmap_accuracy_3d [RESOLUTION_M | auto] [PRESET ... | LOG] [--detector NAME] [--models LIST]
// (defaults: 0.05, micron; auto: each log's automatic resolution, autoResolutionForLog, as `sonarmap
// map` without --resolution; --detector: every model with that detector instead of the default, e.g.
// evidence; --models: the comma-separated models to table, of planar, volume, volume-surface-unknown
// and inversion (BeamModel::kInversion), default the first three)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonarmap/eval/heard_surface.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/scene.hpp"

namespace {

using namespace sonarmap;

struct Model {
  const char* name;
  const char* key;  ///< its name in --models
  BeamModel beam;
  double water_surface_depth_m = MapperOptions{}.water_surface_depth_m;  ///< NaN: unknown
};

/// Table rows of the mission's recall and erosion per scene primitive.
std::string recallBySurface(const std::string& preset, const std::string& mission, const Scene& scene,
                            const MissionAccuracy& accuracy) {
  std::string rows;
  for (const SurfaceRecall& surface : accuracy.truth.recall_by_surface) {
    const auto share = [&](std::size_t n) { return static_cast<double>(n) / static_cast<double>(surface.visible_voxels); };
    char row[256];
    std::snprintf(row, sizeof row, "| %s | %s | %zu (%s) | %zu | %.3f | %.3f |\n", preset.c_str(), mission.c_str(),
                  surface.primitive, primitiveKind(scene.primitives[surface.primitive]), surface.visible_voxels,
                  share(surface.found_voxels), share(surface.free_voxels));
    rows += row;
  }
  return rows;
}

/// The levels over the receiver's floor at which the maps are scored against the heard surface, dB.
constexpr double kHeardLevels_db[] = {0.0, -6.0};

/// A mission's heard surfaces, one per level of kHeardLevels_db, made at the first voxel size a map
/// asks for and again only when a map of another voxel size comes (`auto` resolves per model).
class HeardSurfaces {
 public:
  explicit HeardSurfaces(const MissionRun& run) : run_(run) {}

  /// The heard surface at level `level` (an index into kHeardLevels_db) on the grid of `resolution_m`;
  /// its voxel count is recorded for the table of heard surfaces.
  const OcTree16& at(std::size_t level, double resolution_m) {
    if (maps_.empty() || resolution_m_ != resolution_m) {
      maps_.clear();
      resolution_m_ = resolution_m;
      for (const double level_db : kHeardLevels_db) {
        HeardSurfaceStats stats;
        maps_.push_back(heardSurfaceMap(run_, HeardSurfaceOptions{resolution_m, level_db}, &stats));
        made_.push_back({level_db, resolution_m, stats.voxels});
      }
    }
    return maps_[level];
  }

  struct Made {
    double level_db, resolution_m;
    std::size_t voxels;
  };
  /// Every heard surface made, in order.
  const std::vector<Made>& made() const { return made_; }

 private:
  const MissionRun& run_;
  double resolution_m_ = 0.0;
  std::vector<OcTree16> maps_;
  std::vector<Made> made_;
};

bool isLog(const std::string& argument) {
  for (const char* extension : {".mat", ".V4LOG", ".csv"}) {
    const std::string ending(extension);
    if (argument.size() > ending.size() && argument.compare(argument.size() - ending.size(), ending.size(), ending) == 0) {
      return true;
    }
  }
  return false;
}

/// A static log mapped in 3D: occupied voxels by horizontal range from the sonar.
void printBands(const std::string& path, double resolution_m) {
  MapperOptions options;
  options.resolution_m = resolution_m;
  options.beam_model = BeamModel::kVolume;
  const SonarMapper mapper = mapSonarLog(readSonarLog(path), options);
  const OcTree16& map = mapper.map();
  struct Band {
    std::size_t voxels = 0;
    double z_min_m = INFINITY, z_max_m = -INFINITY;
  };
  std::map<int, Band> bands;  // by 0.25 m ring
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (map.model().classify(leaf.log_odds) != Occupancy::kOccupied) return;
    leaf.forEachVoxel([&](const Key16& key) {
      const Eigen::Vector3d centre = map.coder().centerOf(key);
      Band& band = bands[static_cast<int>(std::floor(std::hypot(centre.x(), centre.y()) / 0.25))];
      ++band.voxels;
      band.z_min_m = std::min(band.z_min_m, centre.z());
      band.z_max_m = std::max(band.z_max_m, centre.z());
    });
  });
  std::printf("| range (m) | occupied voxels | height (m) | 2 r tan(aperture / 2) (m) |\n|---|---:|---:|---:|\n");
  for (const auto& [ring, band] : bands) {
    const double middle_m = 0.25 * ring + 0.125;
    std::printf("| %.2f–%.2f | %zu | %.2f | %.2f |\n", 0.25 * ring, 0.25 * ring + 0.25, band.voxels,
                band.z_max_m - band.z_min_m, 2.0 * middle_m * std::tan(0.5 * options.vertical_aperture_rad));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool automatic = argc > 1 && std::string(argv[1]) == "auto";
  const double resolution_m = argc > 1 && !automatic ? std::atof(argv[1]) : 0.05;
  if (argc > 2 && isLog(argv[2])) {
    try {
      if (automatic) throw std::invalid_argument("give a log's resolution in metres");
      printBands(argv[2], resolution_m);
    } catch (const std::exception& error) {
      std::fprintf(stderr, "sonarmap_accuracy_3d: %s\n", error.what());
      return 1;
    }
    return 0;
  }
  std::vector<std::string> presets;
  DetectorOptions detector;
  std::string wanted = "planar,volume,volume-surface-unknown";
  for (int i = 2; i < argc; ++i) {
    if (std::string(argv[i]) == "--detector" && i + 1 < argc) {
      selectDetector(detector, argv[++i]);
    } else if (std::string(argv[i]) == "--models" && i + 1 < argc) {
      wanted = std::string(",") + argv[++i] + ",";
    } else {
      presets.emplace_back(argv[i]);
    }
  }
  if (presets.empty()) presets = {"micron"};
  const Model all_models[] = {
      {"planar", "planar", BeamModel::kPlanar},
      {"volume", "volume", BeamModel::kVolume},
      {"volume, water surface unknown", "volume-surface-unknown", BeamModel::kVolume, std::numeric_limits<double>::quiet_NaN()},
      {"inversion", "inversion", BeamModel::kInversion}};
  wanted = "," + wanted + ",";
  std::vector<Model> models;
  for (const Model& model : all_models) {
    if (wanted.find(std::string(",") + model.key + ",") != std::string::npos) models.push_back(model);
  }
  std::printf("| head | mission | model | occupied | precision | off the surface, in water | recall | F1 | "
              "heard recall / F1, 0 dB | heard recall / F1, −6 dB | "
              "surface error median / p90 (m) | erosion | free accuracy | obstacles | voxel updates | mapping (s) | real time / mapping | voxel (m) |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::string by_surface;  // the default model's recall and erosion per scene primitive
  std::string heard_rows;  // the heard surfaces' sizes
  for (const std::string& preset : presets) {
    for (const std::string& mission : simulatedMissionNames()) {
      const SimulatedMission simulated{preset, "quay3d", mission};
      std::optional<MissionRun> run;
      try {
        run = simulateMission(simulated);
      } catch (const std::exception& error) {
        std::printf("| %s | %s | %s |\n", preset.c_str(), mission.c_str(), error.what());
        continue;
      }
      HeardSurfaces heard(*run);
      const std::vector<Beam>& beams = run->simulation.log.beams;
      const double duration_s = beams.empty() ? 0.0 : beams.back().time_s - beams.front().time_s;  // the mission's length
      for (const Model& model : models) {
        MapperOptions options;
        if (!automatic) options.resolution_m = resolution_m;
        options.detector = detector;
        options.beam_model = model.beam;
        options.water_surface_depth_m = model.water_surface_depth_m;
        try {
          std::vector<HeardSurfaceScore> scores;
          const MissionAccuracy a =
              evaluateMission(simulated, *run, options, [&](const OcTree16& map, const MissionAccuracy& scored) {
                for (std::size_t level = 0; level < std::size(kHeardLevels_db); ++level) {
                  scores.push_back(scoreAgainstHeardSurface(map, scored.truth, heard.at(level, map.resolution_m())));
                }
              });
          const GroundTruthReport& t = a.truth;
          const std::size_t off_surface = t.occupied_voxels - t.occupied_on_surface;
          std::printf("| %s | %s | %s | %zu | %.3f | %.3f | %.3f | %.3f | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f | %.4f "
                      "| %.3f | %zu | %.3g | %.2f | %.0f | %.3g |\n",
                      preset.c_str(), mission.c_str(), model.name, t.occupied_voxels, t.precision,
                      off_surface > 0 ? static_cast<double>(t.occupied_in_water) / static_cast<double>(off_surface) : 0.0,
                      t.recall, a.f1(), scores[0].recall, scores[0].f1, scores[1].recall, scores[1].f1,
                      t.surface_error_median_m, t.surface_error_p90_m, t.erosion, t.free_accuracy, a.obstacles,
                      static_cast<double>(a.voxel_updates), a.seconds_mapping, duration_s / a.seconds_mapping,
                      a.resolution_m);
          if (model.beam == BeamModel::kVolume && model.water_surface_depth_m == MapperOptions{}.water_surface_depth_m) {
            by_surface += recallBySurface(preset, mission, run->simulation.scene, a);
          }
        } catch (const std::exception& error) {
          std::printf("| %s | %s | %s | %s |\n", preset.c_str(), mission.c_str(), model.name, error.what());
        }
        std::fflush(stdout);
      }
      for (const HeardSurfaces::Made& made : heard.made()) {
        char row[160];
        std::snprintf(row, sizeof row, "| %s | %s | %+.0f dB | %zu | %.3g |\n", preset.c_str(), mission.c_str(),
                      made.level_db, made.voxels, made.resolution_m);
        heard_rows += row;
      }
    }
  }
  std::printf("\nRecall and erosion of the default volume model by surface (visible surface voxels nearest each "
              "primitive of the scene, builtin_scenes.hpp):\n\n| head | mission | primitive | visible voxels | "
              "recall | erosion |\n|---|---|---|---:|---:|---:|\n%s",
              by_surface.c_str());
  std::printf("\nThe heard surfaces the maps were scored against (heardSurfaceMap: surface points whose mean echo "
              "is at least the level over the receiver's floor):\n\n| head | mission | level over the floor | heard "
              "voxels | voxel (m) |\n|---|---|---|---:|---:|\n%s",
              heard_rows.c_str());
  return 0;
}
