#include "localize_command.hpp"

#include "help_groups.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "origin_option.hpp"
#include "slam_outputs.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/navigation_reader.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/slam/point_scans.hpp"

namespace sonarmap::cli {

Command addLocalizeCommand(CLI::App& app, LocalizeArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "localize",
      "Correct a track by matching point scans detected elsewhere, as map --slam");
  cmd->add_option("scans", args.scans, "Point scans: CSV scan,time_s,x_m,y_m (body frame, m)")->required();
  cmd->add_option("--nav", args.nav, "Dead reckoning the scans correct: CSV, ROS log, .tlog, .BIN, or none")
      ->capture_default_str()
      ->group(help_group::kNavigation);
  cmd->add_option("--nav-topic", args.nav_topic, "Navigation topic of a ROS log given to --nav")
      ->group(help_group::kNavigation);
  cmd->add_option("--trajectory", args.trajectory, "Corrected trajectory to write (.csv, or TUM .tum/.txt)")
      ->required()
      ->group(help_group::kOutput);
  cmd->add_option("--range-sigma", args.range_sigma_m, "1-sigma of a point's range, METRES > 0")
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--bearing-sigma", args.bearing_sigma_deg, "1-sigma of a point's bearing, DEGREES > 0")
      ->capture_default_str()
      ->group(help_group::kInput);
  addOdometryOptions(*cmd, args.odometry);
  addOriginOption(*cmd, args.origin);
  cmd->add_flag("-q,--quiet", args.quiet, "Print nothing on success")->group(help_group::kOutput);
  auto check = [&args] {
    checkOdometryArgs(args.odometry, true);
    if (!(std::isfinite(args.range_sigma_m) && args.range_sigma_m > 0.0)) {
      throw ValueError("--range-sigma expects METRES > 0");
    }
    if (!(std::isfinite(args.bearing_sigma_deg) && args.bearing_sigma_deg > 0.0 && args.bearing_sigma_deg < 90.0)) {
      throw ValueError("--bearing-sigma expects DEGREES in (0, 90)");
    }
  };
  return {cmd, check, [&args] { runLocalize(args); }};
}

void runLocalize(const LocalizeArgs& args) {
  const std::vector<BodyPoint> points = readPointScansCsv(args.scans);
  NavTrack dead_reckoning;
  if (args.nav != "none") dead_reckoning = readNavigation(args.nav, args.nav_topic).track;
  // Positions far from zero (UTM) are localized about a local origin (map's rule at a resolution
  // of the points' range σ: beyond 32,767 σ), and written back in the navigation's coordinates;
  // with no octree to hold, any extent is localized.
  const LocalOrigin origin = chooseLocalOrigin(dead_reckoning, givenOrigin(args.origin), args.range_sigma_m, 0.0);
  moveToOrigin(dead_reckoning, origin.ned_m);
  PointScanOptions options;
  options.range_sigma_m = args.range_sigma_m;
  options.bearing_sigma_rad = args.bearing_sigma_deg * std::numbers::pi / 180.0;
  const SlamResult result = localizePointScans(points, dead_reckoning, options, toSlamOptions(args.odometry, dead_reckoning));
  FileTransaction outputs;
  stageTrajectory(outputs, args.trajectory, inNavigationFrame(result.trajectory, origin));
  outputs.commit();
  if (args.quiet) return;
  printOrigin(origin);
  printSlamSummary(result.report, !dead_reckoning.empty());
}

}  // namespace sonarmap::cli
