// printRealLogTable (see real_log_table.hpp).
#include "real_log_table.hpp"

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "sonarmap/eval/echo_agreement.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/range_scales.hpp"

namespace sonarmap::bench {

void printRealLogTable(const std::string& data_dir, const MapperOptions& options) {
  std::printf("\n### Real logs against their own strong echoes (20 dB above the range's median, 0.3 m)\n\n");
  std::printf("| log | beams | range scales | voxel (m) | obstacles | occupied | echo points | precision | recall "
              "| first-echo recall | mapping (s) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const char* name : {"cras_micron_tank_static.mat", "seanet_sector_target.V4LOG", "ping360_basin.bin",
                           "ping360_harbour_range_changes.bin", "micron_pool_ros1.bag"}) {
    const std::string path = data_dir + "/" + name;
    if (!std::filesystem::exists(path)) {
      std::printf("| `%s` | (absent) |\n", name);
      continue;
    }
    try {
      const SonarLog log = readSonarLog(path);
      const auto start = std::chrono::steady_clock::now();
      const SonarMapper mapper = mapSonarLog(log, options);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const EchoAgreement a = echoAgreement(mapper.map(), log);
      std::printf("| `%s` | %zu | %zu | %.3g | %zu | %zu | %zu | %.3f | %.3f | %.3f | %.3f |\n", name, log.beams.size(),
                  rangeScales(log).size(), mapper.map().resolution_m(), mapper.stats().obstacles, a.occupied,
                  a.echo_points, a.precision, a.recall, a.first_echo_recall, seconds);
    } catch (const std::exception& error) {
      std::printf("| `%s` | error: %s |\n", name, error.what());
    }
    std::fflush(stdout);
  }
}

}  // namespace sonarmap::bench
