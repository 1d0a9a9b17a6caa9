#pragma once
/// @file heads.hpp
/// The drivers of the heads `sonarmap live` drives, by the protocol they speak.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/devices/head_driver.hpp"
#include "sonarmap/devices/head_emulator.hpp"
#include "sonarmap/devices/head_settings.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/sim/scene.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {

/// A driver for a head speaking `format`'s protocol: LogFormat::kPing360 (ping360_driver.hpp) or
/// LogFormat::kSeaNet (seanet_driver.hpp), asking it for `settings`. `link_baud`: the serial
/// link's bits per second, for the time a reply takes to arrive; 0 for a network link.
/// @throws ValueError for another format, or settings the head cannot take (naming the option and
///         what it can take).
std::unique_ptr<HeadDriver> makeHeadDriver(LogFormat format, const HeadSettings& settings, unsigned link_baud);

/// What a program that only listens to a head sends to the UDP server relaying it, so that the
/// server sends it the head's bytes: BlueOS's `bridges` (the ping proxy on 9092) serves only the
/// clients a datagram came from in the last 10 s, and writes their bytes to the head
/// (patrickelectric/bridges, src/socket.rs and src/main.rs; an empty datagram makes it send the
/// head a line break, so it is never empty). A request the head answers without changing any
/// setting: Ping360, general_request(protocol_version) (ping-python's first message); SeaNet,
/// mtSendVersion (the drivers' first question).
/// @throws ValueError for another format.
std::vector<std::uint8_t> listenerRegistration(LogFormat format);

/// The heads `sonarmap emulate` emulates, by their simulator preset (sim/sonar_presets.hpp):
/// "ping360", "ping360-2m", "ping360-5m" (ping360_emulator.hpp: one Ping360, the preset choosing
/// the scene's size), "micron", "seaking-30", "seaking-50" (seanet_emulator.hpp).
std::vector<std::string> emulatedHeadNames();

/// Where an emulated head is and how its replies cross its link.
struct EmulatedHeadPlace {
  Scene scene;                ///< the scene it pings (map frame)
  Trajectory trajectory;      ///< the vehicle's pose over the emulator's time, seconds
  Eigen::Isometry3d sonar_to_body = Eigen::Isometry3d::Identity();  ///< its mounting
  std::uint64_t seed = 1;     ///< of the speckle and noise
  unsigned baud = 115200;     ///< the serial link's rate (replies take their time to cross); 0: a network link
  double sound_speed_m_s = 1500.0;
};

/// The emulated head `name` (emulatedHeadNames) at `place`.
/// @throws ValueError naming the heads that can be emulated, for another name; as the emulators'
///         constructors for an invalid scene or trajectory.
std::unique_ptr<HeadEmulator> makeHeadEmulator(const std::string& name, const EmulatedHeadPlace& place);

}  // namespace sonarmap
