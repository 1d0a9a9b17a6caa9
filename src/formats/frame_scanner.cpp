/// @file frame_scanner.cpp
/// scanFrames: frames of a serial protocol in a raw capture (see frame_scanner.hpp).

#include "frame_scanner.hpp"

#include <algorithm>
#include <optional>

namespace sonarmap::detail {
namespace {

/// A run of bytes outside every frame, being gathered.
struct GarbageRun {
  std::size_t from = 0;
  std::string first_reason;  ///< the first rejected candidate's offset and reason
  std::optional<std::size_t> cut_at;  ///< a frame cut short by the end of the capture starts here
  std::string cut_reason;
};

}  // namespace

void addSkip(SonarLog& log, const std::string& source, const std::string& what) {
  ++log.skipped_beams;
  log.skip_reasons.push_back(source + ": " + what);
}

void scanFrames(std::span<const unsigned char> bytes, const FrameScan& scan, const std::string& source,
                SonarLog& log) {
  const auto where = [&](std::size_t offset) {
    return scan.where ? scan.where(offset) : "byte " + std::to_string(offset);
  };
  std::optional<GarbageRun> run;
  // Reports the run that ends at `end`; a frame cut short counts as such only at the capture's end
  // (a frame found after it lies inside its declared extent: its header was false).
  const auto flush = [&](std::size_t end, bool at_capture_end) {
    if (!run) return;
    const bool cut = at_capture_end && run->cut_at;
    const std::size_t garbage_end = cut ? *run->cut_at : end;
    if (garbage_end > run->from) {
      std::string what = where(run->from) + " to " + where(garbage_end - 1) + ": " +
                         std::to_string(garbage_end - run->from) + " bytes outside any " + std::string(scan.noun);
      if (!run->first_reason.empty()) what += " (" + run->first_reason + ")";
      addSkip(log, source, what);
    }
    if (cut) addSkip(log, source, std::string(scan.noun) + " at " + where(*run->cut_at) + " cut short: " + run->cut_reason);
    run.reset();
  };
  const auto outside = [&](std::size_t from, std::size_t to) {  // bytes [from, to) are in no frame
    if (from >= to) return;
    if (!run) run = GarbageRun{from, {}, std::nullopt, {}};
  };

  const auto* begin = bytes.data();
  const auto* end = bytes.data() + bytes.size();
  std::size_t position = 0;
  while (position < bytes.size()) {
    const auto* found = std::search(begin + position, end, scan.start.begin(), scan.start.end(),
                                    [](unsigned char a, char b) { return a == static_cast<unsigned char>(b); });
    // A start cut by the end of the capture (e.g. a lone 'B' as the last byte) is garbage too.
    const std::size_t at = static_cast<std::size_t>(found - begin);
    outside(position, at);
    if (at >= bytes.size()) break;
    const FrameProbe probe = scan.probe(at);
    if (probe.kind == FrameProbe::Kind::kFrame) {
      flush(at, false);
      scan.on_frame(at, probe.size);
      position = at + probe.size;
      continue;
    }
    outside(at, at + 1);
    if (probe.kind == FrameProbe::Kind::kCutShort) {
      if (!run->cut_at) {
        run->cut_at = at;
        run->cut_reason = probe.reason;
      }
    } else if (run->first_reason.empty()) {
      run->first_reason = "at " + where(at) + ": " + probe.reason;
    }
    position = at + 1;
  }
  flush(bytes.size(), true);
}

}  // namespace sonarmap::detail
