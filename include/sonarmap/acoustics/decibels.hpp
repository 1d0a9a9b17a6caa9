#pragma once
/// @file decibels.hpp
/// Levels and powers. Every term of the sonar equation is a level, L = 10 log10(P / P_ref) dB
/// re a reference power (Urick, "Principles of Underwater Sound", 3rd ed. 1983, ch. 2); here the
/// reference is 1 in whatever power unit the caller uses (the simulator's: the echo of a perfect
/// reflector filling the beam at normal incidence, msis_simulator.hpp).

namespace sonarmap {

/// The power of a level: 10^(level_db / 10). −infinity gives 0, +infinity gives +infinity.
/// @throws ValueError when level_db is NaN.
double powerOfLevel(double level_db);

/// The level of a power: 10 log10(power) dB; −infinity for 0, +infinity for +infinity.
/// @throws ValueError when power is negative or NaN.
double levelOfPower(double power);

}  // namespace sonarmap
