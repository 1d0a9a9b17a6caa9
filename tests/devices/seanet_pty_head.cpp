/// @file seanet_pty_head.cpp
/// Test-only program: a SeaNetEmulator (tank scene, still vehicle) served on a pseudo-terminal, so
/// that an outside SeaNet client (another project's driver) can open PATH as the serial port of a
/// head. Prints one line per packet each way (time, direction, message type, hex of short ones).
///
///   sonarmap_seanet_pty_head PATH [PRESET [SECONDS [BAUD]]]   (defaults: micron, 30 s, 115200)

#include <poll.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "sonarmap/devices/seanet_emulator.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"
#include "sonarmap/live/byte_link.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace {

using namespace sonarmap;

void print(double t, const char* direction, const seanet::Packet& packet, const std::vector<std::uint8_t>& bytes) {
  std::string hex;
  if (bytes.size() <= 96) {
    char byte[4];
    for (const std::uint8_t b : bytes) {
      std::snprintf(byte, sizeof byte, "%02x", b);
      hex += byte;
    }
  }
  std::printf("%9.3f %s %-14s %4zu bytes %s\n", t, direction, seanet::messageTypeName(packet.type).c_str(), bytes.size(),
              hex.c_str());
  std::fflush(stdout);
}

int run(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s PATH [PRESET [SECONDS [BAUD]]]\n", argv[0]);
    return 2;
  }
  const std::string preset_name = argc > 2 ? argv[2] : "micron";
  const double seconds = argc > 3 ? std::stod(argv[3]) : 30.0;
  const unsigned baud = argc > 4 ? static_cast<unsigned>(std::stoul(argv[4])) : 115200;
  const SonarPreset preset = sonarPreset(preset_name);
  SeaNetEmulator head(MsisBeamSimulator(builtinScene("tank"), preset.head, preset.echo, staticTrajectory(),
                                        defaultSonarToBody(), 1),
                      SeaNetEmulatorOptions{preset_name, baud});
  ByteLink link("pty:" + std::string(argv[1]), baud);
  std::printf("serving %s on %s for %.0f s\n", preset_name.c_str(), link.description().c_str(), seconds);
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  auto now = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  std::vector<TimedBytes> due;
  seanet::PacketParser host_packets;
  std::vector<std::uint8_t> buffer(4096);
  while (now() < seconds) {
    pollfd fd{link.fd(), POLLIN, 0};
    ::poll(&fd, 1, 5);
    const double t = now();
    if (fd.revents & POLLIN) {
      const long n = link.read(buffer);
      if (n > 0) {
        const std::span<const std::uint8_t> bytes(buffer.data(), static_cast<std::size_t>(n));
        for (const seanet::Packet& p : host_packets.feed(bytes)) print(t, "host->head", p, seanet::encodePacket(p));
        for (TimedBytes& reply : head.receive(bytes, t)) due.push_back(std::move(reply));
      }
    }
    for (TimedBytes& alive : head.poll(t)) due.push_back(std::move(alive));
    std::stable_sort(due.begin(), due.end(), [](const TimedBytes& a, const TimedBytes& b) { return a.at_s < b.at_s; });
    while (!due.empty() && due.front().at_s <= now()) {
      seanet::PacketParser parser;
      for (const seanet::Packet& p : parser.feed(due.front().bytes)) print(now(), "head->host", p, due.front().bytes);
      link.write(due.front().bytes);
      due.erase(due.begin());
    }
  }
  std::printf("beams sent: %zu; %s\n", head.beamsSent(), head.settingsText().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sonarmap_seanet_pty_head: %s\n", e.what());
    return 1;
  }
}
