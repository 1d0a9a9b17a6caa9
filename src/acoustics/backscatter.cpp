/// @file backscatter.cpp
/// Lambert's law (see backscatter.hpp).

#include "sonarmap/acoustics/backscatter.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

void requireReflectivity(double reflectivity) {
  if (!(reflectivity >= 0.0 && reflectivity <= 1.0)) {
    throw ValueError("backscatter: reflectivity must be in [0, 1], got " + std::to_string(reflectivity));
  }
}

void requireExponent(double lambert_exponent) {
  if (!(std::isfinite(lambert_exponent) && lambert_exponent >= 1.0)) {
    throw ValueError("backscatter: lambert_exponent must be >= 1, got " + std::to_string(lambert_exponent));
  }
}

void requireCosine(double cos_incidence) {
  if (!(std::isfinite(cos_incidence) && cos_incidence >= 0.0)) {
    throw ValueError("backscatter: cos_incidence must be >= 0, got " + std::to_string(cos_incidence));
  }
}

}  // namespace

double lambertCoefficient(double reflectivity) {
  requireReflectivity(reflectivity);
  return reflectivity / std::numbers::pi;
}

double lambertStrength_db(double reflectivity, double grazing_rad, double lambert_exponent) {
  requireExponent(lambert_exponent);
  if (!(grazing_rad >= 0.0 && grazing_rad <= 0.5 * std::numbers::pi)) {
    throw ValueError("backscatter: grazing_rad must be in [0, π/2], got " + std::to_string(grazing_rad));
  }
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
