#pragma once
/// @file log_reader.hpp
/// Opens a sonar log by its file extension, or in a format named by the caller (for a raw capture
/// of any file name).

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/beam_source.hpp"

namespace sonarmap {

/// The sonar log formats the library reads.
enum class LogFormat {
  kMat,      ///< "mat": CRAS Tritech Micron MATLAB 5 struct array (readCrasMat), `.mat`
  kCsv,      ///< "csv": beam CSV, one beam per row (readBeamCsv), `.csv`
  kV4Log,    ///< "v4log": Tritech SeaNet V4 log (readSeaNetV4Log), `.V4LOG`
  kSeaNet,   ///< "seanet": raw Tritech SeaNet wire capture (readSeaNetCapture), `.seanet`
  kPing360,  ///< "ping360": Ping Viewer log or raw Ping360 ping-protocol stream (readPing360), `.bin`
  kRosBag,   ///< "rosbag": ROS 1 bag, its sonar topic found by its fields (readRosBag), `.bag`
  kMcap,     ///< "mcap": ROS 2 log in MCAP, read as a ROS 1 bag is (readRosBag), `.mcap`
  kRosbag2,  ///< "rosbag2": ROS 2 log in rosbag2's SQLite storage (readRosBag): a folder, or `.db3`
};

/// Whether `format` is a ROS log (a ROS 1 bag or an MCAP file): topics, a sonar's and the
/// vehicle's navigation (ros_bag_navigation.hpp).
constexpr bool isRosLog(LogFormat format) {
  return format == LogFormat::kRosBag || format == LogFormat::kMcap || format == LogFormat::kRosbag2;
}

/// The format named `name`: "mat", "csv", "v4log", "seanet", "ping360", "rosbag", "mcap" or
/// "rosbag2" (case-insensitive).
/// @throws ValueError for any other name, listing the names.
LogFormat parseLogFormat(std::string_view name);

/// One format of the registry every list of formats is made from (errors, `map`'s and `info`'s help).
struct LogFormatEntry {
  LogFormat format;
  std::string_view name;         ///< parseLogFormat's name: "mat"
  std::string_view extension;    ///< the extension, as files usually spell it (".V4LOG"); matched in any case
  std::string_view description;  ///< what the files are: "Tritech SeaNet V4 log"
};

/// Every format the library reads, in one list: parseLogFormat, logFormatName and logFormatOfPath
/// read it, and so do the texts below.
std::span<const LogFormatEntry> logFormats();

/// The formats' names joined by `separator`: "mat, csv, v4log, …" or "mat | csv | …".
std::string logFormatNamesText(std::string_view separator);

/// The formats' extensions with their descriptions: ".mat (CRAS Micron MATLAB struct array), .csv
/// (beam CSV, also .csv.gz), …".
std::string logFormatExtensionsText();

/// The error for a log `path` whose extension names no format: the extension found, every
/// extension known (logFormatExtensionsText) and the format names.
std::string unknownLogTypeMessage(const std::string& path);

/// The name parseLogFormat takes for `format` ("mat", "csv", "v4log", "seanet", "ping360", "rosbag",
/// "mcap", "rosbag2").
std::string_view logFormatName(LogFormat format);

/// The format of a file by its extension, case-insensitive: `.mat`, `.csv` (and `.csv.gz`), `.v4log`, `.seanet`,
/// `.bin`, `.bag`, `.mcap`, `.db3`, and a folder (a rosbag2 log); a name ending in `.part` (a
/// recording cut short: `live --record`'s file before it is whole) by the extension before it;
/// std::nullopt for any other.
std::optional<LogFormat> logFormatOfPath(const std::string& path);

/// The nominal beam of the sonar that writes `format`: Blue Robotics Ping360 (ping360) 2° × 25°
/// (Ping360 datasheet); Tritech heads (mat: the CRAS Micron; v4log, seanet: SeaNet, whose Micron
/// and SeaKing DST are 3° wide, 35° and about 40° tall), the beam CSV and the ROS bag (no sonar
/// named) 3° × 35°, the Micron's and the mapper's defaults.
NominalBeam nominalBeam(LogFormat format);
/// The beam of the sonar of a log read in `format` whose header is `header`: the one it records
/// (SonarLog::nominal_beam), else nominalBeam(format).
NominalBeam nominalBeam(LogFormat format, const SonarLog& header);

/// Reads the beams of a sonar log in the format its extension names (logFormatOfPath), with each
/// reader's default options (V4LogOptions, CaptureOptions: 1500 m/s; raw captures have no clock,
/// so their beams are all at 0 s).
/// @throws FileError for an unknown extension (naming the extensions) or a file the format's
///   reader rejects.
SonarLog readSonarLog(const std::string& path);

/// What a caller may choose where a file holds more than one sonar.
struct LogReadOptions {
  /// A ROS bag's sonar topic (RosBagOptions::sonar_topic); empty: found by its fields. Other
  /// formats hold one sonar and ignore it.
  std::string sonar_topic{};
  /// A ROS bag's bearing unit: "auto", "deg", "rad" or "grad" (parseBearingUnit).
  std::string bearing_unit = "auto";
  /// A ROS bag's bearing direction seen from above: "cw" or "ccw" (parseBearingDirection).
  std::string bearing_direction = "cw";
  /// Seconds east of UTC of the recording computer's clock, for a log whose name gives its start in
  /// local time (a Ping Viewer log: SonarLog::clock_utc_s = the name's time − this); parseUtcOffset
  /// reads `+03:30`.
  double utc_offset_s = 0.0;
  /// A folder of `.msg` files for a rosbag2 SQLite log's types (RosBagOptions::msg_path).
  std::string msg_path{};
};

/// Reads the beams of a sonar log in `format` whatever its file name, with the reader's default
/// options but for `options` (e.g. `readSonarLog("capture.raw", parseLogFormat("seanet"))`).
/// @throws FileError for a file the format's reader rejects.
SonarLog readSonarLog(const std::string& path, LogFormat format, const LogReadOptions& options = {});

/// The beams readSonarLog(path, format, options) reads, one at a time (beam_source.hpp), with the
/// same header: a beam CSV (openBeamCsv) and the ROS logs (openRosBag) are read from the file as
/// the beams are asked for, so that a log of hours is read in the memory of a chunk; the other
/// formats (files of minutes) are read whole on opening.
/// @throws FileError as readSonarLog, on opening or (CSV, ROS logs) from next().
std::unique_ptr<BeamSource> openBeamSource(const std::string& path, LogFormat format, const LogReadOptions& options = {});

}  // namespace sonarmap
