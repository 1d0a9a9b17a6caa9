// sonarmap_accuracy_table: the tables of docs/accuracy.md.
//  1. Every simulated sonar head (sonar_presets.hpp) × built-in scene built for its range
//     (builtin_scenes.hpp), 360° scans, plus a sector scan and a moving run of the harbour, mapped
//     with the mapper's DEFAULT options, scored against the scene (eval/simulated_accuracy.hpp).
//  2. The real CRAS tank log with each detector: the rectangle measure (eval/tank_quality.hpp) at
//     a 10 cm tolerance.
//  3. The real SeaNet sector log: is the target's last position occupied?
//     Every shared real log against its own strong echoes (real_log_table.hpp).
//  4. With --analysis, where the errors come from (accuracy_analysis.hpp).
//
// Usage: sonarmap_accuracy_table [DATA_DIR] [--analysis] [--real-only] [--noise-tails] [--head PRESET]... [--detector NAME] [--local-reverberation]
//        (DATA_DIR holds the shared logs;
//        default: the SONARMAP_DATA environment variable, else the configured shared data folder;
//        --head: only the simulated rows of the named presets, e.g. --head ping360-2m --head ping360-5m;
//        --detector: the simulated rows and the real logs' own-echo table mapped with that detector
//        instead of the default, e.g. --detector evidence)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "accuracy_analysis.hpp"
#include "real_log_table.hpp"
#include "sonarmap/eval/last_sweep.hpp"
#include "sonarmap/eval/simulated_accuracy.hpp"
#include "sonarmap/eval/tank_quality.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace {

using namespace sonarmap;

std::string offsets(const SimulatedAccuracy& a) {
  std::string text;
  char cell[48];
  for (const SurfaceOffset& s : a.truth.surfaces) {
    if (s.voxels < 10) continue;
    bool off_plane = false;
    for (const SurfaceOffset& o : a.off_plane) off_plane |= o.primitive == s.primitive;
    std::snprintf(cell, sizeof cell, "%s%+.3f%s", text.empty() ? "" : " ", s.median_signed_offset_m, off_plane ? "*" : "");
    text += cell;
  }
  return text.empty() ? "–" : text;
}

void printRow(const SimulatedAccuracy& a) {
  const char* scan = a.run.speed_range_per_min > 0.0 ? "360°, moving" : (a.run.sector_deg < 360.0 ? "90° sector" : "360°");
  const double per_sweep = a.sweeps > 0 ? static_cast<double>(a.obstacles) / static_cast<double>(a.sweeps) : 0.0;
  std::printf("| %s | %s | %s | %.3g | %zu | %.3f | %.3f | %.3f | %.3f | %s | %.1f | %.3f |\n", a.run.preset.c_str(),
              a.run.scene.c_str(), scan, a.resolution_m, a.truth.occupied_voxels, a.truth.precision, a.truth.recall,
              a.truth.free_accuracy, a.worst_offset_m, offsets(a).c_str(), per_sweep, a.seconds_mapping);
  std::fflush(stdout);
}

/// The simulated table; `heads` limits it to those presets (all when empty).
void printSimulatedTable(const std::vector<std::string>& heads, const MapperOptions& options) {
  std::printf("\n### Simulated heads × scenes, %s detector\n\n", detectorName(options.detector).c_str());
  std::printf("| head | scene | scan | voxel (m) | occupied | precision | recall | free accuracy | worst \\|offset\\| (m) "
              "| offset per surface (m) | obstacles / sweep | mapping (s) |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|---:|---|---:|---:|\n");
  for (const std::string& preset : heads.empty() ? sonarPresetNames() : heads) {
    for (const std::string& scene : builtinSceneNames()) {
      try {
        printRow(evaluateSimulatedRun(SimulatedRun{preset, scene}, options));
      } catch (const std::exception& error) {
        std::printf("| %s | %s | 360° | %s |\n", preset.c_str(), scene.c_str(), error.what());
      }
    }
    SimulatedRun sector{preset, "harbour"};
    sector.sector_deg = 90.0;
    sector.turns = 16;
    printRow(evaluateSimulatedRun(sector, options));
    SimulatedRun moving{preset, "harbour"};
    moving.speed_range_per_min = 1.0;
    printRow(evaluateSimulatedRun(moving, options));
  }
}

