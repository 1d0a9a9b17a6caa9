#pragma once
/// @file head_emulator.hpp
/// A sonar head's side of its protocol, answering from a simulated scene (sim/beam_simulator.hpp):
/// it pings only when commanded, at the commanded angle, range and gain, and takes as long as the
/// head would (the motor's step, the echo's two-way travel, sending the samples). A state machine
/// without I/O, as the drivers (head_driver.hpp): `sonarmap emulate` owns the link and the clock.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sonarmap {

/// Bytes an emulated head sends, and when: `at_s` on the emulator's clock (≥ the time of the
/// event that caused them).
struct TimedBytes {
  double at_s = 0.0;
  std::vector<std::uint8_t> bytes;
};

/// One emulated head. Times are seconds on the emulator's clock; the scene's trajectory is
/// evaluated at those times.
class HeadEmulator {
 public:
  virtual ~HeadEmulator() = default;
  /// The host sent `bytes` at `now_s` (any chunk). Returns the replies, each due at its time, in
  /// order of those times.
  virtual std::vector<TimedBytes> receive(std::span<const std::uint8_t> bytes, double now_s) = 0;
  /// Messages the head sends unprompted by `now_s` (a SeaNet head's mtAlive every second, a
  /// Ping360's pings in auto-transmit mode).
  virtual std::vector<TimedBytes> poll(double now_s) = 0;
  /// Beams pinged so far.
  virtual std::size_t beamsSent() const = 0;
  /// The settings the host commanded last, one line ("range 50 m, gain 1, angle 133 grad ...").
  virtual std::string settingsText() const = 0;
};

}  // namespace sonarmap
