/// @file decibels.cpp
/// The messages of the level and power checks (see decibels.hpp).

#include "sonarmap/acoustics/decibels.hpp"

#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {

void throwInvalidLevel(double) { throw ValueError("a level in dB is NaN"); }

void throwInvalidPower(double power) {
  throw ValueError("a power must be >= 0, got " + std::to_string(power));
}

}  // namespace sonarmap::detail
