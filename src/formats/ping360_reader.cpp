/// @file ping360_reader.cpp
/// readPing360 / parsePing360Stream: raw ping-protocol streams of a Ping360 → SonarLog (see
/// ping360_reader.hpp; Ping Viewer logs: ping_viewer_log.cpp).

#include "sonarmap/formats/ping360_reader.hpp"

#include <array>
#include <filesystem>
#include <fstream>

#include "sonarmap/formats/log_clock.hpp"
#include "sonarmap/formats/wire_stream.hpp"
#include "reader_support.hpp"

namespace sonarmap {

SonarLog parsePing360Stream(std::span<const unsigned char> bytes, const std::string& source,
                            const CaptureOptions& options) {
  return detail::parseClocklessCapture(LogFormat::kPing360, bytes, source, options,
                                       "Ping360 device_data messages ('B' 'R' ... checksum)");
}

SonarLog parsePing360(std::span<const unsigned char> bytes, const std::string& source, const CaptureOptions& options) {
  return isPingViewerLog(bytes) ? parsePingViewerLog(bytes, source, options) : parsePing360Stream(bytes, source, options);
}

bool isPingViewerLogFile(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  std::ifstream file(path, std::ios::binary);
  std::array<char, 64> start{};  // the header string: 4 + 2 × 26 bytes in UTF-16BE
  file.read(start.data(), start.size());
  const auto got = static_cast<std::size_t>(file.gcount());
  return isPingViewerLog(std::span(reinterpret_cast<const unsigned char*>(start.data()), got));
}

SonarLog readPing360(const std::string& path, const CaptureOptions& options) {
  const std::vector<unsigned char> bytes = detail::readFileBytes(path);
  SonarLog log = parsePing360(bytes, path, options);
  if (isPingViewerLog(bytes)) log.clock_utc_s = pingViewerNameTime_s(path);
  return log;
}

}  // namespace sonarmap
