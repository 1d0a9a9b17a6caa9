/// @file nav_input.cpp
/// Streamed navigation (see nav_input.hpp).

#include "nav_input.hpp"

#include "sonarmap/formats/mavlink_messages.hpp"

namespace sonarmap::live {

NavInput::NavInput(const std::string& spec, unsigned baud)
    : link_(spec, baud), stream_(link_.description()), buffer_(65536), send_heartbeats_(link_.networkClient()) {}

void NavInput::poll(double now_s) {
  if (!send_heartbeats_ || now_s - last_heartbeat_s_ < kHeartbeatPeriod_s) return;
  if (stream_.protocol() == NavigationStream::Protocol::kCsv) return;  // a CSV sender is not a MAVLink router
  MavlinkHeartbeat heartbeat;
  heartbeat.type = 18;          // MAV_TYPE_ONBOARD_CONTROLLER
  heartbeat.autopilot = 8;      // MAV_AUTOPILOT_INVALID
  heartbeat.system_status = 4;  // MAV_STATE_ACTIVE
  last_heartbeat_s_ = now_s;
  if (link_.write(encodeMavlink(heartbeat_encoder_, toMavlinkPayload(heartbeat)))) ++heartbeats_sent_;
}

std::vector<NavSample> NavInput::read(double now_s, bool& ended) {
  ended = false;
  const long got = link_.read(buffer_);
  if (got == 0) {
    ended = true;
    return stream_.finish();
  }
  if (got < 0) return {};
  return stream_.feed(std::span(buffer_.data(), static_cast<std::size_t>(got)), now_s);
}

}  // namespace sonarmap::live
