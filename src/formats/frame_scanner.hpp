#pragma once
/// @file frame_scanner.hpp
/// Private to src/formats: finds the frames (packets, messages) of a serial protocol in a raw
/// capture that may hold line noise between them, a frame cut by a pulled cable, or a false start
/// byte inside garbage. Shared by the SeaNet wire reader and the ping-protocol reader, whole files
/// and live streams alike (FrameStream: bytes fed in any chunks give the frames and skip lines of
/// the whole buffer); the protocol says, through a probe, whether a frame starts at a candidate.

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

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
  /// The protocol's verdict on a candidate start (start bytes already matched): `bytes` from the
  /// candidate's first byte to the last byte received so far, `at` its offset in the stream (for
  /// messages). kCutShort must mean "more bytes could decide": the verdict on a prefix of the
  /// bytes is kCutShort or the verdict on all of them.
  std::function<FrameProbe(std::span<const unsigned char> bytes, std::size_t at)> probe;
  /// Called for every frame, in order: its bytes and its offset in the stream.
  std::function<void(std::span<const unsigned char> frame, std::size_t at)> on_frame;
  /// How an offset is named in skip lines ("byte 120"); defaults to that form.
  std::function<std::string(std::size_t offset)> where;
};

/// Frames of a stream fed in chunks of any size, with the verdicts of scanFrames on the whole
/// stream: a candidate whose probe is kCutShort is held (with the bytes after it) until more bytes
/// decide it or finish() says the stream ended; a trailing part of `start` is held likewise. Holds
/// at most one frame's bytes (the protocol's largest) beyond what it has decided.
class FrameStream {
 public:
  /// Skipped items are appended to `log` (which must outlive the stream), named with `source`.
  FrameStream(FrameScan scan, std::string source, SonarLog& log);
  /// Scans `bytes`, the stream's next bytes: frames complete within them go to scan.on_frame.
  void feed(std::span<const unsigned char> bytes);
  /// The end of the stream: the held bytes are scanned as the end of a capture (a frame cut short,
  /// the last garbage run). Further calls do nothing.
  void finish();
  /// Bytes fed so far.
  std::size_t bytesFed() const { return base_ + held_.size(); }

 private:
  struct GarbageRun {
    std::size_t from = 0;
    std::string first_reason;           ///< the first rejected candidate's offset and reason
    std::optional<std::size_t> cut_at;  ///< a frame cut short by the end of the capture starts here
    std::string cut_reason;
  };
  /// Scans `bytes` (stream offset base_): returns how many leading bytes are decided.
  std::size_t scan(std::span<const unsigned char> bytes, bool at_end);
  std::string where(std::size_t offset) const;
  void flush(std::size_t end, bool at_capture_end);

  FrameScan scan_;
  std::string source_;
  SonarLog* log_;
  std::vector<unsigned char> held_;  ///< bytes from offset base_ not decided yet
  std::size_t base_ = 0;
  std::optional<GarbageRun> run_;
  bool finished_ = false;
};

/// Walks `bytes` from the start (a FrameStream fed `bytes` at once, then finished): each occurrence of `scan.start` is probed; a frame is handed to
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
