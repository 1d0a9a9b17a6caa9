/// @file heads.cpp
/// The drivers by protocol (see heads.hpp).

#include "sonarmap/devices/heads.hpp"

#include "sonarmap/core/errors.hpp"
#include "sonarmap/devices/ping360_driver.hpp"
#include "sonarmap/devices/ping360_emulator.hpp"
#include "sonarmap/devices/seanet_driver.hpp"
#include "sonarmap/devices/seanet_emulator.hpp"
#include "sonarmap/formats/ping_protocol.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"
#include "sonarmap/sim/beam_simulator.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap {

std::unique_ptr<HeadDriver> makeHeadDriver(LogFormat format, const HeadSettings& settings, unsigned link_baud) {
  if (format == LogFormat::kSeaNet) return std::make_unique<SeaNetDriver>(SeaNetDriverOptions{.settings = settings});
  if (format == LogFormat::kPing360) return std::make_unique<Ping360Driver>(settings, Ping360DriverOptions{link_baud});
  throw ValueError("a head is driven in the ping360 or seanet protocol");
}

std::vector<std::uint8_t> listenerRegistration(LogFormat format) {
  if (format == LogFormat::kPing360) return ping_protocol::encode(ping_protocol::GeneralRequest{ping_protocol::kProtocolVersion});
  if (format == LogFormat::kSeaNet) return seanet::encodeSimpleCommand(seanet::MessageType::kSendVersion);
  throw ValueError("a head is listened to in the ping360 or seanet protocol");
}

std::vector<std::string> emulatedHeadNames() {
  return {"ping360", "ping360-2m", "ping360-5m", "micron", "seaking-30", "seaking-50"};
}

std::unique_ptr<HeadEmulator> makeHeadEmulator(const std::string& name, const EmulatedHeadPlace& place) {
  if (name == "ping360" || name == "ping360-2m" || name == "ping360-5m") {
    Ping360EmulatorOptions options;
    options.baud = place.baud;
    options.sound_speed_m_s = place.sound_speed_m_s;
    return std::make_unique<Ping360Emulator>(place.scene, place.trajectory, place.sonar_to_body, place.seed, options);
  }
  if (name == "micron" || name == "seaking-30" || name == "seaking-50") {
    const SonarPreset preset = sonarPreset(name);
    SeaNetEmulatorOptions options;
    options.preset = name;
    options.baud = place.baud > 0 ? place.baud : 115200;
    return std::make_unique<SeaNetEmulator>(
        MsisBeamSimulator(place.scene, preset.head, preset.echo, place.trajectory, place.sonar_to_body, place.seed),
        options);
  }
  std::string names;
  for (const std::string& known : emulatedHeadNames()) names += (names.empty() ? "" : ", ") + known;
  throw ValueError("no emulator for the head '" + name + "': expected one of " + names);
}

}  // namespace sonarmap
