#pragma once
/// @file map_file.hpp
/// Map files chosen by their extension: `.bt` (OctoMap binary, maximum likelihood;
/// octomap_binary.hpp) or `.ot` (OctoMap full tree, exact log-odds; octomap_full.hpp).
/// The extension is compared without regard to case.

#include <iosfwd>
#include <string>
#include <vector>

#include "sonarmap/io/octomap_header.hpp"

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

enum class MapFormat {
  kBinary,  ///< `.bt`
  kFull,    ///< `.ot`
};

/// Format of a map file named `path`, from its extension.
/// @throws FileError when the extension is neither `.bt` nor `.ot`.
MapFormat mapFormatOf(const std::string& path);

/// Writes `tree` to `path` atomically in the format its extension names, `comments` as header
/// comment lines (octomap_header.hpp; e.g. mapping/map_frame.hpp's frame line). The tree is not modified.
/// @throws FileError on an unknown extension or when the file cannot be written (an existing
///         file is then left untouched); ValueError for a comment holding a line break.
void writeMapFile(const OcTree16& tree, const std::string& path, const std::vector<std::string>& comments = {});

/// Writes `tree` to `out` in `format`, `comments` as header comment lines (as writeMapFile; for
/// a caller that stages the file itself, e.g. in a transaction).
/// @throws FileError when `out` fails; ValueError for a comment holding a line break.
void writeMap(const OcTree16& tree, std::ostream& out, MapFormat format, const std::vector<std::string>& comments = {});

/// The header of the map file `path` (its comments, resolution, node count), the data not read.
/// @throws FileError on an unknown extension, a file that cannot be opened, and as readOctomapHeader.
OctomapHeader readMapFileHeader(const std::string& path);

/// Reads the map file `path` in the format its extension names, with `options`.
/// @throws FileError on an unknown extension, and as readBinaryFile / readFullFile.
/// @throws ValueError on a resolution that is not finite and positive.
OcTree16 readMapFile(const std::string& path, const OctreeOptions& options = {});

}  // namespace sonarmap
