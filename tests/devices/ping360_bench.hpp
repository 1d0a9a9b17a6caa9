#pragma once
/// @file ping360_bench.hpp
/// A Ping360Driver talking to a Ping360Emulator in-process, on a simulated clock: the bytes each
/// sends reach the other when due (the emulator's replies at their TimedBytes::at_s), the driver is
/// polled every 50 ms. Replies can be dropped on the way to test the driver's repeats.

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sonarmap/devices/ping360_driver.hpp"
#include "sonarmap/devices/ping360_emulator.hpp"
#include "sonarmap/formats/ping_protocol.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap::test {

/// The bytes of hex digits ("4252...").
inline std::vector<std::uint8_t> hexBytes(const std::string& text) {
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < text.size(); i += 2) {
    bytes.push_back(static_cast<std::uint8_t>(std::stoul(text.substr(i, 2), nullptr, 16)));
  }
  return bytes;
}

/// A Ping360 emulator in the built-in tank (5 m scale), the vehicle still at the origin.
inline Ping360Emulator tankPing360(unsigned baud = 115200, std::uint64_t seed = 1) {
  Ping360EmulatorOptions options;
  options.baud = baud;
  return Ping360Emulator(builtinScene("tank"), staticTrajectory(), defaultSonarToBody(), seed, options);
}

class Ping360Bench {
 public:
  Ping360Bench(const HeadSettings& settings, Ping360Emulator emulator, unsigned link_baud = 115200)
      : driver_(settings, Ping360DriverOptions{link_baud}), emulator_(std::move(emulator)) {}

  /// Drop the replies for which this returns true (called once per reply, in order).
  std::function<bool(const ping_protocol::Message&)> drop;

  Ping360Driver& driver() { return driver_; }
  Ping360Emulator& emulator() { return emulator_; }
  double now() const { return now_; }
  const std::vector<Beam>& beams() const { return beams_; }
  const std::vector<double>& beamTimes() const { return beam_times_; }
  const std::vector<std::string>& notes() const { return notes_; }
  /// Every byte the driver sent, in order.
  const std::vector<std::uint8_t>& sent() const { return sent_; }

  void start() { handle(driver_.start(now_)); }

  /// Runs until `beams` beams arrived or `max_s` passed on the clock.
  void runUntilBeams(std::size_t beams, double max_s) {
    const double end = now_ + max_s;
    while (beams_.size() < beams && now_ < end) step();
  }

  /// Runs for `seconds` on the clock.
  void runFor(double seconds) {
    const double end = now_ + seconds;
    while (now_ < end) step();
  }

  /// The driver's stop bytes sent to the head.
  void stop() { toHead(driver_.stop()); }

  /// Bytes another program sends the head through the same proxy (BlueOS's bridges): the head's
  /// replies reach the driver too.
  void fromAnotherProgram(const std::vector<std::uint8_t>& bytes) { queue(emulator_.receive(bytes, now_)); }

 private:
  void step() {
    double next = now_ + 0.05;
    if (!in_flight_.empty()) next = std::min(next, in_flight_.front().at_s);
    now_ = std::max(now_, next);
    while (!in_flight_.empty() && in_flight_.front().at_s <= now_) {
      const TimedBytes reply = in_flight_.front();
      in_flight_.erase(in_flight_.begin());
      ping_protocol::MessageParser parser;
      const std::vector<ping_protocol::Message> messages = parser.feed(reply.bytes);
      if (drop && !messages.empty() && drop(messages.front())) continue;
      handle(driver_.receive(reply.bytes, now_));
    }
    handle(driver_.poll(now_));
    queue(emulator_.poll(now_));
  }

  void handle(const DriverOutput& out) {
    for (const Beam& beam : out.beams) {
      beams_.push_back(beam);
      beam_times_.push_back(now_);
    }
    notes_.insert(notes_.end(), out.notes.begin(), out.notes.end());
    toHead(out.send);
  }

  void toHead(const std::vector<std::uint8_t>& bytes) {
    if (bytes.empty()) return;
    sent_.insert(sent_.end(), bytes.begin(), bytes.end());
    queue(emulator_.receive(bytes, now_));
  }

  void queue(std::vector<TimedBytes> replies) {
    for (TimedBytes& reply : replies) in_flight_.push_back(std::move(reply));
    std::stable_sort(in_flight_.begin(), in_flight_.end(),
                     [](const TimedBytes& a, const TimedBytes& b) { return a.at_s < b.at_s; });
  }

  Ping360Driver driver_;
  Ping360Emulator emulator_;
  double now_ = 0.0;
  std::vector<TimedBytes> in_flight_;
  std::vector<Beam> beams_;
  std::vector<double> beam_times_;
  std::vector<std::string> notes_;
  std::vector<std::uint8_t> sent_;
};

}  // namespace sonarmap::test
