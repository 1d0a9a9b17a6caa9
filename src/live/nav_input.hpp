#pragma once
/// @file nav_input.hpp
/// Private to src/live: the vehicle's navigation as it streams in over a link, as fixes on the
/// run's arrival clock.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

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
  /// since the run's start). Sets `ended` when the stream ended.
  std::vector<NavSample> read(double now_s, bool& ended);

  std::size_t skipped() const { return csv_.skippedRows(); }
  std::string lastSkipReason() const { return csv_.lastSkipReason(); }

 private:
  ByteLink link_;
  NavCsvStream csv_;
  std::optional<double> offset_s_;  ///< arrival clock − the stream's clock
  std::vector<std::uint8_t> buffer_;
};

}  // namespace sonarmap::live
