#pragma once
/// @file point_text.hpp
/// Plain-text point files as OctoMap's examples use them (`scan.dat`; `../shared/docs/formats.md`):
/// one point per line, `x y z` in metres separated by spaces or tabs. Blank lines are skipped and
/// `#` starts a comment that runs to the end of the line. The frame is whatever the file's
/// producer used (OctoMap's examples: the sensor frame); nothing is transformed.

#include <istream>
#include <string>

#include "sonarmap/core/point_cloud.hpp"

namespace sonarmap {

/// Reads the points of a text point file, in file order. `nan` and `inf` are kept (a sensor's
/// "no return"): insertPointCloud skips and counts non-finite points.
/// @throws FileError (naming the file and the 1-based line number) when the file cannot be opened,
///         a line does not hold exactly 3 values, a value is not a number, or the file holds no
///         point at all.
PointCloud readPointText(const std::string& path);

/// Reads points from the rest of `in`. @param source name used in messages.
/// @throws FileError as readPointText(path).
PointCloud readPointText(std::istream& in, const std::string& source = "<stream>");

}  // namespace sonarmap
