#pragma once
/// @file frame_scanner.hpp
/// Private to src/formats: finds the frames (packets, messages) of a serial protocol in a raw
/// capture that may hold line noise between them, a frame cut by a pulled cable, or a false start
/// byte inside garbage. Shared by the SeaNet wire reader and the ping-protocol reader; the
/// protocol says, through a probe, whether a frame starts at a candidate offset.

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap::detail {

/// A protocol's verdict on the bytes at a candidate start.
struct FrameProbe {
  enum class Kind {
    kNotAFrame,  ///< the start bytes are not a frame's (bad length, no end marker, bad checksum…)
    kCutShort,   ///< a consistent header whose frame runs past the end of the bytes
    kFrame,      ///< a whole, checked frame of `size` bytes
  };
  Kind kind = Kind::kNotAFrame;
  std::size_t size = 0;  ///< bytes of the frame (kFrame)
  std::string reason;    ///< why it is not a frame, or what is cut short (for the skip line)
};

/// How frames are found and where their bytes are named.
struct FrameScan {
  std::string_view start;  ///< the bytes every frame begins with ("@", "BR")
  std::string_view noun;   ///< "packet", "message": used in skip lines
  /// The protocol's verdict on a candidate start at offset `at` (start bytes already matched).
  std::function<FrameProbe(std::size_t at)> probe;
  /// Called for every frame, in order: offset and size.
  std::function<void(std::size_t at, std::size_t size)> on_frame;
  /// How an offset is named in skip lines ("byte 120"); defaults to that form.
  std::function<std::string(std::size_t offset)> where;
};

/// Walks `bytes` from the start: each occurrence of `scan.start` is probed; a frame is handed to
/// `on_frame` and scanning resumes after it; anything else resumes one byte after the candidate.
/// Bytes outside every frame are gathered into runs, each appended to `log` as one skipped
/// item ("SOURCE: byte A to byte B: N bytes outside any packet (at byte X: REASON)", with the
/// reason of the first rejected candidate in the run, when there is one), counted in
/// `log.skipped_beams`. When the capture ends inside a frame (a consistent header whose frame runs
/// past the end, with no frame found after it), the bytes from its start are one item
/// "SOURCE: packet at byte X cut short: REASON" instead.
void scanFrames(std::span<const unsigned char> bytes, const FrameScan& scan, const std::string& source,
                SonarLog& log);

/// Appends one skipped item "SOURCE: WHAT" to `log` (skip_reasons and skipped_beams).
void addSkip(SonarLog& log, const std::string& source, const std::string& what);

}  // namespace sonarmap::detail
