#pragma once
/// @file checks.hpp
/// Private to the acoustics layer: argument checks cheap enough for the simulator's inner loops
/// (the message is built only when a check fails).

#include <limits>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::acoustics_checks {

/// @throws ValueError(what) when !valid.
inline void require(bool valid, const char* what) {
  if (!valid) throw ValueError(what);
}

/// @throws ValueError("<what>, got <value>") when !valid.
inline void require(bool valid, const char* what, double value) {
  if (!valid) throw ValueError(std::string(what) + ", got " + std::to_string(value));
}

/// Finite and > 0.
inline bool positive(double value) { return value > 0.0 && value < std::numeric_limits<double>::infinity(); }

/// Finite and ≥ 0.
inline bool nonNegative(double value) { return value >= 0.0 && value < std::numeric_limits<double>::infinity(); }

}  // namespace sonarmap::acoustics_checks
