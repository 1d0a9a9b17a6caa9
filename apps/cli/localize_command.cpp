#include "localize_command.hpp"

#include "help_groups.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "origin_option.hpp"
#include "output_checks.hpp"
#include "slam_outputs.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/navigation_reader.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/render/point_figures.hpp"
#include "sonarmap/slam/point_scan_map.hpp"
#include "sonarmap/slam/point_scans.hpp"
#include "sonarmap/sonar/png_writer.hpp"

namespace sonarmap::cli {
namespace {

/// The panels of --png: the scans placed on the dead reckoning (when there is one) and on the
/// corrected track, each titled.
std::vector<PointPanel> localizePanels(const std::vector<SonarScan>& scans, const NavTrack& dead_reckoning,
                                       const SlamResult& result) {
  std::vector<PointPanel> panels;
  if (!dead_reckoning.empty()) {
    std::vector<Pose2> dead_reckoned;
    for (const SonarScan& scan : scans) dead_reckoned.push_back(scan.dead_reckoning);
    panels.push_back(pointPanel("the scans on the navigation (--nav)", placedScanPoints(scans, dead_reckoned), dead_reckoning));
  }
  char title[96];
  std::snprintf(title, sizeof title, "on the corrected track: %zu of %zu loop closures accepted",
                result.report.loopClosuresAccepted(), result.report.loop_closures.size());
  panels.push_back(pointPanel(title, placedScanPoints(scans, result.scan_poses), result.trajectory));
  return panels;
}

}  // namespace

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
  cmd->add_option("--map", args.map, "Map of the point scans placed on the corrected track (.bt or .ot, ENU)")
      ->group(help_group::kOutput);
  cmd->add_option("--png", args.png, "Picture of the point scans on the dead reckoning and on the corrected track")
      ->group(help_group::kOutput);
  CLI::Option* resolution =
      cmd->add_option("--resolution", args.resolution_m, "Voxel of --map and cell of --png, METRES > 0 (default: the points' typical sigma)")
          ->group(help_group::kOutput);
  addOdometryOptions(*cmd, args.odometry);
  addOriginOption(*cmd, args.origin);
  cmd->add_flag("-q,--quiet", args.quiet, "Print nothing on success")->group(help_group::kOutput);
  auto check = [&args, resolution] {
    checkOdometryArgs(args.odometry, true);
    if (!(std::isfinite(args.range_sigma_m) && args.range_sigma_m > 0.0)) {
      throw ValueError("--range-sigma expects METRES > 0");
    }
    if (!(std::isfinite(args.bearing_sigma_deg) && args.bearing_sigma_deg > 0.0 && args.bearing_sigma_deg < 90.0)) {
      throw ValueError("--bearing-sigma expects DEGREES in (0, 90)");
    }
    if (resolution->count() > 0 && !(std::isfinite(args.resolution_m) && args.resolution_m > 0.0)) {
      throw ValueError("--resolution expects METRES > 0");
    }
    requireTrajectoryOutput(args.trajectory);
    requireMapOutput(args.map, "--map");
    requirePngOutput(args.png, "--png");
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
  const SlamOptions slam = toSlamOptions(args.odometry, dead_reckoning);
  const SlamResult result = localizePointScans(points, dead_reckoning, options, slam);
  FileTransaction outputs;
  stageTrajectory(outputs, args.trajectory, inNavigationFrame(result.trajectory, origin));
  double resolution_m = args.resolution_m;
  double cell_m = 0.0;  // the picture's, coarser than resolution_m over a wide extent (pointFigureCell)
  if (!args.map.empty() || !args.png.empty()) {
    // The scans as the localizer formed them: each echo at its leading edge, in its scan's frame.
    const std::vector<SonarScan> scans =
        formPointScans(points, dead_reckoning, options, withNavigationPeriod(slam, dead_reckoning).forming);
    if (!(resolution_m > 0.0)) resolution_m = scanMapResolution(scans);
    if (!args.map.empty()) {
      const OcTree16 map = mapInFrame(mapScans(scans, result.scan_poses, resolution_m), kDefaultMapFrame);
      outputs.stage(args.map, [&](std::ostream& out) {
        writeMap(map, out, mapFormatOf(args.map), mapHeaderComments(kDefaultMapFrame, origin.ned_m));
      });
    }
    if (!args.png.empty()) {
      const std::vector<PointPanel> panels = localizePanels(scans, dead_reckoning, result);
      cell_m = pointFigureCell(panels, resolution_m);
      outputs.stageBytes(args.png, encodePng(pointPanelsFigure(panels, cell_m)));
    }
  }
  outputs.commit();
  if (args.quiet) return;
  printOrigin(origin);
  printSlamSummary(result.report, !dead_reckoning.empty());
  if (!args.map.empty()) {
    std::printf("map of the point scans on the corrected track: %.3g m voxels -> %s in %s\n", resolution_m, args.map.c_str(),
                mapFrameDescription(kDefaultMapFrame).c_str());
  }
  if (!args.png.empty()) std::printf("picture: %.3g m cells -> %s\n", cell_m, args.png.c_str());
}

}  // namespace sonarmap::cli
