// libFuzzer harness: bytes from a SeaNet serial line → PacketParser (in chunks the input's first
// byte sizes), every decoder on every packet, and the same bytes into a SeaNetDriver and a
// SeaNetEmulator. None may throw, whatever the bytes (the contract of seanet_protocol.hpp,
// seanet_driver.hpp, seanet_emulator.hpp).
#include <cstddef>
#include <cstdint>
#include <span>

#include "sonarmap/devices/seanet_driver.hpp"
#include "sonarmap/devices/seanet_emulator.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace {

sonarmap::SeaNetEmulator makeEmulator() {
  const sonarmap::SonarPreset preset = sonarmap::sonarPreset("micron");
  return sonarmap::SeaNetEmulator(sonarmap::MsisBeamSimulator(sonarmap::builtinScene("tank"), preset.head, preset.echo,
                                                              sonarmap::staticTrajectory(), sonarmap::defaultSonarToBody(), 1),
                                  sonarmap::SeaNetEmulatorOptions{});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace seanet = sonarmap::seanet;
  const std::size_t chunk = size > 0 ? 1 + data[0] % 64 : 1;
  const std::span<const std::uint8_t> bytes(data, size);
  seanet::PacketParser parser;
  sonarmap::SeaNetDriverOptions options;
  options.time_of_day_ms = [] { return 0U; };
  sonarmap::SeaNetDriver driver(options);
  driver.start(0.0);
  static sonarmap::SeaNetEmulator emulator = makeEmulator();
  double now_s = 0.0;
  for (std::size_t at = 0; at < size; at += chunk) {
    const std::span<const std::uint8_t> part = bytes.subspan(at, std::min(chunk, size - at));
    for (const seanet::Packet& packet : parser.feed(part)) {
      seanet::decodeAlive(packet);
      seanet::decodeVersionData(packet);
      seanet::decodeBBUserData(packet);
      seanet::decodeSendData(packet);
      seanet::decodeHeadData(packet, 1500.0);
      if (const auto command = seanet::decodeHeadCommand(packet)) seanet::encodeHeadCommand(*command);
      seanet::encodePacket(packet);
    }
    now_s += 0.05;
    driver.receive(part, now_s);
    driver.poll(now_s);
    emulator.receive(part, now_s);
    emulator.poll(now_s);
  }
  parser.takeSkipped();
  return 0;
}
