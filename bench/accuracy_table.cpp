// sonarmap_accuracy_table: the accuracy of every detector × smoothing on the simulated tank and
// harbour (ground truth, eval/ground_truth.hpp) and on the real CRAS tank log (rectangle fit only,
// eval/tank_quality.hpp), printed as the Markdown tables of docs/accuracy.md.
//
// Usage: sonarmap_accuracy_table [DATA_DIR]   (DATA_DIR holds cras_micron_tank_static.mat;
//        default: the SONARMAP_DATA environment variable, else the configured shared data folder)
// Each simulated scene: one static run of 28 turns, seed 1 (simulateMsis defaults), mapped with
// mapSonarLog and default options except the detector and the smoothing.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/eval/tank_quality.hpp"
#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/formats/log_reader.hpp"

namespace {

using namespace sonarmap;

const std::vector<std::string> kDetectors{"threshold", "canny", "background", "cfar-ca", "cfar-so", "cfar-go", "cfar-os"};
const std::vector<std::string> kSmoothings{"none", "mean", "median", "gaussian"};

MapperOptions optionsFor(const std::string& detector, const std::string& smoothing) {
  MapperOptions options;
  selectDetector(options.detector, detector);
  options.smoothing.kind = parseSmoothing(smoothing);
  return options;
}

void printSceneTable(const std::string& name) {
  const Scene scene = builtinScene(name);
  const SonarLog log = simulateMsis(scene).log;
  std::printf("\n### Simulated `%s`\n\n", name.c_str());
  std::printf("| detector | smoothing | occupied | precision | recall | free accuracy | wall error mean / rms (m) |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|\n");
  for (const std::string& detector : kDetectors) {
    for (const std::string& smoothing : kSmoothings) {
      const SonarMapper mapper = mapSonarLog(log, optionsFor(detector, smoothing));
      try {
        const GroundTruthReport r = evaluateAgainstScene(mapper.map(), scene);
        std::printf("| %s | %s | %zu | %.3f | %.3f | %.3f | %.3f / %.3f |\n", detector.c_str(), smoothing.c_str(),
                    r.occupied_voxels, r.precision, r.recall, r.free_accuracy, r.mean_distance_m, r.rms_distance_m);
      } catch (const std::exception& error) {
        std::printf("| %s | %s | – | %s | | | |\n", detector.c_str(), smoothing.c_str(), error.what());
      }
      std::fflush(stdout);
    }
  }
}

void printCrasTable(const std::string& path) {
  std::printf("\n### Real CRAS tank (`%s`), rectangle fit at z = 0\n\n", path.c_str());
  if (!std::filesystem::exists(path)) {
    std::printf("(absent)\n");
    return;
  }
  const SonarLog log = readSonarLog(path);
  std::printf("| detector | smoothing | occupied | on walls | walls covered | rms to walls (m) | fitted size (m) | inside free |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& detector : kDetectors) {
    for (const std::string& smoothing : kSmoothings) {
      const SonarMapper mapper = mapSonarLog(log, optionsFor(detector, smoothing));
      const std::size_t occupied = cellsInSlice(mapper.map(), 0.0, Occupancy::kOccupied).size();
      if (occupied < 8) {
        std::printf("| %s | %s | %zu | – | – | – | – | – |\n", detector.c_str(), smoothing.c_str(), occupied);
        continue;
      }
      const TankMapQuality q = evaluateTankMap(mapper.map(), 0.0);
      std::printf("| %s | %s | %zu | %.3f | %.3f | %.3f | %.2f × %.2f | %.3f |\n", detector.c_str(), smoothing.c_str(),
                  q.occupied_cells, q.walls.share_on_walls, q.walls.wall_coverage, q.walls.rms_wall_distance_m,
                  q.walls.rect.width_m, q.walls.rect.height_m, q.interior_free_share);
      std::fflush(stdout);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const char* env = std::getenv("SONARMAP_DATA");
  const std::string data = argc > 1 ? argv[1] : (env != nullptr ? env : SONARMAP_SHARED_DATA);
  try {
    for (const std::string& name : builtinSceneNames()) printSceneTable(name);
    printCrasTable(data + "/cras_micron_tank_static.mat");
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sonarmap_accuracy_table: error: %s\n", error.what());
    return 1;
  }
  return 0;
}
