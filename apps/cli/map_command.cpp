#include "map_command.hpp"

#include "help_groups.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include "map_outputs.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/geotiff.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/slam/slam_mapping.hpp"
#include "navigation_input.hpp"
#include "origin_option.hpp"
#include "output_checks.hpp"
#include "reader_skips.hpp"
#include "slam_outputs.hpp"

namespace sonarmap::cli {
namespace {

/// --mounting and --trajectory place and follow a moving sonar: without navigation (or --slam)
/// they are usage errors.
void requireNavigation(const MapArgs& args, bool without_navigation) {
  if (!without_navigation || args.slam) return;
  if (!args.mounting.empty()) throw ValueError("--mounting needs --nav or --slam");
  if (!args.trajectory_out.empty()) throw ValueError("--trajectory needs --nav or --slam: a static log has no trajectory");
}

}  // namespace

Command addMapCommand(CLI::App& app, MapArgs& args) {
  CLI::App* cmd = app.add_subcommand("map", "Map a sonar log into an occupancy octree (.bt)");
  cmd->add_option("input", args.input, logInputHelp())->required();
  cmd->add_option("-o,--output", args.output_bt, "Output map: .bt (maximum likelihood) or .ot (log-odds)")
      ->required()
      ->group(help_group::kOutput);
  // MapArgs (map_options.hpp) has no field for the side view: it lives beside the checked options.
  struct Checked {
    MapperOptions options;
    Eigen::Isometry3d sonar_to_body;
    std::string side_png;
  };
  auto checked = std::make_shared<Checked>();
  cmd->add_option("--png", args.map_png, "Top view of the map (PNG, axes in metres)")->group(help_group::kOutput);
  cmd->add_option("--side-png", checked->side_png, "With --3d: side view of the map (PNG, along +y)")
      ->group(help_group::kOutput);
  cmd->add_option("--polar-png", args.polar_png, "Polar image of the largest sweep (PNG)")->group(help_group::kOutput);
  cmd->add_option("--cartesian-png", args.cartesian_png, "Cartesian image of the largest sweep (PNG, metres)")
      ->group(help_group::kOutput);
  addMappingOptions(*cmd, args);
  addLogInputOptions(*cmd, args.nav_file, args.log_read, args.nav_topic, args.nav_time_offset_s,
                     "Vehicle navigation: CSV, ROS log, .tlog, .BIN, or none");
  addMountingOption(*cmd, args.mounting, "With --nav: ");
  cmd->add_flag("--slam", args.slam, "Correct the navigation by matching the sonar's scans")
      ->group(help_group::kLocalization);
  addOdometryOptions(*cmd, args.odometry);
  addOriginOption(*cmd, args.origin);
  addGeoOriginOption(*cmd, args.geo_origin);
  cmd->add_option("--geotiff", args.geotiff, "The 2D map on the Earth as a GeoTIFF (UTM; needs a geodetic origin)")
      ->group(help_group::kOutput);
  cmd->add_flag("--mosaic", args.mosaic, "With --geotiff: the echo intensity as its second band")->group(help_group::kOutput);
  cmd->add_option("--trajectory", args.trajectory_out, "Write the trajectory mapped with (.csv, or TUM .tum/.txt)")
      ->group(help_group::kOutput);
  auto check = [&args, checked] {
    // A bag may hold its own navigation: known once it is read (requireNavigation).
    const std::optional<LogFormat> format = args.format == "auto" ? logFormatOfPath(args.input) : parseLogFormat(args.format);
    const bool bag = format && isRosLog(*format);
    if (!bag) requireNavigation(args, args.nav_file.empty() || args.nav_file == "none");
    if (!checked->side_png.empty() && !args.volume) {
      throw ValueError("--side-png draws a 3D map: give --3d (the planar map is one slice, see --png)");
    }
    checkOdometryArgs(args.odometry, args.slam);
    requireMapOutput(args.output_bt);
    requirePngOutput(args.map_png, "--png");
    requirePngOutput(checked->side_png, "--side-png");
    requirePngOutput(args.polar_png, "--polar-png");
    requirePngOutput(args.cartesian_png, "--cartesian-png");
    requireTrajectoryOutput(args.trajectory_out);
    requireGeoTiffOutput(args.geotiff, args.mosaic);
    checked->options = toMapperOptions(args);
    checked->sonar_to_body = toSonarToBody(args.mounting);
  };
  return {cmd, check,
          [&args, checked] { runMap(args, checked->options, checked->sonar_to_body, checked->side_png); }};
}

Eigen::Isometry3d toSonarToBody(const std::vector<double>& mounting) { return sonarToBodyOfMounting(mounting); }

namespace {

/// Maps the log, static (`nav` empty) or with navigation, drawing a progress bar unless args.quiet:
/// beam by beam from `source` (surveyed as `survey`); with args.slam, the log held whole in `whole`
/// localized first (slam_mapping.hpp) and `slam` receives the localization.
MappedLog mapLog(const MapArgs& args, BeamSource& source, const LogSurvey& survey, const SonarLog* whole,
                 const MapperOptions& options, const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body, SlamResult& slam) {
  if (args.slam) {
    return mapWithProgress(
        [&](const ProgressCallback& progress) {
          SlamMapping mapped =
              mapSonarLogWithSlam(*whole, nav, sonar_to_body, options, toSlamOptions(args.odometry, nav), progress);
          slam = std::move(mapped.slam);
          return std::move(mapped.mapper);
        },
        args.quiet);
  }
  if (nav.empty()) {
    return mapWithProgress([&](const ProgressCallback& progress) { return mapSonarLog(source, survey, options, progress); },
                           args.quiet);
  }
  return mapWithProgress(
      [&](const ProgressCallback& progress) { return mapSonarLog(source, survey, nav, sonar_to_body, options, progress); },
      args.quiet);
}

}  // namespace

std::string resolutionNote(const LogSurvey& survey, const MapperOptions& options) {
  if (options.resolution_m) return {};
  const AutoResolution chosen = autoResolutionForLog(survey, options);
  if (chosen.scales < 2 && !chosen.coarsened) return {};
  char note[160];
  std::snprintf(note, sizeof note, " (auto: the %.3g m range scale, %zu of %zu beams%s)", chosen.scale.reach_m,
                chosen.scale.beams, chosen.beams, chosen.coarsened ? ", coarsened to fit --max-voxel-updates-per-beam" : "");
  return note;
}


void runMap(const MapArgs& args, const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body,
            const std::string& side_png) {
  if (!args.geotiff.empty()) loadGeoTiffWriter();  // GDAL's plugin, loaded now: if it is missing, before the mapping
  const LogFormat format = inputFormat(args.input, args.format);
  // Read beam by beam, so that a log of hours maps in the memory of its map; --slam localizes on
  // the whole log (its scans are matched and the map rebuilt), so it holds it.
  std::optional<SonarLog> whole;
  std::unique_ptr<BeamSource> source;
  if (args.slam) {
    whole = readSonarLog(args.input, format, args.log_read);
    source = std::make_unique<LogBeamSource>(*whole);
  } else {
    source = openBeamSource(args.input, format, args.log_read);
  }
  const MapperOptions sonar_options = withSonarBeam(options, args, nominalBeam(format, source->header()));
  // The navigation needs only the log's clock; the survey then counts the beams within its span.
  std::optional<AlignedNavigation> navigation = navigationFor(args.input, format, source->header(), args.nav_file,
                                                                    args.nav_topic, args.nav_time_offset_s, args.log_read.msg_path);
  const BeamPass pass = passOver(*source);
  const LogSurvey survey = surveyLog(pass, surveyMinBeams(sonar_options), spanOf(navigation));
  printWarnings(optionWarnings(sonar_options, survey));
  requireNavigation(args, !navigation);
  const NavTrack no_nav;
  const NavTrack& nav = navigation ? navigation->source.track : no_nav;  // not copied: it grows with the log
  LocalOrigin origin;
  if (navigation) {
    printNavigationSource(*navigation, args.nav_file);
    requireClockOverlap(survey, source->header().clock_utc_s, *navigation);
    const double resolution_m = sonar_options.resolution_m ? *sonar_options.resolution_m
                                                           : autoResolutionForLog(survey, sonar_options).resolution_m;
    origin = moveTrackToOrigin(navigation->source.track, args.origin, resolution_m,
                               std::min(survey.reach_m, sonar_options.max_range_m));
    printOrigin(origin);
  } else if (!args.origin.empty()) {
    throw ValueError("--origin needs navigation (--nav): without it the map's zero is the sonar's");
  }
  const Eigen::Isometry3d mounting =
      mountingFor(args.input, format, source->header(), navigation, !args.mounting.empty(), sonar_to_body);
  SlamResult slam;
  MappedLog mapped = mapLog(args, *source, survey, whole ? &*whole : nullptr, sonar_options, nav, mounting, slam);
  mapped.resolution_note = resolutionNote(survey, sonar_options);
  const NavTrack& trajectory = args.slam ? slam.trajectory : nav;
  FileTransaction outputs;  // nothing appears unless every output could be written
  if (!args.trajectory_out.empty()) stageTrajectory(outputs, args.trajectory_out, inNavigationFrame(trajectory, origin));
  MapArgs shown = args;  // the images spread each beam over the sonar's width (its default when not given)
  shown.beam_width_deg = sonar_options.beam_width_rad * 180.0 / std::numbers::pi;
  shown.map_origin_ned_m = origin.ned_m;
  shown.mosaic_min_range_m = mapped.mapper.stats().calibration.min_range_highest_m;
  shown.map_geodetic_zero = mapGeodeticZero(navigation ? navigation->source.geodetic_origin : std::nullopt,
                                            args.geo_origin, origin);
  const std::string geo_from = !args.geo_origin.empty() ? "--geo-origin"
                               : navigation             ? navigation->source.geodetic_description
                                                        : std::string();
  if (!args.geotiff.empty() && !shown.map_geodetic_zero) {
    throw ValueError("--geotiff needs the map's place on the Earth: the log holds no latitude and longitude "
                     "(NavSatFix, GPS, GLOBAL_POSITION_INT) within its navigation's span; give --geo-origin LAT,LON");
  }
  stageMapOutputs(outputs, shown, *source, survey, mapped.mapper.map(), mapped.mapper.map().resolution_m(), side_png,
                  trajectory.empty() ? std::vector<Eigen::Vector3d>{Eigen::Vector3d::Zero()}
                                     : sonarTrack(trajectory, mounting, survey),
                  sonarPoseOn(trajectory, mounting));
  outputs.commit();
  std::vector<SkipReasonGroup> skip_reasons;
  addSkipReasons(skip_reasons, source->header().skip_reasons);
  mapped.skip_note =
      skipNote(mapped.mapper.stats().beams_skipped, skip_reasons, mapped.mapper.stats().out_of_map, args.input);
  const std::vector<std::string> warnings =
      mappingWarnings(mapped.mapper.stats(), mapped.mapper.options(), mapped.mapper.map().resolution_m());
  printWarnings(warnings);
  printGeodeticZero(shown.map_geodetic_zero, geo_from);
  printMapSummary(mapped, args, /*with_nav=*/!trajectory.empty(), warnings.size());
  if (args.slam) printSlamSummary(slam.report, !nav.empty());
  if (args.tank_report) printTankReport(mapped.mapper.map());
}

}  // namespace sonarmap::cli
