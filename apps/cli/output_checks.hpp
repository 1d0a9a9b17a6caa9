#pragma once
// Output paths checked before any work: a file whose extension says another format than the one
// written (`-o map.png` for an octree) is refused in one line, and nothing is written.

#include <initializer_list>
#include <string>
#include <string_view>

namespace sonarmap::cli {

/// Checks that `path` ends in one of `extensions` (with the dot, any case). Nothing is checked for
/// an empty path (the output not asked for).
/// @throws ValueError "OPTION 'PATH': WHAT, not '.EXT'" otherwise, e.g. "-o 'x.png': the map is
///         an OctoMap file, .bt (binary tree) or .ot (full tree), not '.png'".
void requireOutputExtension(const std::string& path, std::initializer_list<std::string_view> extensions,
                            std::string_view option, std::string_view what);

/// requireOutputExtension for a map written with writeMapFile: .bt or .ot.
void requireMapOutput(const std::string& path, std::string_view option = "-o");

/// requireOutputExtension for a trajectory (stageTrajectory): .csv (navigation CSV), .tum or .txt (TUM).
void requireTrajectoryOutput(const std::string& path, std::string_view option = "--trajectory");

/// requireOutputExtension for a PNG picture.
void requirePngOutput(const std::string& path, std::string_view option);

/// requireOutputExtension for --geotiff (.tif or .tiff); ValueError for --mosaic without it.
void requireGeoTiffOutput(const std::string& path, bool mosaic);

}  // namespace sonarmap::cli
