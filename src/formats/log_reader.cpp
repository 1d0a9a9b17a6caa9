#include "sonarmap/formats/log_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <numbers>
#include <utility>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/mat_reader.hpp"
#include "sonarmap/formats/ping360_reader.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"
#include "sonarmap/formats/seanet_capture.hpp"
#include "sonarmap/formats/v4log_reader.hpp"

namespace sonarmap {
namespace {

constexpr std::array<LogFormatEntry, 8> kFormats{{
    {LogFormat::kMat, "mat", ".mat", "CRAS Micron MATLAB struct array"},
    {LogFormat::kCsv, "csv", ".csv", "beam CSV, also .csv.gz"},
    {LogFormat::kV4Log, "v4log", ".V4LOG", "Tritech SeaNet V4 log"},
    {LogFormat::kSeaNet, "seanet", ".seanet", "SeaNet wire capture"},
    {LogFormat::kPing360, "ping360", ".bin", "Ping360: Ping Viewer log or raw stream"},
    {LogFormat::kRosBag, "rosbag", ".bag", "ROS 1 bag"},
    {LogFormat::kMcap, "mcap", ".mcap", "ROS 2 MCAP"},
    {LogFormat::kRosbag2, "rosbag2", ".db3", "ROS 2 rosbag2 SQLite, or its folder"}}};

/// A log read whole, served beam by beam.
class HeldLog final : public BeamSource {
 public:
  explicit HeldLog(SonarLog log) : log_(std::move(log)), beams_(log_) {}
  std::optional<Beam> next() override { return beams_.next(); }
  void rewind() override { beams_.rewind(); }
  const SonarLog& header() const override { return beams_.header(); }

 private:
  SonarLog log_;
  LogBeamSource beams_;
};

/// A ROS log's source with its clock: header stamps are seconds since 1970, UTC.
class RosLogSource final : public BeamSource {
 public:
  explicit RosLogSource(std::unique_ptr<BeamSource> source) : source_(std::move(source)) { update(); }
  std::optional<Beam> next() override {
    std::optional<Beam> beam = source_->next();
    if (!beam) update();  // the end of a pass: the skips are counted
    return beam;
  }
  void rewind() override { source_->rewind(); }
  const SonarLog& header() const override { return header_; }

 private:
  void update() {
    header_ = source_->header();
    header_.clock_utc_s = 0.0;
  }
  std::unique_ptr<BeamSource> source_;
  SonarLog header_;
};

RosBagOptions rosBagOptionsOf(const LogReadOptions& options) {
  return RosBagOptions{options.sonar_topic, parseBearingUnit(options.bearing_unit),
                       parseBearingDirection(options.bearing_direction), options.msg_path};
}

std::string lowerCase(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower;
}

}  // namespace

LogFormat parseLogFormat(std::string_view name) {
  const std::string lower = lowerCase(name);
  for (const LogFormatEntry& entry : kFormats) {
    if (entry.name == lower) return entry.format;
  }
  throw ValueError("unknown sonar log format '" + std::string(name) + "', expected " + logFormatNamesText(", "));
}

std::span<const LogFormatEntry> logFormats() { return kFormats; }

std::string logFormatNamesText(std::string_view separator) {
  std::string text;
  for (const LogFormatEntry& entry : kFormats) text += (text.empty() ? "" : std::string(separator)) + std::string(entry.name);
  return text;
}

std::string logFormatExtensionsText() {
  std::string text;
  for (const LogFormatEntry& entry : kFormats) {
    text += (text.empty() ? "" : ", ") + std::string(entry.extension) + " (" + std::string(entry.description) + ")";
  }
  return text;
}

NominalBeam nominalBeam(LogFormat format) {
  constexpr double kDegree = std::numbers::pi / 180.0;
  if (format == LogFormat::kPing360) return {2.0 * kDegree, 25.0 * kDegree};
  return {3.0 * kDegree, 35.0 * kDegree};
}

NominalBeam nominalBeam(LogFormat format, const SonarLog& header) {
  return header.nominal_beam.value_or(nominalBeam(format));
}

std::string_view logFormatName(LogFormat format) {
  for (const LogFormatEntry& entry : kFormats) {
    if (entry.format == format) return entry.name;
  }
  return "unknown";
}

std::string unknownLogTypeMessage(const std::string& path) {
  return "'" + path + "': unknown sonar log type '" + std::filesystem::path(path).extension().string() + "', expected " +
         logFormatExtensionsText() + ", or a format named (" + logFormatNamesText(", ") + ")";
}

std::optional<LogFormat> logFormatOfPath(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) return LogFormat::kRosbag2;  // a rosbag2 folder
  std::filesystem::path name(path);
  // A recording cut short (`live --record`'s NAME.mcap.part after a crash or a power cut): the
  // extension before ".part".
  if (lowerCase(name.extension().string()) == ".part") name = name.stem();
  std::string extension = lowerCase(name.extension().string());
  // A gzip-compressed beam CSV (io/text_input.hpp reads it): the extension before ".gz".
  if (extension == ".gz" && lowerCase(name.stem().extension().string()) == ".csv") extension = ".csv";
  for (const LogFormatEntry& entry : kFormats) {
    if (lowerCase(entry.extension) == extension) return entry.format;
  }
  return std::nullopt;
}

SonarLog readSonarLog(const std::string& path, LogFormat format, const LogReadOptions& options) {
  switch (format) {
    case LogFormat::kMat: return readCrasMat(path);
    case LogFormat::kCsv: return readBeamCsv(path);
    case LogFormat::kV4Log: return readSeaNetV4Log(path);
    case LogFormat::kSeaNet: return readSeaNetCapture(path);
    case LogFormat::kPing360: {
      SonarLog log = readPing360(path);
      if (log.clock_utc_s) *log.clock_utc_s -= options.utc_offset_s;  // the name's local time → UTC
      return log;
    }
    case LogFormat::kRosBag:
    case LogFormat::kMcap:  // the reader tells them apart by their first bytes
    case LogFormat::kRosbag2: {
      SonarLog log = readRosBag(path, rosBagOptionsOf(options));
      log.clock_utc_s = 0.0;  // header stamps: seconds since 1970
      return log;
    }
  }
  throw ValueError("unknown log format number " + std::to_string(static_cast<int>(format)));
}

std::unique_ptr<BeamSource> openBeamSource(const std::string& path, LogFormat format, const LogReadOptions& options) {
  if (format == LogFormat::kCsv) return openBeamCsv(path);
  if (isRosLog(format)) return std::make_unique<RosLogSource>(openRosBag(path, rosBagOptionsOf(options)));
  return std::make_unique<HeldLog>(readSonarLog(path, format, options));
}

SonarLog readSonarLog(const std::string& path) {
  const std::optional<LogFormat> format = logFormatOfPath(path);
  if (!format) throw FileError(unknownLogTypeMessage(path));
  return readSonarLog(path, *format);
}

}  // namespace sonarmap
