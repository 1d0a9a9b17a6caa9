#pragma once
/// @file seanet_bench.hpp
/// Test fixture: a SeaNetDriver talking to a SeaNetEmulator in-process, no I/O, on a simulated
/// clock stepped by 10 ms. The emulator's replies reach the driver at their due time; a test may
/// drop some of them on the way.

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sonarmap/devices/seanet_driver.hpp"
#include "sonarmap/devices/seanet_emulator.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"
#include "sonarmap/sim/beam_simulator.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap::test {

/// A simulator of the preset `name` in the tank scene from a still vehicle, with `bins` bins.
inline MsisBeamSimulator seaNetSimulator(const std::string& name) {
  const SonarPreset preset = sonarPreset(name);
  return MsisBeamSimulator(builtinScene("tank"), preset.head, preset.echo, staticTrajectory(), defaultSonarToBody(), 1);
}

struct SeaNetBench {
  SeaNetEmulator emulator;
  SeaNetDriver driver;
  double now_s = 0.0;
  std::vector<TimedBytes> in_flight;       ///< emulator → driver, not yet due
  std::vector<std::uint8_t> host_types;    ///< message types the driver sent, in order
  std::vector<Beam> beams;
  std::vector<double> beam_times_s;        ///< arrival of each beam
  std::vector<std::string> notes;
  std::function<bool(const seanet::Packet&)> drop;  ///< drops an emulator → driver packet
  seanet::PacketParser host_parser;
  std::size_t dropped = 0;

  SeaNetBench(const std::string& preset, SeaNetDriverOptions options)
      : emulator(seaNetSimulator(preset), SeaNetEmulatorOptions{preset}), driver(std::move(options)) {
    handle(driver.start(now_s));
  }

  void queue(std::vector<TimedBytes> replies) {
    for (TimedBytes& reply : replies) {
      if (drop) {
        seanet::PacketParser parser;
        const std::vector<seanet::Packet> packets = parser.feed(reply.bytes);
        if (packets.size() == 1 && drop(packets.front())) {
          ++dropped;
          continue;
        }
      }
      in_flight.push_back(std::move(reply));
    }
    std::stable_sort(in_flight.begin(), in_flight.end(),
                     [](const TimedBytes& a, const TimedBytes& b) { return a.at_s < b.at_s; });
  }

  void handle(const DriverOutput& out) {
    for (const Beam& beam : out.beams) {
      beams.push_back(beam);
      beam_times_s.push_back(now_s);
    }
    notes.insert(notes.end(), out.notes.begin(), out.notes.end());
    if (out.send.empty()) return;
    for (const seanet::Packet& packet : host_parser.feed(out.send)) host_types.push_back(packet.type);
    queue(emulator.receive(out.send, now_s));
  }

  /// Steps the clock to `end_s` (or until `done()`), delivering and polling every 10 ms.
  void runUntil(double end_s, const std::function<bool()>& done = {}) {
    while (now_s < end_s && !(done && done())) {
      now_s += 0.01;
      queue(emulator.poll(now_s));
      while (!in_flight.empty() && in_flight.front().at_s <= now_s) {
        const TimedBytes reply = std::move(in_flight.front());
        in_flight.erase(in_flight.begin());
        handle(driver.receive(reply.bytes, now_s));
      }
      handle(driver.poll(now_s));
    }
  }

  bool sawNote(const std::string& text) const {
    return std::any_of(notes.begin(), notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
  }
};

}  // namespace sonarmap::test
