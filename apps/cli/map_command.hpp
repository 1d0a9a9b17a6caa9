#pragma once
// `sonarmap map`: sonar log → occupancy octree (.bt) and images.

#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"

#include "sonarmap/mapping/sonar_mapper.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap map` as typed by the user.
struct MapArgs {
  std::string input;
  std::string output_bt;
  std::string map_png;
  std::string polar_png;
  std::string cartesian_png;
  double resolution_m = 0.02;
  std::string detector = "background";
  std::string smoothing = "gaussian";
  std::string ray = "dda";
  std::string aggregation = "max";
  double self_reflection_m = 0.5;
  double beam_width_deg = 3.0;
  bool quiet = false;
  bool tank_report = false;
};

/// Adds the `map` subcommand to `app`; its options fill `args`.
Command addMapCommand(CLI::App& app, MapArgs& args);

/// Turns the arguments into mapper options. @throws ValueError for a bad name or value (usage).
MapperOptions toMapperOptions(const MapArgs& args);

/// Reads, maps and writes. Prints the one-line summary on stdout.
/// @throws sonarmap::Error (or std::exception) for bad data or a failed write.
void runMap(const MapArgs& args, const MapperOptions& options);

}  // namespace sonarmap::cli
