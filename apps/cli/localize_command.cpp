#include "localize_command.hpp"

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
      "Localize point scans detected elsewhere with the scan matcher, loop closures and pose graph of map --slam, and "
      "write the corrected trajectory");
  cmd->add_option("scans", args.scans,
                  "Point scans: a CSV with the header scan,time_s,x_m,y_m, one row per point: its scan (an integer, a "
                  "scan's rows together, in increasing number), when it was measured (s, the navigation's clock, never "
                  "decreasing) and where it lay in the vehicle's body frame then (m, x forward, y to starboard); gzipped or "
                  "not (.csv.gz)")
      ->required();
  cmd->add_option("--nav", args.nav,
                  "The dead reckoning the scans correct: a navigation CSV (time_s,x_m,y_m,z_m,roll_rad,pitch_rad,"
                  "yaw_rad; NED), a ROS log (.bag, .mcap, .db3), a BlueROV2 .tlog or .BIN; none (the default): the "
                  "vehicle believed still, its motion from the scans alone")
      ->capture_default_str();
  cmd->add_option("--nav-topic", args.nav_topic, "The navigation topic of a ROS log given to --nav");
  cmd->add_option("--trajectory", args.trajectory,
                  "Where to write the corrected trajectory: a navigation CSV, or TUM (time x y z qx qy qz qw, NED) when "
                  "the name ends in .tum or .txt")
      ->required();
  cmd->add_option("--range-sigma", args.range_sigma_m,
                  "1-sigma of a point's range along its line of sight, METRES > 0 (the sonar's range resolution)")
      ->capture_default_str();
  cmd->add_option("--bearing-sigma", args.bearing_sigma_deg,
                  "1-sigma of a point's bearing, DEGREES > 0 (half the horizontal beam width)")
      ->capture_default_str();
  addOdometryOptions(*cmd, args.odometry);
  addOriginOption(*cmd, args.origin);
  cmd->add_flag("-q,--quiet", args.quiet, "Print nothing on success");
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
