/// @file propagation.cpp
/// Spreading, absorption and the time-varying gain (see propagation.hpp).

#include "sonarmap/acoustics/propagation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

void require(bool valid, const std::string& what) {
  if (!valid) throw ValueError(what);
}

void requireAbsorption(double absorption_db_per_m) {
  require(std::isfinite(absorption_db_per_m) && absorption_db_per_m >= 0.0,
          "propagation: absorption must be >= 0 dB/m, got " + std::to_string(absorption_db_per_m));
}

void requireRange(double range_m) {
  require(std::isfinite(range_m) && range_m > 0.0, "propagation: range_m must be > 0, got " + std::to_string(range_m));
}

}  // namespace

double oneWayTransmissionLoss_db(double range_m, double absorption_db_per_m) {
  requireRange(range_m);
  requireAbsorption(absorption_db_per_m);
  return 20.0 * std::log10(range_m) + absorption_db_per_m * range_m;
}

double twoWayTransmissionFactor(double range_m, double absorption_db_per_m) {
  requireRange(range_m);
  requireAbsorption(absorption_db_per_m);
  const double range_squared = range_m * range_m;
  return std::pow(10.0, -2.0 * absorption_db_per_m * range_m / 10.0) / (range_squared * range_squared);
}

double twoWayLossPerSolidAngle(double path_m, double absorption_db_per_m, double min_range_m) {
  require(std::isfinite(path_m) && path_m >= 0.0, "propagation: path_m must be >= 0, got " + std::to_string(path_m));
  requireAbsorption(absorption_db_per_m);
  requireRange(min_range_m);
  const double range_m = std::max(0.5 * path_m, min_range_m);
  return std::pow(10.0, -absorption_db_per_m * path_m / 10.0) / (range_m * range_m);
}

double tvgGain(double range_m, double tvg_absorption_db_per_m) {
  require(std::isfinite(range_m) && range_m >= 0.0, "propagation: range_m must be >= 0, got " + std::to_string(range_m));
  requireAbsorption(tvg_absorption_db_per_m);
  return range_m * range_m * std::pow(10.0, 2.0 * tvg_absorption_db_per_m * range_m / 10.0);
}

}  // namespace sonarmap
