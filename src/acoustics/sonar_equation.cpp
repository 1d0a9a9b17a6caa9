/// @file sonar_equation.cpp
/// A patch's echo and a flat seabed's echo in closed form (see sonar_equation.hpp).

#include "sonarmap/acoustics/sonar_equation.hpp"

#include <cmath>
#include <numbers>

#include "checks.hpp"
#include "sonarmap/acoustics/receiver_model.hpp"

namespace sonarmap {

using acoustics_checks::nonNegative;
using acoustics_checks::positive;
using acoustics_checks::require;

double surfaceEchoPower(double two_way_pattern, double scatter_per_area, double area_m2, double range_m,
                        double equivalent_solid_angle_sr) {
  require(two_way_pattern >= 0.0 && two_way_pattern <= 1.0, "sonar equation: two_way_pattern must be in [0, 1]");
  require(nonNegative(scatter_per_area), "sonar equation: scatter_per_area must be >= 0");
  require(nonNegative(area_m2), "sonar equation: area_m2 must be >= 0");
  require(positive(range_m), "sonar equation: range_m must be > 0");
  require(positive(equivalent_solid_angle_sr), "sonar equation: equivalent_solid_angle_sr must be > 0");
  return two_way_pattern * scatter_per_area * area_m2 / (range_m * range_m * equivalent_solid_angle_sr);
}

void FlatSeabedHead::validate() const {
  vertical.validate();
  vertical_sampling.validate();
  require(positive(pulse_length_m), "flat seabed head: pulse_length_m must be > 0", pulse_length_m);
  require(positive(bin_length_m), "flat seabed head: bin_length_m must be > 0", bin_length_m);
}

void FlatSeabed::validate() const {
  require(positive(altitude_m), "flat seabed: altitude_m must be > 0", altitude_m);
  require(reflectivity >= 0.0 && reflectivity <= 1.0,
          "flat seabed: reflectivity must be in [0, 1]", reflectivity);
  require(std::isfinite(lambert_exponent) && lambert_exponent >= 1.0,
          "flat seabed: lambert_exponent must be >= 1", lambert_exponent);
}

double flatSeabedEchoPower(const FlatSeabedHead& head, const FlatSeabed& seabed, double range_m, double tilt_rad) {
  head.validate();
  seabed.validate();
  require(positive(range_m), "flat seabed: range_m must be > 0", range_m);
  require(tilt_rad >= 0.0 && tilt_rad < 0.5 * std::numbers::pi,
          "flat seabed: tilt_rad must be in [0, π/2)", tilt_rad);
  if (range_m <= seabed.altitude_m) return 0.0;
  const double span_rad = head.vertical_sampling.extent * head.vertical.width_rad;
  const double pattern_integral = elevationPatternIntegral(head.vertical, head.vertical_sampling);  // V
  const double sin_grazing = seabed.altitude_m / range_m;
  const double grazing_rad = std::asin(sin_grazing);
  const double elevation_rad = tilt_rad - grazing_rad;  // in the head's frame
  if (std::abs(elevation_rad) > 0.5 * span_rad) return 0.0;  // outside the aperture's cells
  const double p = oneWayPattern(head.vertical, elevation_rad);
  const double per_metre = seabed.reflectivity * p * p * std::cos(elevation_rad) *
                           std::pow(sin_grazing, seabed.lambert_exponent + 1.0) /
                           (seabed.altitude_m * pattern_integral * std::cos(grazing_rad));
  // The receiver sums the energy of a pulse length of bins.
  return per_metre * pulseBins(head.pulse_length_m, head.bin_length_m) * head.bin_length_m;
}

}  // namespace sonarmap
