// sonarmap_first_returns: how many of a real log's first returns its default map holds
// (eval/first_returns.hpp): each beam's first return is where its echo first rises out of the water
// in front of it and stays up, found on the beam alone, and it counts as mapped when an occupied
// voxel lies in the beam's wedge at that range. Each log is mapped as `sonarmap map LOG` maps it, with
// each detector named, and scored at rises of 3, 6 and 10 dB (6: the measure of docs/accuracy.md).
//
// Usage: sonarmap_first_returns [--detector NAME]... [--beam-width DEG] [--returns-csv OUT.csv] LOG...
//   (default detectors: background and evidence; a ROS bag is read after
//   scripts/rosbag_to_beam_csv.py has turned it into a beam CSV). --returns-csv writes the first
//   returns at 6 dB of the last log with each detector: detector,beam,time_s,bearing_deg,range_m,mapped
//   (examples/plot_first_returns.py draws them over the log's polar images).
#include <cstdio>
#include <fstream>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "sonarmap/eval/first_returns.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"

int main(int argc, char** argv) {
  using namespace sonarmap;
  std::vector<std::string> detectors, logs;
  double beam_width_deg = 3.0;
  std::string returns_csv;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--detector" && i + 1 < argc) {
      detectors.emplace_back(argv[++i]);
    } else if (arg == "--returns-csv" && i + 1 < argc) {
      returns_csv = argv[++i];
    } else if (arg == "--beam-width" && i + 1 < argc) {
      beam_width_deg = std::atof(argv[++i]);
    } else {
      logs.push_back(arg);
    }
  }
  if (logs.empty()) {
    std::fprintf(stderr, "usage: sonarmap_first_returns [--detector NAME]... [--beam-width DEG] LOG...\n");
    return 2;
  }
  if (detectors.empty()) detectors = {"background", "evidence"};
  std::ofstream returns_out;
  if (!returns_csv.empty()) {
    returns_out.open(returns_csv);
    returns_out << "detector,beam,time_s,bearing_deg,range_m,mapped\n";
  }
  std::printf("| log | detector | voxel (m) | beams | first returns (6 dB) | mapped at 3 dB | at 6 dB | at 10 dB |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& path : logs) {
    try {
      const SonarLog log = readSonarLog(path);
      for (const std::string& detector : detectors) {
        MapperOptions options;
        selectDetector(options.detector, detector);
        options.beam_width_rad = beam_width_deg * std::numbers::pi / 180.0;
        const SonarMapper mapper = mapSonarLog(log, options);
        std::string cells;
        std::size_t returns_6db = 0;
        for (const double rise_db : {3.0, 6.0, 10.0}) {
          FirstReturnOptions measure;
          measure.rise_db = rise_db;
          measure.beam_width_rad = options.beam_width_rad;
          const FirstReturnScore score = firstReturns(mapper.map(), log, {}, measure);
          if (rise_db == 6.0) {
            returns_6db = score.returns.size();
            if (returns_out.is_open() && &path == &logs.back()) {
              for (const FirstReturn& first : score.returns) {
                const Beam& beam = log.beams[first.beam];
                returns_out << detector << ',' << first.beam << ',' << beam.time_s << ','
                            << beam.bearing_rad * 180.0 / std::numbers::pi << ',' << first.range_m << ','
                            << (first.mapped ? 1 : 0) << '\n';
              }
            }
          }
          char cell[64];
          std::snprintf(cell, sizeof cell, " %.3f (%zu) |", score.share(), score.returns.size());
          cells += cell;
        }
        std::printf("| `%s` | %s | %.3g | %zu | %zu |%s\n", std::filesystem::path(path).filename().c_str(), detector.c_str(),
                    mapper.map().resolution_m(), log.beams.size(), returns_6db, cells.c_str());
        std::fflush(stdout);
      }
    } catch (const std::exception& error) {
      std::printf("| `%s` | error: %s |\n", path.c_str(), error.what());
    }
  }
  return 0;
}
