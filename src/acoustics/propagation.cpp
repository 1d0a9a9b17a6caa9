/// @file propagation.cpp
/// Spreading, absorption and the time-varying gain (see propagation.hpp).

#include "sonarmap/acoustics/propagation.hpp"

#include <algorithm>
#include <cmath>

#include "checks.hpp"

namespace sonarmap {
namespace {

using acoustics_checks::nonNegative;
using acoustics_checks::positive;
using acoustics_checks::require;

void requireAbsorption(double absorption_db_per_m) {
  require(nonNegative(absorption_db_per_m), "propagation: the absorption must be >= 0 dB/m", absorption_db_per_m);
}

}  // namespace

double oneWayTransmissionLoss_db(double range_m, double absorption_db_per_m) {
  require(positive(range_m), "propagation: range_m must be > 0", range_m);
  requireAbsorption(absorption_db_per_m);
  return 20.0 * std::log10(range_m) + absorption_db_per_m * range_m;
}

double twoWayTransmissionFactor(double range_m, double absorption_db_per_m) {
  require(positive(range_m), "propagation: range_m must be > 0", range_m);
  requireAbsorption(absorption_db_per_m);
  const double range_squared = range_m * range_m;
  return std::pow(10.0, -2.0 * absorption_db_per_m * range_m / 10.0) / (range_squared * range_squared);
}

double twoWayLossPerSolidAngle(double path_m, double absorption_db_per_m, double min_range_m) {
  require(nonNegative(path_m), "propagation: path_m must be >= 0", path_m);
  requireAbsorption(absorption_db_per_m);
  require(positive(min_range_m), "propagation: min_range_m must be > 0", min_range_m);
  const double range_m = std::max(0.5 * path_m, min_range_m);
  return std::pow(10.0, -absorption_db_per_m * path_m / 10.0) / (range_m * range_m);
}

double tvgGain(double range_m, double tvg_absorption_db_per_m) {
  require(nonNegative(range_m), "propagation: range_m must be >= 0", range_m);
  requireAbsorption(tvg_absorption_db_per_m);
  return range_m * range_m * std::pow(10.0, 2.0 * tvg_absorption_db_per_m * range_m / 10.0);
}

}  // namespace sonarmap
