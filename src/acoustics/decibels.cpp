/// @file decibels.cpp
/// Levels and powers (see decibels.hpp).

#include "sonarmap/acoustics/decibels.hpp"

#include <cmath>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

double powerOfLevel(double level_db) {
  if (std::isnan(level_db)) throw ValueError("powerOfLevel: level_db is NaN");
  return std::pow(10.0, level_db / 10.0);
}

double levelOfPower(double power) {
  if (!(power >= 0.0)) throw ValueError("levelOfPower: power must be >= 0, got " + std::to_string(power));
  return 10.0 * std::log10(power);
}

}  // namespace sonarmap
