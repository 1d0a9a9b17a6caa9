#pragma once
/// @file seanet_settings.hpp
/// Private to src/devices: HeadSettings → a SeaNet mtHeadCommand and the settings as applied, by
/// the rules seanet_driver.hpp documents.

#include <optional>
#include <string>
#include <vector>

#include "sonarmap/devices/head_settings.hpp"
#include "sonarmap/devices/seanet_driver.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"

namespace sonarmap::detail {

/// What the head told about itself (unknown fields: nothing heard yet).
struct SeaNetHeadKnowledge {
  std::optional<seanet::VersionInfo> version;
  std::optional<seanet::BBUserInfo> user;
};

/// The command for the head, the settings as applied, and notes (a frequency ignored…).
struct SeaNetPlan {
  seanet::HeadCommand command;
  AppliedSettings applied;
  std::vector<std::string> notes;
  double listening_s = 0.0;  ///< NBins · ADInterval · 640 ns: the time a ping listens
};

/// Frequencies of the two channels SeaNet Pro's commands set, kHz.
inline constexpr double kSeaNetChannelKhz[2] = {325.0, 675.0};

/// The plan for `options` on a head described by `head`.
/// @throws ValueError naming the option and its allowed values.
SeaNetPlan planSeaNetCommand(const SeaNetDriverOptions& options, const SeaNetHeadKnowledge& head);

}  // namespace sonarmap::detail
