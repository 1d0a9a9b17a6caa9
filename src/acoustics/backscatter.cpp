/// @file backscatter.cpp
/// Lambert's law (see backscatter.hpp).

#include "sonarmap/acoustics/backscatter.hpp"

#include <cmath>
#include <numbers>

#include "checks.hpp"

namespace sonarmap {
namespace {

using acoustics_checks::nonNegative;
using acoustics_checks::require;

void requireReflectivity(double reflectivity) {
  require(reflectivity >= 0.0 && reflectivity <= 1.0, "backscatter: reflectivity must be in [0, 1]", reflectivity);
}

void requireExponent(double lambert_exponent) {
  require(lambert_exponent >= 1.0 && std::isfinite(lambert_exponent), "backscatter: lambert_exponent must be >= 1",
          lambert_exponent);
}

void requireCosine(double cos_incidence) {
  require(nonNegative(cos_incidence), "backscatter: cos_incidence must be >= 0", cos_incidence);
}

}  // namespace

double lambertCoefficient(double reflectivity) {
  requireReflectivity(reflectivity);
  return reflectivity / std::numbers::pi;
}

double lambertStrength_db(double reflectivity, double grazing_rad, double lambert_exponent) {
  requireExponent(lambert_exponent);
  require(grazing_rad >= 0.0 && grazing_rad <= 0.5 * std::numbers::pi, "backscatter: grazing_rad must be in [0, π/2]",
          grazing_rad);
  return 10.0 * std::log10(lambertCoefficient(reflectivity)) +
         10.0 * lambert_exponent * std::log10(std::sin(grazing_rad));
}

double lambertScatter(double reflectivity, double cos_incidence, double lambert_exponent) {
  requireReflectivity(reflectivity);
  requireCosine(cos_incidence);
  requireExponent(lambert_exponent);
  return reflectivity * std::pow(cos_incidence, lambert_exponent);
}

double lambertScatterPerSolidAngle(double reflectivity, double cos_incidence, double lambert_exponent) {
  requireReflectivity(reflectivity);
  requireCosine(cos_incidence);
  requireExponent(lambert_exponent);
  return reflectivity * std::pow(cos_incidence, lambert_exponent - 1.0);
}

}  // namespace sonarmap
