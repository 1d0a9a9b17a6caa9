#pragma once
/// @file reader_support.hpp
/// Private to src/formats: what the binary sonar log readers share: a whole file read into memory
/// and the check of the options that turn head settings into metres and seconds.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sonarmap/formats/wire_stream.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap::detail {

/// The bytes of the file at `path`.
/// @throws FileError "cannot open 'PATH' for reading" or "PATH: reading failed".
std::vector<unsigned char> readFileBytes(const std::string& path);

/// @throws ValueError unless `sound_speed_m_s` is a positive finite number ("the sound speed is X
///   m/s, expected a positive finite number").
void checkSoundSpeed(double sound_speed_m_s);

/// @throws ValueError unless `beam_interval_s` is finite and ≥ 0.
void checkBeamInterval(double beam_interval_s);

/// Ends the reading of a capture without a clock: beam i gets time i × beam_interval_s.
/// @throws FileError "SOURCE: no beam in N bytes, expected EXPECTED (FIRST SKIP REASON)" when
///   `log` has no beam.
void finishClocklessCapture(SonarLog& log, std::size_t capture_bytes, const std::string& source,
                            std::string_view expected, double beam_interval_s);

/// @throws FileError as finishClocklessCapture when `log` has no beam.
void requireBeams(const SonarLog& log, std::size_t capture_bytes, const std::string& source, std::string_view expected);

/// A whole capture without a clock (raw SeaNet or Ping360 bytes, `format`) decoded as one stream
/// (WireStreamDecoder), its beams then timed by finishClocklessCapture; `expected` names what the
/// capture holds, for its messages.
/// @throws ValueError for an invalid sound speed or beam interval; FileError as
///         finishClocklessCapture.
SonarLog parseClocklessCapture(LogFormat format, std::span<const unsigned char> bytes, const std::string& source,
                               const CaptureOptions& options, std::string_view expected);

}  // namespace sonarmap::detail
