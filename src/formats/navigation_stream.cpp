/// @file navigation_stream.cpp
/// NavigationStream: MAVLink or navigation CSV told by the first bytes (see navigation_stream.hpp).

#include "sonarmap/formats/navigation_stream.hpp"

#include <cmath>
#include <optional>
#include <utility>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kKeptBytes = 64 * 1024;
constexpr std::size_t kLongestLine = 4096;
/// Whether `line` (without its newline) is the navigation CSV's header (its first field time_s, as
/// NavCsvStream tells it) or one of its rows.
bool isCsvLine(std::string line) {
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
  std::string bare;
  for (const char c : line) {
    if (c != ' ' && c != '\t' && c != '\r') bare.push_back(c);
  }
  if (bare == "time_s" || bare.rfind("time_s,", 0) == 0) return true;
  NavCsvStream probe("probe");
  line.push_back('\n');
  return !probe.feed({reinterpret_cast<const std::uint8_t*>(line.data()), line.size()}).empty();
}

}  // namespace

struct NavigationStream::State {
  State(std::string source_name, const MavlinkNavigationOptions& options)
      : source(std::move(source_name)), mavlink_options(options) {}

  /// Looks at `bytes` for a checked MAVLink frame or a whole CSV line; the protocol once one is found.
  Protocol look(std::span<const std::uint8_t> bytes) {
    for (const MavlinkFrame& frame : probe.feed(bytes)) {
      if (frame.checked) return Protocol::kMavlink;
    }
    for (const std::uint8_t b : bytes) {
      if (b == '\n') {
        if (!line_too_long && isCsvLine(line)) return Protocol::kCsv;
        line.clear();
        line_too_long = false;
      } else if (line.size() < kLongestLine) {
        line.push_back(static_cast<char>(b));
      } else {
        line_too_long = true;
      }
    }
    return Protocol::kUndecided;
  }

  std::vector<NavSample> decode(std::span<const std::uint8_t> bytes, double arrival_s) {
    if (mavlink) return mavlink->feed(bytes, arrival_s);
    std::vector<NavSample> fixes = csv->feed(bytes);
    for (NavSample& fix : fixes) {
      if (!csv_offset_s) csv_offset_s = arrival_s - fix.time_s;
      fix.time_s += *csv_offset_s;
    }
    return fixes;
  }

  void decide(Protocol found) {
    protocol = found;
    if (found == Protocol::kMavlink) {
      mavlink.emplace(source, mavlink_options);
      notes.push_back(source + ": MAVLink (a frame with a matching checksum)");
    } else {
      csv.emplace(source);
      notes.push_back(source + ": navigation CSV rows");
    }
  }

  std::string source;
  MavlinkNavigationOptions mavlink_options;
  Protocol protocol = Protocol::kUndecided;
  std::vector<std::pair<double, std::vector<std::uint8_t>>> kept;  ///< chunks while undecided, with their arrivals
  std::size_t kept_bytes = 0;
  std::size_t dropped_bytes = 0;
  MavlinkFrameParser probe;
  std::string line;
  bool line_too_long = false;
  std::optional<MavlinkNavigation> mavlink;
  std::optional<NavCsvStream> csv;
  std::optional<double> csv_offset_s;
  std::size_t csv_skipped_seen = 0;
  std::vector<std::string> notes;
};

NavigationStream::NavigationStream(std::string source, const MavlinkNavigationOptions& mavlink) {
  MavlinkNavigation check(source, mavlink);  // the options' errors now, not at the first frame
  state_ = std::make_unique<State>(std::move(source), mavlink);
}

NavigationStream::~NavigationStream() = default;
NavigationStream::NavigationStream(NavigationStream&&) noexcept = default;
NavigationStream& NavigationStream::operator=(NavigationStream&&) noexcept = default;

std::vector<NavSample> NavigationStream::feed(std::span<const std::uint8_t> bytes, double arrival_s) {
  if (!std::isfinite(arrival_s)) throw ValueError("NavigationStream::feed: arrival time is not finite");
  State& s = *state_;
  if (s.protocol != Protocol::kUndecided) return s.decode(bytes, arrival_s);
  s.kept.emplace_back(arrival_s, std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  s.kept_bytes += bytes.size();
  const Protocol found = s.look(bytes);
  if (found == Protocol::kUndecided) {
    while (s.kept_bytes > kKeptBytes) {
      s.kept_bytes -= s.kept.front().second.size();
      s.dropped_bytes += s.kept.front().second.size();
      s.kept.erase(s.kept.begin());
    }
    return {};
  }
  s.decide(found);
  std::vector<NavSample> fixes;
  for (const auto& [kept_arrival_s, chunk] : std::exchange(s.kept, {})) {
    for (const NavSample& fix : s.decode(chunk, kept_arrival_s)) fixes.push_back(fix);
  }
  s.kept_bytes = 0;
  return fixes;
}

std::vector<NavSample> NavigationStream::finish() {
  State& s = *state_;
  return s.mavlink ? s.mavlink->finish() : std::vector<NavSample>{};
}

NavigationStream::Protocol NavigationStream::protocol() const { return state_->protocol; }

std::string NavigationStream::description() const {
  const State& s = *state_;
  if (s.mavlink) {
    const std::optional<MavlinkSender> vehicle = s.mavlink->vehicle();
    if (!vehicle) return "MAVLink (no ATTITUDE yet)";
    return "MAVLink from system " + std::to_string(vehicle->system) + ", component " +
           std::to_string(vehicle->component) + " (" + s.mavlink->description() + ")";
  }
  if (s.csv) return "navigation CSV rows";
  return "undecided (" + std::to_string(s.kept_bytes + s.dropped_bytes) +
         " bytes, neither a MAVLink frame nor a navigation CSV row yet)";
}

std::size_t NavigationStream::skipped() const {
  const State& s = *state_;
  if (s.mavlink) return s.mavlink->streamCounts().bad_frames + s.mavlink->attitudesWithoutFix();
  if (s.csv) return s.csv->skippedRows();
  return 0;
}

std::size_t NavigationStream::bytesDropped() const { return state_->dropped_bytes; }

std::vector<std::string> NavigationStream::takeNotes() {
  State& s = *state_;
  std::vector<std::string> notes = std::exchange(s.notes, {});
  if (s.mavlink) {
    for (std::string& note : s.mavlink->takeNotes()) notes.push_back(std::move(note));
  } else if (s.csv && s.csv->skippedRows() > s.csv_skipped_seen) {
    s.csv_skipped_seen = s.csv->skippedRows();
    notes.push_back(s.csv->lastSkipReason());
  }
  return notes;
}

}  // namespace sonarmap
