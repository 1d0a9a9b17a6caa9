#pragma once
/// @file octomap_header.hpp
/// The ASCII header shared by OctoMap's `.bt` and `.ot` files (`../shared/docs/formats.md`):
/// a fixed first line, `#` comment lines, then `id`, `size`, `res` in any order and `data`.

#include <cstddef>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace sonarmap {

/// First line of a `.bt` file.
inline constexpr const char* kBinaryFileFirstLine = "# Octomap OcTree binary file";
/// First line of a `.ot` file.
inline constexpr const char* kFullFileFirstLine = "# Octomap OcTree file";

struct OctomapHeader {
  std::string id;          ///< tree type, `OcTree` for occupancy trees
  std::size_t size = 0;    ///< number of nodes in the tree
  double resolution_m = 0; ///< finest voxel edge in metres
  /// Comment lines after the first line, without their leading "# " (written after OctoMap's
  /// fixed comment; read: every `#` line but the first, in order). OctoMap's reader skips them.
  std::vector<std::string> comments;
};

/// Writes the header lines up to and including `data`, `header.comments` each as a "# " line.
/// @throws ValueError when a comment holds a line break (it would end the comment).
void writeOctomapHeader(std::ostream& out, const std::string& first_line, const OctomapHeader& header);

/// Reads the header up to and including the `data` line; the stream is left at the first data byte.
/// @param source file name for messages.
/// @throws FileError when the first line differs, a line is unknown, a value does not parse or
///         is followed by more text (`res 0.1m`), `size` is negative, `id`/`size`/`res` is
///         missing, or the stream ends before `data`. Messages start with `source`; header text
///         quoted in them is escaped (non-printable bytes as \xNN) and cut at 64 bytes.
/// @throws ValueError when the resolution is not finite and positive (checked once the header is
///         complete, so a header cut short inside the `res` line is a FileError).
OctomapHeader readOctomapHeader(std::istream& in, const std::string& first_line, const std::string& source);

}  // namespace sonarmap
