#pragma once
// `sonarmap live`: a sonar head driven (Ping360, Tritech SeaNet) or listened to over a serial line,
// UDP or TCP, or a recorded log replayed, the vehicle's navigation streamed (MAVLink or CSV rows),
// the beams mapped as they arrive into an occupancy octree rewritten every few seconds, what was
// received recorded, and the map shown growing on a page (--serve).

#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "head_options.hpp"
#include "map_options.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap live`: the mapping options of `map` (MapArgs: input is the SOURCE), the
/// head's settings and how the stream is read, mapped, recorded, served and written.
struct LiveArgs {
  MapArgs map;
  HeadArgs head;
  unsigned baud = 115200;       ///< serial devices: bits per second
  /// beam (OnlineIntegration::kProvisionalBeams) | sweep (kSweep) | auto: sweep for a log replayed as
  /// fast as possible (no one watches it beam by beam), beam otherwise.
  std::string show = "auto";
  double write_every_s = 10.0;  ///< seconds between map writes (> 0)
  double idle_timeout_s = 0.0;  ///< end the stream after this many seconds without a byte (0: never)
  std::string nav_stream;       ///< a second link sending navigation: MAVLink or CSV rows (empty: none)
  std::string record;           ///< --record: the received beams and fixes as an MCAP file (empty: none)
  double rate = 0.0;            ///< --rate: a replayed log's pace (1: its own; 0: as fast as possible)
  std::string serve;            ///< --serve [HOST:]PORT: the page showing the map (empty: none)
};

/// Adds the `live` subcommand to `app`; its options fill `args`.
Command addLiveCommand(CLI::App& app, LiveArgs& args);

}  // namespace sonarmap::cli
