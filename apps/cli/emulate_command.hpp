#pragma once
// `sonarmap emulate`: a sonar head emulated over its protocol on a pseudo-terminal or UDP, its
// pings simulated in a scene (devices/head_emulator.hpp), for `sonarmap live` and the makers' own
// programs (Ping Viewer, ping-python) to talk to as to the real head.

#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"

#include "sonarmap/devices/head_emulator.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap emulate`: the head preset, the vehicle's run (SimulationArguments: the
/// mission, speed, heading, depth, mounting, seed; static by default), the scene and the links.
struct EmulateArgs : SimulationArguments {
  EmulateArgs() { sonar = "ping360"; }
  std::string scene = "harbour";  ///< a built-in scene (built for the preset's range) or a scene file
  std::vector<std::string> serial;  ///< --serial: pty:PATH or a serial device, one head on each
  std::vector<std::string> udp;     ///< --udp: udp://:PORT (or any ByteLink), one head on each
  unsigned baud = 115200;           ///< serial links: the rate replies take to cross (UDP: none)
  double sound_speed_m_s = 1500.0;  ///< the water's
  double duration_s = 0.0;          ///< stop after this long; 0: at SIGINT or SIGTERM
  std::string mavlink;              ///< --mavlink: a link to send the vehicle's navigation to as ArduSub does
  double nav_rate_hz = 10.0;        ///< --nav-rate: navigation updates per second
  bool no_position = false;         ///< --no-position: no LOCAL_POSITION_NED (a vehicle without a DVL)
  double time_scale = 1.0;          ///< --time-scale: the emulated dive runs this many times faster
};

/// Adds the `emulate` subcommand to `app`; its options fill `args`.
Command addEmulateCommand(CLI::App& app, EmulateArgs& args);


}  // namespace sonarmap::cli
