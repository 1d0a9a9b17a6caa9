#pragma once
/// @file ping_viewer_time.hpp
/// Private to src/formats: the time stamp of a Ping Viewer log record (ping360_reader.hpp).
///
/// Ping Viewer writes each record's time as QTime::toString("hh:mm:ss.zzz") of the time since
/// logging began, and Qt writes the digits of the recording computer's locale: ASCII on most
/// machines, Extended Arabic-Indic (U+06F0–U+06F9) on a Persian Windows (the shared
/// ping360_*.bin logs), Arabic-Indic, Devanagari, Bengali, Thai… elsewhere. A digit is any
/// character of Unicode's decimal-number category (ICU's u_charDigitValue), so every locale reads
/// alike.

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace sonarmap::detail {

/// Seconds of a record's time text: four runs of decimal digits (any script) split by single
/// separators, hours:minutes:seconds.milliseconds (hours of any length, minutes and seconds < 60,
/// three digits of milliseconds); format characters (bidirectional marks) are ignored; nullopt for
/// anything else.
/// @param bytes  the QString's bytes: UTF-16BE when `utf16`, else UTF-8 (decode_sensor_binary_log.py).
std::optional<double> pingViewerTime_s(std::span<const unsigned char> bytes, bool utf16);

/// The text of a QString's bytes as UTF-8 (for messages); invalid sequences become U+FFFD.
std::string pingViewerText(std::span<const unsigned char> bytes, bool utf16);

/// UTF-8 `text` with every decimal digit of any script written as its ASCII digit and every other
/// character but ASCII ones as '?' (a file name Qt wrote in the recording computer's digits).
std::string asciiDigits(std::string_view text);

}  // namespace sonarmap::detail
