#pragma once
// `sonarmap map`: sonar log → occupancy octree (.bt) and images.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"

#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/nav/navigation.hpp"  // defaultSonarToBody

namespace sonarmap::cli {

/// Arguments of `sonarmap map` as typed by the user.
struct MapArgs {
  std::string input;
  std::string output_bt;
  std::string map_png;
  std::string polar_png;
  std::string cartesian_png;
  std::string resolution = "auto";  ///< metres, or "auto" (autoResolution_m of the log's reach)
  std::string detector = "background";
  std::string smoothing = "gaussian";
  std::string ray = "dda";
  std::string aggregation = "max";
  double self_reflection_m = 0.5;
  double max_range_m = 300.0;  ///< MapperOptions::max_range_m
  double beam_width_deg = 3.0;
  bool quiet = false;
  bool tank_report = false;
  std::string nav_csv;          ///< navigation CSV (empty: the sonar is static at the map origin)
  std::vector<double> mounting;  ///< X,Y,Z (m), ROLL,PITCH,YAW (degrees) of the sonar in the body; empty: default
};

/// Adds the `map` subcommand to `app`; its options fill `args`.
Command addMapCommand(CLI::App& app, MapArgs& args);

/// `text` as a number of metres > 0. @throws ValueError (usage) naming `option` otherwise.
double parseMetres(const std::string& text, const char* option);

/// Turns the arguments into mapper options. @throws ValueError for a bad name or value (usage).
MapperOptions toMapperOptions(const MapArgs& args);

/// The sonar's mounting from --mounting: sonar frame (beam.hpp) → body frame (FRD), translation
/// X,Y,Z in metres and rotation Rz(YAW)·Ry(PITCH)·Rx(ROLL) in degrees (navigation.hpp's Z-Y-X
/// convention). Empty: defaultSonarToBody(), upright and aligned (the same as 0,0,0,180,0,0).
/// @throws ValueError (usage) unless there are exactly six finite values.
Eigen::Isometry3d toSonarToBody(const std::vector<double>& mounting);

/// Reads, maps and writes. Prints the one-line summary on stdout. With args.nav_csv, each beam is
/// placed with the vehicle's pose at its time and `sonar_to_body`.
/// @throws sonarmap::Error (or std::exception) for bad data or a failed write.
void runMap(const MapArgs& args, const MapperOptions& options,
            const Eigen::Isometry3d& sonar_to_body = defaultSonarToBody());

}  // namespace sonarmap::cli
