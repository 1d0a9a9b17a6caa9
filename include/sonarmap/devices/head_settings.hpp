#pragma once
/// @file head_settings.hpp
/// What a user asks of a sonar head, in physical units and named as the makers' own programs name
/// them (Blue Robotics' Ping Viewer for the Ping360, Tritech's SeaNet Pro for the Micron and
/// SeaKing), and what a driver applied after rounding to the head's own units.

#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sonarmap {

/// The settings `sonarmap live` sends to a head (`--range`, `--gain`, `--sector`,
/// `--sector-center`, `--step`, `--frequency`, `--sound-speed`). Unset fields take the driver's
/// default, which its header states. Angles are bearings in the sonar frame (beam.hpp: clockwise
/// seen from above, 0 ahead).
struct HeadSettings {
  std::optional<double> range_m;  ///< range scale, metres (> 0)
  /// Receiver gain in the head's own terms: a Ping360's gain setting "low", "normal" or "high"
  /// (0, 1, 2, as Ping Viewer shows it); a SeaNet head's gain in percent ("40" or "40%").
  std::optional<std::string> gain;
  double sector_width_rad = 2.0 * std::numbers::pi;  ///< width of the scanned sector; 2π: continuous turns
  double sector_center_rad = 0.0;                    ///< bearing of the sector's centre (sector scans)
  std::optional<double> step_rad;                    ///< bearing step between beams (> 0)
  std::optional<double> frequency_khz;               ///< transmit frequency, kHz, where the head has a choice
  double sound_speed_m_s = 1500.0;                   ///< speed of sound for ranges ↔ times, m/s (> 0)

  /// Whether the head turns continuously (sector_width_rad within 1e-9 of 2π or more).
  bool fullTurns() const { return sector_width_rad >= 2.0 * std::numbers::pi - 1e-9; }
};

/// The settings a driver applied, as the head takes them: the head's name, then one entry per
/// setting, its name carrying its unit (`range_m`, `gain`, `step_deg`, `transmit_duration_us`...)
/// and its value as text. Printed by `live` and recorded in the log it writes.
struct AppliedSettings {
  std::string head;  ///< "Ping360", "Tritech SeaNet head"
  std::vector<std::pair<std::string, std::string>> fields;

  /// "Ping360: range_m 50, gain normal, ...": one line for the user.
  std::string text() const;
  /// The value of `name`, or empty when there is none.
  std::string value(const std::string& name) const;
};

}  // namespace sonarmap
