#pragma once
// What `map --slam` and `live --slam` write and say: the trajectory file and the localization's
// one-line summary.

#include <string>

#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/slam/localizer.hpp"

namespace sonarmap::cli {

/// Stages `trajectory` at `path`: TUM format (nav/tum_trajectory.hpp) when the name ends in .tum or
/// .txt, else a navigation CSV (writeNavCsv).
/// @throws ValueError when the trajectory is empty (nothing to write); FileError when it cannot be staged.
void stageTrajectory(FileTransaction& outputs, const std::string& path, const NavTrack& trajectory);

/// One line on stdout: scans, scans matched, loop closures accepted of those tried, and the
/// commonest reason a loop closure was refused.
void printSlamSummary(const SlamReport& report, bool with_nav);

}  // namespace sonarmap::cli
