#pragma once
// `sonarmap live`: beams from a sonar as they arrive (serial, UDP, TCP, standard input) → an
// occupancy octree (.bt) rewritten atomically every few seconds and at the end of the stream.

#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "map_options.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap live`: the mapping options of `map` (MapArgs: input is the SOURCE) and
/// how the stream is read, mapped and written.
struct LiveArgs {
  MapArgs map;
  unsigned baud = 115200;      ///< serial devices: bits per second
  std::string show = "beam";        ///< beam (OnlineIntegration::kProvisionalBeams) | sweep (kSweep)
  double write_every_s = 10.0;     ///< seconds between map writes (> 0)
  double idle_timeout_s = 0.0;     ///< end the stream after this many seconds without a byte (0: never)
  std::string nav_stream;          ///< a second source of navigation CSV rows (empty: none)
};

/// Adds the `live` subcommand to `app`; its options fill `args`.
Command addLiveCommand(CLI::App& app, LiveArgs& args);

}  // namespace sonarmap::cli
