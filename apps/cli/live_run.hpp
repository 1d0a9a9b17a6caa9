#pragma once
// Running `sonarmap live` once its options are checked: the live session (live/live_session.hpp)
// built from them, its progress on stderr, its map, trajectory and summary at the end.

#include <Eigen/Geometry>

#include "live_command.hpp"
#include "sonarmap/mapping/mapper_options.hpp"

namespace sonarmap::cli {

/// Whether `live` replays a recorded log beam by beam with its own clock, read as `map` reads it,
/// rather than reading a head's wire stream: a ROS log (by --format, or the source's name) or a
/// Ping Viewer log file (by its header).
bool isReplay(const LiveArgs& args);

/// Runs `live`: until the stream ends, --idle-timeout, or SIGINT/SIGTERM (the map and the
/// recording are then written whole and the head told to stop).
/// @throws FileError when nothing was received, when no beam met the navigation, or a link or an
///         output fails; ValueError for settings the head cannot take.
void runLive(const LiveArgs& args, const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body);

}  // namespace sonarmap::cli
