#pragma once
// The settings `sonarmap live` sends to the head it drives, in physical units and named as Ping
// Viewer and SeaNet Pro name them (devices/head_settings.hpp).

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "sonarmap/devices/head_settings.hpp"

namespace sonarmap::cli {

/// The head options as typed.
struct HeadArgs {
  std::optional<double> range_m;         ///< --range (m)
  std::string gain;                      ///< --gain: Ping360 low|normal|high (0|1|2); SeaNet percent
  double sector_deg = 360.0;             ///< --sector (°), (0, 360]
  double sector_center_deg = 0.0;        ///< --sector-center (° clockwise from ahead)
  std::optional<double> step_deg;        ///< --step (°)
  std::optional<double> frequency_khz;   ///< --frequency (kHz)
  double sound_speed_m_s = 1500.0;       ///< --sound-speed (m/s)
  bool listen_only = false;              ///< --listen-only: send the head nothing
};

/// Adds --range, --gain, --sector, --sector-center, --step, --frequency, --sound-speed and
/// --listen-only to `cmd` (help group Head).
void addHeadOptions(CLI::App& cmd, HeadArgs& args);

/// The settings `args` asks for. @throws ValueError for a value out of its range (the option named).
HeadSettings toHeadSettings(const HeadArgs& args);

/// Whether the user set any setting of the head (not --listen-only, --sound-speed).
bool anyHeadSetting(const HeadArgs& args);

}  // namespace sonarmap::cli
