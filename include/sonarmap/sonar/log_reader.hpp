#pragma once
/// @file log_reader.hpp
/// Opens a sonar log by its file extension.

#include <string>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Reads the beams of a sonar log: `.mat` (CRAS Tritech Micron, MATLAB 5 struct array).
/// @throws FileError for an unknown extension or a file the format's reader rejects.
SonarLog readSonarLog(const std::string& path);

}  // namespace sonarmap
