#pragma once
// `sonarmap map`: sonar log → occupancy octree (.bt) and images.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "map_options.hpp"

#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/nav/navigation.hpp"  // defaultSonarToBody

namespace sonarmap::cli {

/// Adds the `map` subcommand to `app`; its options fill `args`.
Command addMapCommand(CLI::App& app, MapArgs& args);

/// The sonar's mounting from --mounting: sonar frame (beam.hpp) → body frame (FRD), translation
/// X,Y,Z in metres and rotation Rz(YAW)·Ry(PITCH)·Rx(ROLL) in degrees (navigation.hpp's Z-Y-X
/// convention). Empty: defaultSonarToBody(), upright and aligned (the same as 0,0,0,0,0,0).
/// @throws ValueError (usage) unless there are exactly six finite values.
Eigen::Isometry3d toSonarToBody(const std::vector<double>& mounting);

/// What the summary says after an automatic resolution (MappedLog::resolution_note): the range
/// scale it follows when the log has several, and whether it was coarsened to fit the budget;
/// empty for a resolution given by the user or a log of one scale.
std::string resolutionNote(const LogSurvey& survey, const MapperOptions& options);

/// Reads, maps and writes. Prints the warnings about the options and the mapping (mappingWarnings)
/// on stderr and the one-line summary on stdout. With navigation (args.nav_file, or the input bag's own), each beam is placed with the
/// vehicle's pose at its time and `sonar_to_body`. A non-empty `side_png` (--side-png) receives the
/// side view of the map (stageMapOutputs).
/// @throws sonarmap::Error (or std::exception) for bad data, a log beyond the work budget, a map no
///         beam fits in, or a failed write.
void runMap(const MapArgs& args, const MapperOptions& options,
            const Eigen::Isometry3d& sonar_to_body = defaultSonarToBody(), const std::string& side_png = {});

}  // namespace sonarmap::cli
