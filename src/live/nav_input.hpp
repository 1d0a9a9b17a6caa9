#pragma once
/// @file nav_input.hpp
/// Private to src/live: the vehicle's navigation as it streams in over a link (an autopilot's
/// MAVLink or navigation CSV rows, told apart by their bytes: formats/navigation_stream.hpp), as
/// fixes on the run's arrival clock. On a link to a server (udp://HOST:PORT, tcp://HOST:PORT) it
/// sends a MAVLink HEARTBEAT every second, as QGroundControl and Ping Viewer do: BlueOS's MAVLink
/// "UDP Server" endpoints (14550, 14660) send only to clients they have heard from.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sonarmap/formats/mavlink.hpp"
#include "sonarmap/formats/navigation_stream.hpp"
#include "sonarmap/live/byte_link.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::live {

class NavInput {
 public:
  /// @throws as ByteLink.
  NavInput(const std::string& spec, unsigned baud);

  int fd() const { return link_.fd(); }
  const std::string& description() const { return link_.description(); }
  /// Reads what the link has: the fixes it completes, their times on the arrival clock (seconds
  /// since the run's start, `now_s` being the arrival of these bytes). Sets `ended` when the
  /// stream ended (its last fixes are then returned too).
  std::vector<NavSample> read(double now_s, bool& ended);
  /// On a link to a server, while the stream is MAVLink or undecided: a HEARTBEAT when the last
  /// was kHeartbeatPeriod_s ago or more (the first at once). The heartbeat is a companion
  /// computer's (system 1, component 191 MAV_COMP_ID_ONBOARD_COMPUTER, type 18
  /// MAV_TYPE_ONBOARD_CONTROLLER, autopilot 8 MAV_AUTOPILOT_INVALID: MAVLink's heartbeat
  /// microservice), not a ground station's (system 255 is what ArduSub's GCS failsafe watches).
  /// A link that refuses it (nothing there yet) is tried again a period later.
  /// @throws FileError on a link error.
  void poll(double now_s);
  std::size_t heartbeatsSent() const { return heartbeats_sent_; }
  static constexpr double kHeartbeatPeriod_s = 1.0;
  /// Lines for the user not taken yet (the protocol found, the decoder's notes).
  std::vector<std::string> takeNotes() { return stream_.takeNotes(); }

  std::size_t skipped() const { return stream_.skipped(); }
  /// "MAVLink from system 1, ...", "navigation CSV rows".
  std::string protocol() const { return stream_.description(); }

 private:
  ByteLink link_;
  NavigationStream stream_;
  std::vector<std::uint8_t> buffer_;
  MavlinkEncoder heartbeat_encoder_{1, 191};
  bool send_heartbeats_ = false;
  double last_heartbeat_s_ = -1e300;
  std::size_t heartbeats_sent_ = 0;
};

}  // namespace sonarmap::live
