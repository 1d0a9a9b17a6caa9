#pragma once
// The navigation's noise model on the command line (map --slam, live --slam, localize): a class of
// navigation sensors (slam/scan_forming.hpp, odometryNoiseOf) and its values overridden one by one,
// in the sensors' own units.

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "sonarmap/slam/localizer.hpp"
#include "sonarmap/slam/scan_forming.hpp"

namespace sonarmap::cli {

/// What the user said of the navigation; unset: the class's value.
struct OdometryArgs {
  std::string nav_class = "auto";                   ///< --nav-class; auto: navigationClassOf the track
  std::optional<double> scale_sigma_pct;            ///< --nav-scale-sigma, %
  std::optional<double> heading_sigma_deg;          ///< --nav-heading-sigma, degrees
  std::optional<double> velocity_noise_mps;         ///< --nav-velocity-noise, m/s
  std::optional<double> gyro_walk_deg_per_sqrt_s;   ///< --nav-gyro-walk, °/√s
  std::optional<double> max_speed_mps;              ///< --max-speed, m/s
  std::optional<double> max_turn_rate_deg_s;        ///< --max-turn-rate, °/s

  /// Whether anything but the default class was given.
  bool stated() const;
};

/// Adds --nav-class, --nav-scale-sigma, --nav-heading-sigma, --nav-velocity-noise, --nav-gyro-walk,
/// --max-speed and --max-turn-rate.
void addOdometryOptions(CLI::App& cmd, OdometryArgs& args);

/// The noise model the arguments state, of `track` (the navigation given: its class when "auto",
/// navigationClassOf).
/// @throws ValueError for an unknown class, a value that is negative or not finite, or a limit
///         (--max-speed, --max-turn-rate) that is not > 0.
OdometryNoise toOdometryNoise(const OdometryArgs& args, const NavTrack& track = {});

/// Checks the arguments before anything runs: valid (toOdometryNoise), and given only with
/// `slam` (a command whose localization is optional; localize always localizes: true).
/// @throws ValueError naming what is wrong.
void checkOdometryArgs(const OdometryArgs& args, bool slam);

/// The localization's options with the arguments' noise model of `track`, the rest default.
/// @throws ValueError as toOdometryNoise.
SlamOptions toSlamOptions(const OdometryArgs& args, const NavTrack& track);

}  // namespace sonarmap::cli
