// `sonarmap live`'s options and their checks (see live_command.hpp); live_run.cpp runs it.

#include "live_command.hpp"

#include <memory>

#include "help_groups.hpp"
#include "live_run.hpp"
#include "map_command.hpp"
#include "odometry_options.hpp"
#include "origin_option.hpp"
#include "output_checks.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/live/live_page.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::cli {

Command addLiveCommand(CLI::App& app, LiveArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "live", "Drive a sonar head (Ping360, SeaNet) and map its beams as they arrive, or replay a log");
  cmd->add_option("source", args.map.input,
                  "Head's link (serial device, udp://HOST:PORT, udp://:PORT, tcp://HOST:PORT, -) or a log to replay")
      ->required();
  cmd->add_option("-o,--output", args.map.output_bt, "Output map (.bt or .ot), rewritten every --write-every")
      ->required()
      ->group(help_group::kOutput);
  addMappingOptions(*cmd, args.map);
  cmd->add_option("--baud", args.baud, "Serial devices: bits per second (8N1, raw)")
      ->capture_default_str()
      ->group(help_group::kInput);
  addHeadOptions(*cmd, args.head);
  cmd->add_option("--rate", args.rate, "A replayed log's pace: 1 its own, 2 twice as fast, 0 as fast as possible")
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--show", args.show,
                  "When a beam shows in the written map: beam | sweep | auto (sweep for a log replayed at --rate 0, else beam)")
      ->check(CLI::IsMember({"auto", "beam", "sweep"}))
      ->capture_default_str()
      ->group(help_group::kOutput);
  cmd->add_option("--write-every", args.write_every_s, "SECONDS between map writes (> 0)")
      ->capture_default_str()
      ->group(help_group::kOutput);
  cmd->add_option("--record", args.record, "Record the beams and navigation received (.mcap), for `map` and replays")
      ->group(help_group::kOutput);
  cmd->add_option("--serve", args.serve, "[HOST:]PORT: serve the page showing the map as it grows")
      ->group(help_group::kOutput);
  cmd->add_option("--idle-timeout", args.idle_timeout_s, "End after this many SECONDS without a byte (0: never)")
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd->add_option("--nav", args.map.nav_file, "Navigation CSV (times since the start) or a replayed log's")
      ->group(help_group::kNavigation);
  cmd->add_option("--nav-stream", args.nav_stream, "A link sending the vehicle's navigation: MAVLink or CSV rows")
      ->excludes("--nav")
      ->group(help_group::kNavigation);
  addMountingOption(*cmd, args.map.mounting, "With --nav or --nav-stream: ");
  cmd->add_flag("--slam", args.map.slam, "Correct the navigation by scan matching as sweeps complete")
      ->group(help_group::kLocalization);
  addOdometryOptions(*cmd, args.map.odometry);
  addOriginOption(*cmd, args.map.origin);
  addGeoOriginOption(*cmd, args.map.geo_origin);
  cmd->add_option("--geotiff", args.map.geotiff, "The 2D map on the Earth as a GeoTIFF, rewritten with the map")
      ->group(help_group::kOutput);
  cmd->add_option("--trajectory", args.map.trajectory_out, "With --slam: write the corrected trajectory (.csv, .tum)")
      ->group(help_group::kOutput);
  struct Checked {
    MapperOptions options;
    Eigen::Isometry3d sonar_to_body;
  };
  auto checked = std::make_shared<Checked>();
  auto check = [&args, checked] {
    const bool replay = isReplay(args);
    if (!replay && args.map.format != "seanet" && args.map.format != "ping360") {
      throw ValueError("live needs --format seanet or --format ping360 (a head's wire protocol), or a recorded ROS log "
                       "(.bag, .mcap, .db3, a rosbag2 folder) or Ping Viewer log (.bin), got '" + args.map.format + "'");
    }
    if (replay && !args.nav_stream.empty()) throw ValueError("a replayed log takes --nav, not --nav-stream");
    if (replay && anyHeadSetting(args.head)) throw ValueError("a replayed log has no head to set: --range, --gain, "
                                                              "--sector, --step and --frequency need a head's link");
    if (!replay && args.rate != 0.0) throw ValueError("--rate paces a replayed log; a head's link runs at its own pace");
    if (!(args.rate >= 0.0)) throw ValueError("--rate must be ≥ 0 (1: the log's own pace, 0: as fast as possible)");
    if (!(args.write_every_s > 0.0)) throw ValueError("--write-every must be > 0 seconds");
    checkOdometryArgs(args.map.odometry, args.map.slam);
    if (!(args.idle_timeout_s >= 0.0)) throw ValueError("--idle-timeout must be >= 0 seconds");
    if (!args.map.mounting.empty() && args.map.nav_file.empty() && args.nav_stream.empty() && !args.map.slam &&
        !replay) {
      throw ValueError("--mounting needs --nav, --nav-stream or --slam");
    }
    if (!args.map.trajectory_out.empty() && !args.map.slam) throw ValueError("live --trajectory needs --slam");
    requireMapOutput(args.map.output_bt);
    requireGeoTiffOutput(args.map.geotiff, false);
    requireTrajectoryOutput(args.map.trajectory_out);
    if (!args.record.empty() && !args.record.ends_with(".mcap")) {
      throw ValueError("--record writes an MCAP file: give a path ending in .mcap, got '" + args.record + "'");
    }
    (void)toHeadSettings(args.head);
    if (!args.serve.empty()) (void)webServerOptions(args.serve);
    checked->options = toMapperOptions(args.map);
    checked->sonar_to_body = toSonarToBody(args.map.mounting);
  };
  return {cmd, check, [&args, checked] { runLive(args, checked->options, checked->sonar_to_body); }};
}

}  // namespace sonarmap::cli
