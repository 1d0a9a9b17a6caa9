#pragma once
/// @file nav_input.hpp
/// Private to src/live: the vehicle's navigation as it streams in over a link (an autopilot's
/// MAVLink or navigation CSV rows, told apart by their bytes: formats/navigation_stream.hpp), as
/// fixes on the run's arrival clock.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

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
  /// Lines for the user not taken yet (the protocol found, the decoder's notes).
  std::vector<std::string> takeNotes() { return stream_.takeNotes(); }

  std::size_t skipped() const { return stream_.skipped(); }
  /// "MAVLink from system 1, ...", "navigation CSV rows".
  std::string protocol() const { return stream_.description(); }

 private:
  ByteLink link_;
  NavigationStream stream_;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace sonarmap::live
