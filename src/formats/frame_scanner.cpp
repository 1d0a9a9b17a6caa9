/// @file frame_scanner.cpp
/// FrameStream / scanFrames: frames of a serial protocol in a raw capture (see frame_scanner.hpp).

#include "frame_scanner.hpp"

#include <algorithm>

namespace sonarmap::detail {
namespace {

/// How many last bytes of `bytes` are a proper beginning of `start` (a start cut by the chunk's end).
std::size_t partialStartAtEnd(std::span<const unsigned char> bytes, std::string_view start) {
  for (std::size_t n = std::min(start.size() - 1, bytes.size()); n > 0; --n) {
    if (std::equal(bytes.end() - static_cast<std::ptrdiff_t>(n), bytes.end(), start.begin(),
                   [](unsigned char a, char b) { return a == static_cast<unsigned char>(b); })) {
      return n;
    }
  }
  return 0;
}

}  // namespace

void addSkip(SonarLog& log, const std::string& source, const std::string& what) {
  ++log.skipped_beams;
  log.skip_reasons.push_back(source + ": " + what);
}

FrameStream::FrameStream(FrameScan scan, std::string source, SonarLog& log)
    : scan_(std::move(scan)), source_(std::move(source)), log_(&log) {}

std::string FrameStream::where(std::size_t offset) const {
  return scan_.where ? scan_.where(offset) : "byte " + std::to_string(offset);
}

// Reports the run that ends at `end`; a frame cut short counts as such only at the capture's end
// (a frame found after it lies inside its declared extent: its header was false).
void FrameStream::flush(std::size_t end, bool at_capture_end) {
  if (!run_) return;
  const bool cut = at_capture_end && run_->cut_at;
  const std::size_t garbage_end = cut ? *run_->cut_at : end;
  if (garbage_end > run_->from) {
    std::string what = where(run_->from) + " to " + where(garbage_end - 1) + ": " +
                       std::to_string(garbage_end - run_->from) + " bytes outside any " + std::string(scan_.noun);
    if (!run_->first_reason.empty()) what += " (" + run_->first_reason + ")";
    addSkip(*log_, source_, what);
  }
  if (cut) addSkip(*log_, source_, std::string(scan_.noun) + " at " + where(*run_->cut_at) + " cut short: " + run_->cut_reason);
  run_.reset();
}

std::size_t FrameStream::scan(std::span<const unsigned char> bytes, bool at_end) {
  const auto outside = [&](std::size_t from, std::size_t to) {  // bytes [from, to) are in no frame
    if (from < to && !run_) run_ = GarbageRun{base_ + from, {}, std::nullopt, {}};
  };
  const auto* begin = bytes.data();
  const auto* end = bytes.data() + bytes.size();
  std::size_t position = 0;
  while (position < bytes.size()) {
    const auto* found = std::search(begin + position, end, scan_.start.begin(), scan_.start.end(),
                                    [](unsigned char a, char b) { return a == static_cast<unsigned char>(b); });
    const std::size_t at = static_cast<std::size_t>(found - begin);
    if (at >= bytes.size()) {
      // A start cut by the end of the capture (e.g. a lone 'B' as the last byte) is garbage too;
      // before the end, the next bytes may complete it.
      const std::size_t decided = bytes.size() - (at_end ? 0 : partialStartAtEnd(bytes.subspan(position), scan_.start));
      outside(position, decided);
      position = decided;
      break;
    }
    outside(position, at);
    const FrameProbe probe = scan_.probe(bytes.subspan(at), base_ + at);
    if (probe.kind == FrameProbe::Kind::kFrame) {
      flush(base_ + at, false);
      scan_.on_frame(bytes.subspan(at, probe.size), base_ + at);
      position = at + probe.size;
      continue;
    }
    if (probe.kind == FrameProbe::Kind::kCutShort && !at_end) {
      position = at;  // wait for the bytes that decide it
      break;
    }
    outside(at, at + 1);
    if (probe.kind == FrameProbe::Kind::kCutShort) {
      if (!run_->cut_at) {
        run_->cut_at = base_ + at;
        run_->cut_reason = probe.reason;
      }
    } else if (run_->first_reason.empty()) {
      run_->first_reason = "at " + where(base_ + at) + ": " + probe.reason;
    }
    position = at + 1;
  }
  if (at_end) flush(base_ + bytes.size(), true);
  return position;
}

void FrameStream::feed(std::span<const unsigned char> bytes) {
  if (finished_ || bytes.empty()) return;
  if (held_.empty()) {  // scan the caller's bytes in place: a whole file is not copied
    const std::size_t decided = scan(bytes, false);
    base_ += decided;
    held_.assign(bytes.begin() + static_cast<std::ptrdiff_t>(decided), bytes.end());
    return;
  }
  held_.insert(held_.end(), bytes.begin(), bytes.end());
  const std::size_t decided = scan(held_, false);
  base_ += decided;
  held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(decided));
}

void FrameStream::finish() {
  if (finished_) return;
  finished_ = true;
  base_ += scan(held_, true);
  held_.clear();
}

void scanFrames(std::span<const unsigned char> bytes, const FrameScan& scan, const std::string& source,
                SonarLog& log) {
  FrameStream stream(scan, source, log);
  stream.feed(bytes);
  stream.finish();
}

}  // namespace sonarmap::detail
