#pragma once
/// @file log_reader.hpp
/// Opens a sonar log by its file extension, or in a format named by the caller (for a raw capture
/// of any file name).

#include <optional>
#include <string>
#include <string_view>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// The sonar log formats the library reads.
enum class LogFormat {
  kMat,      ///< "mat": CRAS Tritech Micron MATLAB 5 struct array (readCrasMat), `.mat`
  kCsv,      ///< "csv": beam CSV, one beam per row (readBeamCsv), `.csv`
  kV4Log,    ///< "v4log": Tritech SeaNet V4 log (readSeaNetV4Log), `.V4LOG`
  kSeaNet,   ///< "seanet": raw Tritech SeaNet wire capture (readSeaNetCapture), `.seanet`
  kPing360,  ///< "ping360": Ping Viewer log or raw Ping360 ping-protocol stream (readPing360), `.bin`
};

/// The format named `name`: "mat", "csv", "v4log", "seanet" or "ping360" (case-insensitive).
/// @throws ValueError for any other name, listing the names.
LogFormat parseLogFormat(std::string_view name);

/// The name parseLogFormat takes for `format` ("mat", "csv", "v4log", "seanet", "ping360").
std::string_view logFormatName(LogFormat format);

/// The format of a file by its extension, case-insensitive: `.mat`, `.csv`, `.v4log`, `.seanet`,
/// `.bin`; std::nullopt for any other.
std::optional<LogFormat> logFormatOfPath(const std::string& path);

/// Reads the beams of a sonar log in the format its extension names (logFormatOfPath), with each
/// reader's default options (V4LogOptions, CaptureOptions: 1500 m/s; raw captures have no clock,
/// so their beams are all at 0 s).
/// @throws FileError for an unknown extension (naming the extensions) or a file the format's
///   reader rejects.
SonarLog readSonarLog(const std::string& path);

/// Reads the beams of a sonar log in `format` whatever its file name, with the reader's default
/// options (e.g. `readSonarLog("capture.raw", parseLogFormat("seanet"))`).
/// @throws FileError for a file the format's reader rejects.
SonarLog readSonarLog(const std::string& path, LogFormat format);

}  // namespace sonarmap
