#pragma once
/// @file head_driver.hpp
/// Driving a mechanically scanned sonar head over a byte link: the conversation of each protocol as
/// a state machine without I/O. The caller (sonarmap live) owns the link and the clock: it passes
/// in the bytes the head sent and the time, and writes out the bytes the driver returns. Drivers:
/// ping360_driver.hpp (Blue Robotics ping-protocol), seanet_driver.hpp (Tritech SeaNet).

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/devices/head_settings.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// What a driver asks of its caller after an event.
struct DriverOutput {
  std::vector<std::uint8_t> send;  ///< bytes to write to the head now, in order
  /// Beams the head's replies completed, in order, with time_s unset (0): the wire carries no
  /// clock, so the caller stamps each with the arrival of its bytes.
  std::vector<Beam> beams;
  std::vector<std::string> notes;  ///< lines for the user: the device found, a command repeated, a refusal
};

/// One head's conversation. Times are seconds on the caller's steady clock.
class HeadDriver {
 public:
  virtual ~HeadDriver() = default;
  /// The first bytes to send (a request for the device's identity, a reboot).
  virtual DriverOutput start(double now_s) = 0;
  /// The head sent `bytes` (any chunk: frames are reassembled across calls).
  virtual DriverOutput receive(std::span<const std::uint8_t> bytes, double now_s) = 0;
  /// Called at least every 100 ms: repeats a command whose reply is overdue, as the makers' own
  /// programs do.
  virtual DriverOutput poll(double now_s) = 0;
  /// The bytes that stop the head where its protocol has a way (after them the driver sends
  /// nothing more); empty where it has none.
  virtual std::vector<std::uint8_t> stop() = 0;
  /// The settings as applied (known once the head is configured; before, as requested).
  virtual AppliedSettings applied() const = 0;
  /// The device as it described itself ("Ping360 (firmware 3.1.1)"); empty until it has.
  virtual std::string device() const = 0;
  /// Whether any whole, valid frame came from the head yet.
  virtual bool heard() const = 0;
};

}  // namespace sonarmap
