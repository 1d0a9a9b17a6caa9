#include "slam_outputs.hpp"

#include <cstdio>
#include <cstring>
#include <map>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/tum_trajectory.hpp"

namespace sonarmap::cli {

void stageTrajectory(FileTransaction& outputs, const std::string& path, const NavTrack& trajectory) {
  if (trajectory.empty()) throw ValueError("--trajectory: no trajectory to write (no scan could be localized)");
  const auto endsWith = [&path](const std::string& suffix) {
    return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (endsWith(".tum") || endsWith(".txt")) {
    outputs.stage(path, [&](std::ostream& out) { writeTumTrajectory(out, trajectory); });
  } else {
    outputs.stage(path, [&](std::ostream& out) { writeNavCsv(out, trajectory); });
  }
}

void printSlamSummary(const SlamReport& report, bool with_nav) {
  std::map<std::string, std::size_t> reasons;
  for (const LoopClosure& loop : report.loop_closures) {
    if (!loop.accepted) ++reasons[loop.reason];
  }
  std::string commonest;
  std::size_t most = 0;
  for (const auto& [reason, count] : reasons) {
    if (count > most) {
      most = count;
      commonest = reason;
    }
  }
  char scale[224] = "";
  if (with_nav && report.odometry_scale_observed) {
    std::snprintf(scale, sizeof scale, ", odometry scale %.4f ± %.4f", report.odometry_scale, report.odometry_scale_sigma);
  } else if (with_nav && !report.heading_only) {
    std::snprintf(scale, sizeof scale, ", odometry scale kept 1 (the scans do not constrain it)");
  }
  if (with_nav && report.heading_deviation_observed) {  // a compass's deviation, in degrees
    char deviation[112];
    std::snprintf(deviation, sizeof deviation, ", compass deviation %+.1f cos %+.1f sin of the heading (deg)",
                  report.heading_deviation_rad.x() * 180.0 / std::numbers::pi, report.heading_deviation_rad.y() * 180.0 / std::numbers::pi);
    std::strncat(scale, deviation, sizeof scale - std::strlen(scale) - 1);
  }
  char limits[96] = "";
  if (report.matches_beyond_limits > 0) {
    std::snprintf(limits, sizeof limits, " (%zu refused as faster than --max-speed or --max-turn-rate)",
                  report.matches_beyond_limits);
  }
  char echoes[96] = "";
  if (report.points_behind_echoes > 0) {
    std::snprintf(echoes, sizeof echoes, "; %zu points behind their echo's leading edge left out",
                  report.points_behind_echoes);
  }
  std::printf("slam: %zu scans (%zu with features%s), %zu matched to the scans before them%s, %zu of %zu loop closures "
              "accepted%s%s%s%s\n",
              report.scans, report.scans_with_points, echoes, report.matches_accepted, limits, report.loopClosuresAccepted(),
              report.loop_closures.size(), scale, most > 0 ? "; most refused as " : "", commonest.c_str(),
              !with_nav             ? " (no --nav: the motion comes from the scans alone, and the vehicle stays put "
                                      "between scans they cannot place)"
              : report.heading_only ? " (--nav gives the heading only: the position comes from the scans, and the "
                                      "vehicle keeps its last velocity between scans they cannot place)"
                                    : "");
}

}  // namespace sonarmap::cli
