#pragma once
/// @file decibels.hpp
/// Levels and powers. Every term of the sonar equation is a level, L = 10 log10(P / P_ref) dB
/// re a reference power (Urick, "Principles of Underwater Sound", 3rd ed. 1983, ch. 2); here the
/// reference is 1 in whatever power unit the caller uses (the simulator's: the echo of a perfect
/// reflector filling the beam at normal incidence, msis_simulator.hpp).

#include <cmath>

namespace sonarmap {

namespace detail {
/// Throws ValueError for powerOfLevel's NaN level or levelOfPower's negative or NaN power.
[[noreturn]] void throwInvalidLevel(double level_db);
[[noreturn]] void throwInvalidPower(double power);
}  // namespace detail

/// The power of a level: 10^(level_db / 10). −infinity gives 0, +infinity gives +infinity.
/// Inline: the simulator converts every bin.
/// @throws ValueError when level_db is NaN.
inline double powerOfLevel(double level_db) {
  if (std::isnan(level_db)) detail::throwInvalidLevel(level_db);
  return std::pow(10.0, level_db / 10.0);
}

/// The level of a power: 10 log10(power) dB; −infinity for 0, +infinity for +infinity. Inline.
/// @throws ValueError when power is negative or NaN.
inline double levelOfPower(double power) {
  if (!(power >= 0.0)) detail::throwInvalidPower(power);
  return 10.0 * std::log10(power);
}

}  // namespace sonarmap
