/// @file ensonified_area.cpp
/// Pulse-limited and beam-limited ensonified areas (see ensonified_area.hpp).

#include "sonarmap/acoustics/ensonified_area.hpp"

#include <cmath>
#include <numbers>

#include "checks.hpp"

namespace sonarmap {

using acoustics_checks::positive;
using acoustics_checks::require;

double pulseLimitedArea_m2(double range_m, double grazing_rad, double pulse_length_m, double equivalent_width_rad,
                           double elevation_rad) {
  require(positive(range_m), "ensonified area: range_m must be > 0", range_m);
  require(positive(pulse_length_m), "ensonified area: pulse_length_m must be > 0", pulse_length_m);
  require(positive(equivalent_width_rad), "ensonified area: equivalent_width_rad must be > 0", equivalent_width_rad);
  require(grazing_rad >= 0.0 && grazing_rad < 0.5 * std::numbers::pi, "ensonified area: grazing_rad must be in [0, π/2)",
          grazing_rad);
  require(std::abs(elevation_rad) < 0.5 * std::numbers::pi, "ensonified area: elevation_rad must be in (−π/2, π/2)",
          elevation_rad);
  return range_m * std::cos(elevation_rad) * equivalent_width_rad * pulse_length_m / std::cos(grazing_rad);
}

double footprintArea_m2(double range_m, double solid_angle_sr, double cos_incidence) {
  require(positive(range_m), "ensonified area: range_m must be > 0", range_m);
  require(positive(solid_angle_sr), "ensonified area: solid_angle_sr must be > 0", solid_angle_sr);
  require(cos_incidence > 0.0 && cos_incidence <= 1.0, "ensonified area: cos_incidence must be in (0, 1]", cos_incidence);
  return range_m * range_m * solid_angle_sr / cos_incidence;
}

}  // namespace sonarmap
