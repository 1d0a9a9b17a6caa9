// sonarmap_wall_offsets: where scan forming places an oblique wall's points (docs/localization.md;
// not a test).
//
// For each head, seed 1 of the harbour loop (sim/missions.hpp) flown at the head's default speed,
// its scans formed with the true navigation (slam/scan_forming.hpp): each point seen on the quay
// (north of its face less 2 % of the range) is compared with the quay's face (north 3.5 m at the
// builtin scenes' 5 m reach, scaled to the head's range), binned by the incidence of its line of
// sight on the face. Points on their beams' axes (the default) and at the bearing their leading
// edge came from (ScanFormingOptions::leading_edge_bearing). A negative offset lies in front of
// the face, towards the sonar.
//
// Usage: sonarmap_wall_offsets

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "sonarmap/mapping/detected_log.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"
#include "sonarmap/slam/scan_forming.hpp"

using namespace sonarmap;

namespace {

constexpr int kBins = 5;  // incidence 0–50° in 10° bins

struct Offsets {
  std::array<double, kBins> sum_m{};
  std::array<int, kBins> count{};
};

Offsets quayOffsets(const DetectedLog& detected, const MsisSimulation& run, const MsisSimulationOptions& options,
                    double face_m, bool leading_edge_bearing) {
  ScanFormingOptions forming;
  forming.leading_edge_bearing = leading_edge_bearing;
  Offsets offsets;
  for (const SonarScan& scan : formScans(detected, run.nav, options.sonar_to_body, forming)) {
    for (const ScanPoint& point : scan.points) {
      const Eigen::Vector2d ned = scan.dead_reckoning * point.xy_m;
      if (ned.x() < face_m - 0.02 * options.head.range_m) continue;
      const Eigen::Vector2d look = -(scan.dead_reckoning.rotation() * point.toward_sonar);
      const double incidence_deg = std::acos(std::min(1.0, std::abs(look.x()))) * 180.0 / std::numbers::pi;
      const int bin = static_cast<int>(incidence_deg / 10.0);
      if (bin >= kBins) continue;
      offsets.sum_m[static_cast<std::size_t>(bin)] += ned.x() - face_m;
      ++offsets.count[static_cast<std::size_t>(bin)];
    }
  }
  return offsets;
}

}  // namespace

int main() {
  std::printf("| head | incidence | points | offset on the axis | offset at the leading edge's bearing |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const std::string sonar : {"seaking-30", "ping360", "micron"}) {
    SimulationArguments args;
    args.sonar = sonar;
    args.mission = "harbour-loop";
    args.seed = 1;
    const MsisSimulationOptions options = toSimulationOptions(args);
    const MsisSimulation run = simulateInMissionScene(args.mission, options);
    const DetectedLog detected = detectSonarLog(run.log, MapperOptions{});
    const double face_m = 3.5 * options.head.range_m / kBuiltinSceneReach_m;
    const Offsets axis = quayOffsets(detected, run, options, face_m, false);
    const Offsets edge = quayOffsets(detected, run, options, face_m, true);
    for (std::size_t bin = 0; bin < kBins; ++bin) {
      if (axis.count[bin] == 0) continue;
      std::printf("| %s | %zu–%zu° | %d | %+.3f m | %+.3f m |\n", sonar.c_str(), 10 * bin, 10 * bin + 10, axis.count[bin],
                  axis.sum_m[bin] / axis.count[bin], edge.count[bin] > 0 ? edge.sum_m[bin] / edge.count[bin] : 0.0);
    }
  }
  return 0;
}
