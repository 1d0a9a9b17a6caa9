/// @file mavlink_navigation.cpp
/// MavlinkNavigation: bytes → frames (MavlinkFrameParser) → fixes on the boot clock
/// (MavlinkFixMaker) → the caller's clock, strictly increasing (see mavlink_navigation.hpp).

#include "sonarmap/formats/mavlink_navigation.hpp"

#include <cmath>

#include "sonarmap/core/errors.hpp"
#include "mavlink_fixes.hpp"
#include "vehicle_track.hpp"

namespace sonarmap {

struct MavlinkNavigation::State {
  State(std::string source_name, const MavlinkNavigationOptions& options)
      : source(std::move(source_name)), maker(options) {}

  /// The fixes made, on the arrival clock with the offset known now; those not after the last
  /// one given are dropped.
  std::vector<NavSample> timed() {
    std::vector<NavSample> fixes;
    fixes.reserve(made.size());
    for (detail::BootFix& f : made) {
      f.fix.time_s += maker.clockOffset_s(f.boot);
      if (!std::isfinite(f.fix.time_s) || (last_time_s && f.fix.time_s <= *last_time_s)) {
        ++clock_dropped;
        continue;
      }
      last_time_s = f.fix.time_s;
      fixes.push_back(f.fix);
    }
    made.clear();
    return fixes;
  }

  std::string source;
  MavlinkFrameParser parser;
  detail::MavlinkFixMaker maker;
  std::vector<MavlinkFrame> frames;
  std::vector<detail::BootFix> made;
  std::optional<double> last_time_s;
  std::size_t clock_dropped = 0;
  bool finished = false;
};

MavlinkNavigation::MavlinkNavigation(std::string source, const MavlinkNavigationOptions& options) {
  detail::checkVehicleLogOptions(options.pressure, "MavlinkNavigation");
  if (!std::isfinite(options.max_hold_s) || !(options.max_hold_s > 0.0)) {
    throw ValueError("MavlinkNavigation: max_hold_s is " + std::to_string(options.max_hold_s) +
                     ", expected a positive finite number of seconds");
  }
  state_ = std::make_unique<State>(std::move(source), options);
}

MavlinkNavigation::~MavlinkNavigation() = default;
MavlinkNavigation::MavlinkNavigation(MavlinkNavigation&&) noexcept = default;
MavlinkNavigation& MavlinkNavigation::operator=(MavlinkNavigation&&) noexcept = default;

std::vector<NavSample> MavlinkNavigation::feed(std::span<const std::uint8_t> bytes, double arrival_s) {
  if (!std::isfinite(arrival_s)) throw ValueError("MavlinkNavigation::feed: arrival time is not finite");
  State& s = *state_;
  s.frames.clear();
  s.parser.feed(bytes, s.frames);
  if (s.finished) return {};
  for (const MavlinkFrame& frame : s.frames) s.maker.take(frame, arrival_s, s.made);
  return s.timed();
}

std::vector<NavSample> MavlinkNavigation::feedFrame(const MavlinkFrame& frame, double arrival_s) {
  if (!std::isfinite(arrival_s)) throw ValueError("MavlinkNavigation::feedFrame: arrival time is not finite");
  State& s = *state_;
  if (s.finished) return {};
  s.maker.take(frame, arrival_s, s.made);
  return s.timed();
}

std::vector<NavSample> MavlinkNavigation::finish() {
  State& s = *state_;
  if (s.finished) return {};
  s.finished = true;
  s.maker.finish(s.made);
  return s.timed();
}

const MavlinkStreamCounts& MavlinkNavigation::streamCounts() const { return state_->parser.counts(); }

std::size_t MavlinkNavigation::attitudesWithoutFix() const {
  return state_->maker.attitudesWithoutFix() + state_->clock_dropped;
}

std::optional<MavlinkSender> MavlinkNavigation::vehicle() const { return state_->maker.vehicle(); }

std::string MavlinkNavigation::description() const { return state_->maker.description(); }

std::vector<std::string> MavlinkNavigation::takeNotes() {
  std::vector<std::string> notes = state_->maker.takeNotes();
  for (std::string& note : notes) note = state_->source + ": " + note;
  return notes;
}

}  // namespace sonarmap
