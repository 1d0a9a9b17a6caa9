// sonarmap_point_scan_study: `sonarmap localize` on point scans as users' detectors give them
// (docs/localization.md; not a test).
//
// For each head (Micron, SeaKing-30, Ping360) and loop mission, seeds 1…N with the drifting dead
// reckoning of tests/slam/slam_fixture.hpp (3 % DVL scale error, 2° heading bias, 0.02°/√s): the
// mission's detections (one per beam, detectSonarLog) written as point scans in the body frame,
// then localized (localizePointScans) as they are and in three forms a detector elsewhere may give:
// - "clutter": three beams in ten also list a false point at a random range along the beam;
// - "thick": each detection followed by every bin behind it for 3 % of the range (an echo
//   thresholded bin by bin);
// - "clutter x1": every beam lists a false point at a random range.
// Prints each run's ATE (aligned) beside dead reckoning's, and the loop closures accepted.
//
// Usage: sonarmap_point_scan_study [--seeds N]

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "sonarmap/eval/trajectory_error.hpp"
#include "sonarmap/mapping/detected_log.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"
#include "sonarmap/slam/point_scans.hpp"

namespace {

using namespace sonarmap;

MsisSimulation missionRun(const std::string& mission, const std::string& sonar, std::uint64_t seed) {
  SimulationArguments args;
  args.sonar = sonar;
  args.mission = mission;
  args.seed = seed;
  args.dvl_scale_error = 0.03;
  args.heading_bias_deg = 2.0;
  args.gyro_walk_deg_per_sqrt_s = 0.02;
  return simulateInMissionScene(mission, toSimulationOptions(args));
}

enum class Form { kAsDetected, kClutter, kThick, kClutterEveryBeam };

std::vector<BodyPoint> inForm(const std::vector<BodyPoint>& points, Form form, double range_m, double bin_m,
                              std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double clutter_share = form == Form::kClutter ? 0.3 : form == Form::kClutterEveryBeam ? 1.0 : 0.0;
  std::vector<BodyPoint> out;
  for (const BodyPoint& point : points) {
    out.push_back(point);
    const Eigen::Vector2d along = point.xy_m.normalized();
    if (form == Form::kThick) {
      for (double behind_m = bin_m; behind_m <= 0.03 * range_m; behind_m += bin_m) {
        out.push_back({point.scan, point.time_s, point.xy_m + along * behind_m});
      }
    }
    if (uniform(rng) < clutter_share) out.push_back({point.scan, point.time_s, along * range_m * uniform(rng)});
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t seeds = 3;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--seeds") == 0 && i + 1 < argc) {
      seeds = std::strtoull(argv[++i], nullptr, 10);
    } else {
      std::fprintf(stderr, "usage: %s [--seeds N]\n", argv[0]);
      return 2;
    }
  }
  std::printf("| sonar | mission | seed | DR ATE | as detected | clutter 0.3 | thick | clutter 1 |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const char* sonar : {"micron", "seaking-30", "ping360"}) {
    for (const char* mission : {"harbour-loop", "hull-loop"}) {
      for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
        const MsisSimulation run = missionRun(mission, sonar, seed);
        const DetectedLog detected = detectSonarLog(run.log, MapperOptions{});
        const std::vector<BodyPoint> points = pointScansOf(detected, defaultSonarToBody());
        const Beam& beam = run.log.beams.front();
        const double range_m = beam.bin_length_m * static_cast<double>(beam.intensities.size());
        std::printf("| %s | %s | %llu | %.3f m |", sonar, mission, static_cast<unsigned long long>(seed),
                    evaluateTrajectory(run.dead_reckoning, run.nav).ate_rmse_m);
        for (const Form form : {Form::kAsDetected, Form::kClutter, Form::kThick, Form::kClutterEveryBeam}) {
          const SlamResult slam = localizePointScans(inForm(points, form, range_m, beam.bin_length_m, seed), run.dead_reckoning);
          std::printf(" %.3f m (%zu) |", evaluateTrajectory(slam.trajectory, run.nav).ate_rmse_m,
                      slam.report.loopClosuresAccepted());
        }
        std::printf("\n");
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
