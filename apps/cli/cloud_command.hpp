#pragma once
// `sonarmap cloud`: point clouds (OctoMap scan graph or x y z text) → occupancy octree (.bt/.ot).

#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap cloud` as typed by the user.
struct CloudArgs {
  std::string input;
  std::string output;
  double resolution_m = 0.05;
  double max_range_m = -1.0;
  std::string origin;  ///< "X,Y,Z" in metres, for x y z text clouds
  bool discretize = false;
  unsigned threads = 1;  ///< threads tracing each scan's rays; the map is the same for any count
  bool quiet = false;
};

/// Adds the `cloud` subcommand to `app`; its options fill `args`.
Command addCloudCommand(CLI::App& app, CloudArgs& args);

}  // namespace sonarmap::cli
