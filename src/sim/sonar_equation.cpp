/// @file sonar_equation.cpp
/// A flat seabed's echo power in closed form (see sonar_equation.hpp).

#include "sonarmap/sim/sonar_equation.hpp"

#include <cmath>
#include <numbers>

#include "beam_echo.hpp"
#include "receiver.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {

double flatSeabedEchoPower(const MsisHeadOptions& head, const EchoModelOptions& echo, double altitude_m,
                           double reflectivity, double range_m, double tilt_rad) {
  head.validate();
  echo.validate();
  if (!(altitude_m > 0.0) || !std::isfinite(altitude_m)) throw ValueError("altitude_m must be > 0");
  if (!(range_m > 0.0) || !std::isfinite(range_m)) throw ValueError("range_m must be > 0");
  if (!(reflectivity >= 0.0 && reflectivity <= 1.0)) throw ValueError("reflectivity must be in [0, 1]");
  if (!(tilt_rad >= 0.0 && tilt_rad < 0.5 * std::numbers::pi)) throw ValueError("tilt_rad must be in [0, pi/2)");
  if (range_m <= altitude_m) return 0.0;
  const double width_rad = head.vertical_beam_width_rad;
  const double span_rad = echo.vertical.extent * width_rad;
  const double step_rad = span_rad / echo.vertical.rays;
  // V: the two-way vertical pattern times cos v over the echo model's rays (their normalisation).
  double pattern_integral = 0.0;
  for (int j = 0; j < echo.vertical.rays; ++j) {
    const double v = sim::apertureRayAngle(echo.vertical, width_rad, j);
    const double p = sim::oneWayPattern(v, width_rad, echo.vertical.exponent);
    pattern_integral += p * p * std::cos(v) * step_rad;
  }
  const double sin_grazing = altitude_m / range_m;
  const double grazing_rad = std::asin(sin_grazing);
  const double elevation_rad = tilt_rad - grazing_rad;  // in the head's frame
  if (std::abs(elevation_rad) > 0.5 * span_rad) return 0.0;  // outside the rays
  const double p = sim::oneWayPattern(elevation_rad, width_rad, echo.vertical.exponent);
  const double per_metre = reflectivity * p * p * std::cos(elevation_rad) *
                           std::pow(sin_grazing, echo.lambert_exponent + 1.0) /
                           (altitude_m * pattern_integral * std::cos(grazing_rad));
  // The receiver sums the energy of a pulse length of bins.
  return per_metre * sim::pulseBins(head, echo) * head.binLength_m();
}

double meanNoisePower(const EchoModelOptions& echo, double range_m) {
  echo.validate();
  if (!(range_m > 0.0) || !std::isfinite(range_m)) throw ValueError("range_m must be > 0");
  return std::pow(10.0, echo.noise_level_db / 10.0) * sim::tvgGain(echo, range_m);
}

}  // namespace sonarmap