void printCrasTable(const std::string& path) {
  std::printf("\n### Real CRAS tank (`%s`), rectangle measure at z = 0, 10 cm tolerance\n\n",
              std::filesystem::path(path).filename().c_str());
  if (!std::filesystem::exists(path)) {
    std::printf("(absent)\n");
    return;
  }
  const SonarLog log = readSonarLog(path);
  std::printf("| detector | obstacles | occupied | on walls | walls covered | rms to walls (m) | fitted size (m) | inside free | mapping (s) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const char* detector : {"background", "evidence", "cfar-ca", "cfar-so", "cfar-go", "cfar-os", "threshold", "canny"}) {
    MapperOptions options;
    selectDetector(options.detector, detector);
    const auto start = std::chrono::steady_clock::now();
    const SonarMapper mapper = mapSonarLog(log, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::size_t occupied = cellsInSlice(mapper.map(), 0.0, Occupancy::kOccupied).size();
    if (occupied < 8) {
      std::printf("| %s | %zu | %zu | – | – | – | – | – | %.3f |\n", detector, mapper.stats().obstacles, occupied, seconds);
      continue;
    }
    WallFitOptions fit;
    fit.wall_tolerance_m = 0.10;
    const TankMapQuality q = evaluateTankMap(mapper.map(), 0.0, fit);
    std::printf("| %s | %zu | %zu | %.3f | %.3f | %.3f | %.2f × %.2f | %.3f | %.3f |\n", detector, mapper.stats().obstacles,
                q.occupied_cells, q.walls.share_on_walls, q.walls.wall_coverage, q.walls.rms_wall_distance_m,
                q.walls.rect.width_m, q.walls.rect.height_m, q.interior_free_share, seconds);
    std::fflush(stdout);
  }
}

void printSeaNetRow(const std::string& path) {
  std::printf("\n### Real SeaNet sector log (`%s`): the target's last position\n\n",
              std::filesystem::path(path).filename().c_str());
  if (!std::filesystem::exists(path)) {
    std::printf("(absent)\n");
    return;
  }
  const SonarLog log = readSonarLog(path);
  const SonarMapper mapper = mapSonarLog(log);
  std::size_t echoes = 0, occupied = 0;
  for (const LastSweepEcho& echo : lastSweepEchoes(log, mapper)) {
    ++echoes;
    occupied += echo.occupied;
    std::printf("- beam at %.1f°: echo at %.2f m, %s\n", echo.bearing_rad * 180.0 / std::numbers::pi, echo.range_m,
                echo.occupied ? "occupied" : "NOT occupied");
  }
  std::printf("\n%zu of the last sweep's %zu echoes are occupied cells in the final map (%zu sweeps, %zu obstacles, "
              "%.3g m voxels).\n",
              occupied, echoes, mapper.stats().sweeps, mapper.stats().obstacles, mapper.map().resolution_m());
}

}  // namespace

int main(int argc, char** argv) {
  const char* env = std::getenv("SONARMAP_DATA");
  std::string data = env != nullptr ? env : SONARMAP_SHARED_DATA;
  bool analysis = false;
  bool real_only = false;  // the real logs' tables only (seconds instead of minutes)
  bool noise_tails_only = false;  // the noise-tail table only
  std::vector<std::string> heads;  // --head NAME: the simulated table's rows of those presets only (no real logs)
  std::string detector;  // --detector NAME: instead of the default
  bool local_reverberation = false;  // --local-reverberation: the evidence detector over the local level
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--analysis") {
      analysis = true;
    } else if (std::string(argv[i]) == "--real-only") {
      real_only = true;
    } else if (std::string(argv[i]) == "--noise-tails") {
      noise_tails_only = true;
    } else if (std::string(argv[i]) == "--head" && i + 1 < argc) {
      heads.emplace_back(argv[++i]);
    } else if (std::string(argv[i]) == "--detector" && i + 1 < argc) {
      detector = argv[++i];
    } else if (std::string(argv[i]) == "--local-reverberation") {
      local_reverberation = true;
    } else {
      data = argv[i];
    }
  }
  try {
    if (noise_tails_only) {
      sonarmap::bench::printNoiseTailTable(data);
      return 0;
    }
    MapperOptions options;
    if (!detector.empty()) selectDetector(options.detector, detector);
    options.detector.reverberation.enabled = local_reverberation;
    if (!real_only) printSimulatedTable(heads, options);
    if (!heads.empty()) return 0;
    printCrasTable(data + "/cras_micron_tank_static.mat");
    printSeaNetRow(data + "/seanet_sector_target.V4LOG");
    sonarmap::bench::printRealLogTable(data, options);
    if (analysis) {
      sonarmap::bench::printLeadingEdgeTable();
      sonarmap::bench::printIncidenceTable();
      sonarmap::bench::printFalseAlarmTable();
      sonarmap::bench::printNoiseTailTable(data);
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sonarmap_accuracy_table: error: %s\n", error.what());
    return 1;
  }
  return 0;
}
