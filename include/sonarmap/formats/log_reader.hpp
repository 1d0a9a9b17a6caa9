#pragma once
/// @file log_reader.hpp
/// Opens a sonar log by its file extension.

#include <string>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Reads the beams of a sonar log: `.mat` (CRAS Tritech Micron, MATLAB 5 struct array; readCrasMat),
/// `.csv` (beam CSV, one beam per row; readBeamCsv), `.V4LOG` (Tritech SeaNet V4 log; readSeaNetV4Log,
/// default V4LogOptions). Extensions are matched case-insensitively.
/// @throws FileError for an unknown extension or a file the format's reader rejects.
SonarLog readSonarLog(const std::string& path);

}  // namespace sonarmap
