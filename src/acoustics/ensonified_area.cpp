/// @file ensonified_area.cpp
/// Pulse-limited and beam-limited ensonified areas (see ensonified_area.hpp).

#include "sonarmap/acoustics/ensonified_area.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

void requirePositive(double value, const char* name) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw ValueError(std::string("ensonified area: ") + name + " must be > 0, got " + std::to_string(value));
  }
}

}  // namespace

double pulseLimitedArea_m2(double range_m, double grazing_rad, double pulse_length_m, double equivalent_width_rad,
                           double elevation_rad) {
  requirePositive(range_m, "range_m");
  requirePositive(pulse_length_m, "pulse_length_m");
  requirePositive(equivalent_width_rad, "equivalent_width_rad");
  if (!(grazing_rad >= 0.0 && grazing_rad < 0.5 * std::numbers::pi)) {
    throw ValueError("ensonified area: grazing_rad must be in [0, π/2), got " + std::to_string(grazing_rad));
  }
  if (!(std::abs(elevation_rad) < 0.5 * std::numbers::pi)) {
    throw ValueError("ensonified area: elevation_rad must be in (−π/2, π/2), got " + std::to_string(elevation_rad));
  }
  return range_m * std::cos(elevation_rad) * equivalent_width_rad * pulse_length_m / std::cos(grazing_rad);
}

double footprintArea_m2(double range_m, double solid_angle_sr, double cos_incidence) {
  requirePositive(range_m, "range_m");
  requirePositive(solid_angle_sr, "solid_angle_sr");
  if (!(cos_incidence > 0.0 && cos_incidence <= 1.0)) {
    throw ValueError("ensonified area: cos_incidence must be in (0, 1], got " + std::to_string(cos_incidence));
  }
  return range_m * range_m * solid_angle_sr / cos_incidence;
}

}  // namespace sonarmap
