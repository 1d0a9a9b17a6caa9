#pragma once
/// @file navigation_stream.hpp
/// A navigation stream of either kind `sonarmap live --nav-stream` takes, told by its bytes: an
/// autopilot's MAVLink (mavlink_navigation.hpp) or navigation CSV rows (NavCsvStream,
/// nav/navigation.hpp). Every fix comes out on the caller's arrival clock.
///
/// **Telling them apart.** Until it knows, the stream keeps what arrives (up to 64 KiB; older bytes
/// beyond that are dropped and counted) and decides at the first of: a MAVLink frame of a known
/// message whose checksum matches (MAVLink: CSV text, ASCII or UTF-8, never holds the bytes 0xFD or
/// 0xFE that start a frame), or a whole line that is the CSV header or a row of seven numbers
/// (CSV). Bytes before either (a serial line's noise, a half line) are then read as that protocol
/// reads noise: skipped and counted. The bytes kept are then decoded with the arrival times they
/// came at.
///
/// **Clocks.** MAVLink fixes are put on the arrival clock by MavlinkNavigation (the autopilot's
/// boot time plus the least delay). CSV rows carry the sender's own clock: they are moved by one
/// constant, the first fix's arrival minus its time, so the first fix is at its arrival.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/formats/mavlink_navigation.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

class NavigationStream {
 public:
  enum class Protocol { kUndecided, kMavlink, kCsv };

  /// @param source   names the stream in notes and skip reasons ("udp://0.0.0.0:14550").
  /// @param mavlink  the options of the MAVLink decoder, if the stream turns out to be MAVLink.
  /// @throws ValueError as MavlinkNavigation for invalid options.
  explicit NavigationStream(std::string source, const MavlinkNavigationOptions& mavlink = {});
  ~NavigationStream();
  NavigationStream(NavigationStream&&) noexcept;
  NavigationStream& operator=(NavigationStream&&) noexcept;

  /// The stream's next bytes, received at `arrival_s` (seconds, the caller's clock). Returns the
  /// fixes they complete, on that clock, strictly increasing across calls. Never throws for any
  /// bytes (only std::bad_alloc). @throws ValueError when arrival_s is not finite.
  std::vector<NavSample> feed(std::span<const std::uint8_t> bytes, double arrival_s);
  /// The end of the stream (MavlinkNavigation::finish for MAVLink; nothing for CSV).
  std::vector<NavSample> finish();

  Protocol protocol() const;
  /// "MAVLink from system 1, component 1 (attitude ATTITUDE, position LOCAL_POSITION_NED)",
  /// "navigation CSV rows", or "undecided (N bytes, neither a MAVLink frame nor a CSV row yet)".
  std::string description() const;
  /// Items skipped so far: CSV rows skipped (NavCsvStream::skippedRows), or MAVLink frames refused
  /// (MavlinkStreamCounts::bad_frames) plus ATTITUDEs that gave no fix.
  std::size_t skipped() const;
  /// Bytes dropped while undecided (beyond the 64 KiB kept).
  std::size_t bytesDropped() const;
  /// Lines for the user not taken yet: the protocol found, the MAVLink decoder's notes, the last CSV
  /// skip reason.
  std::vector<std::string> takeNotes();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sonarmap
