/// @file reader_support.cpp
/// readFileBytes and the option checks of the binary sonar log readers (see reader_support.hpp).

#include "reader_support.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {

std::vector<unsigned char> readFileBytes(const std::string& path) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (error || !in) throw FileError("cannot open '" + path + "' for reading");
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (in.gcount() != static_cast<std::streamsize>(bytes.size())) throw FileError(path + ": reading failed");
  return bytes;
}

void checkSoundSpeed(double sound_speed_m_s) {
  if (std::isfinite(sound_speed_m_s) && sound_speed_m_s > 0.0) return;
  throw ValueError("the sound speed is " + std::to_string(sound_speed_m_s) +
                   " m/s, expected a positive finite number");
}

void checkBeamInterval(double beam_interval_s) {
  if (std::isfinite(beam_interval_s) && beam_interval_s >= 0.0) return;
  throw ValueError("the beam interval is " + std::to_string(beam_interval_s) +
                   " s, expected a finite number >= 0");
}

void requireBeams(const SonarLog& log, std::size_t capture_bytes, const std::string& source, std::string_view expected) {
  if (!log.beams.empty()) return;
  std::string message = source + ": no beam in " + std::to_string(capture_bytes) + " bytes, expected " + std::string(expected);
  if (!log.skip_reasons.empty()) {
    const std::string& first = log.skip_reasons.front();
    message += " (" + (first.starts_with(source + ": ") ? first.substr(source.size() + 2) : first) + ")";
  }
  throw FileError(message);
}

void finishClocklessCapture(SonarLog& log, std::size_t capture_bytes, const std::string& source,
                            std::string_view expected, double beam_interval_s) {
  requireBeams(log, capture_bytes, source, expected);
  for (std::size_t i = 0; i < log.beams.size(); ++i) log.beams[i].time_s = static_cast<double>(i) * beam_interval_s;
}

SonarLog parseClocklessCapture(LogFormat format, std::span<const unsigned char> bytes, const std::string& source,
                               const CaptureOptions& options, std::string_view expected) {
  checkSoundSpeed(options.sound_speed_m_s);
  checkBeamInterval(options.beam_interval_s);
  SonarLog log = WireStreamDecoder(format, options, source).decodeAll(bytes);
  finishClocklessCapture(log, bytes.size(), source, expected, options.beam_interval_s);
  return log;
}

}  // namespace sonarmap::detail
