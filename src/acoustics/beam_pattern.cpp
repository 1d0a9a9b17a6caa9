/// @file beam_pattern.cpp
/// The beam pattern and the integrals over it (see beam_pattern.hpp).

#include "sonarmap/acoustics/beam_pattern.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

void require(bool valid, const std::string& what) {
  if (!valid) throw ValueError(what);
}

void validateWidth(double width_rad, const std::string& what) {
  require(std::isfinite(width_rad) && width_rad > 0.0 && width_rad < std::numbers::pi,
          what + " must be in (0, π), got " + std::to_string(width_rad));
}

void validatePattern(const BeamPattern& pattern, const std::string& prefix) {
  validateWidth(pattern.width_rad, prefix + "width_rad");
  require(std::isfinite(pattern.exponent) && pattern.exponent > 0.0,
          prefix + "exponent must be > 0, got " + std::to_string(pattern.exponent));
}

void requireAngle(double angle_rad) { require(!std::isnan(angle_rad), "beam pattern: the angle is NaN"); }

}  // namespace

void BeamPattern::validate() const { validatePattern(*this, "beam pattern: "); }

double oneWayPattern(const BeamPattern& pattern, double angle_rad) {
  pattern.validate();
  requireAngle(angle_rad);
  return std::exp2(-std::pow(std::abs(2.0 * angle_rad / pattern.width_rad), pattern.exponent));
}

double twoWayPattern(const BeamPattern& pattern, double angle_rad) {
  const double one_way = oneWayPattern(pattern, angle_rad);
  return one_way * one_way;
}

void TransducerPattern::validate() const {
  validatePattern(horizontal, "beam pattern, horizontal: ");
  validatePattern(vertical, "beam pattern, vertical: ");
}

double oneWayPattern(const TransducerPattern& pattern, double horizontal_rad, double elevation_rad) {
  return oneWayPattern(pattern.horizontal, horizontal_rad) * oneWayPattern(pattern.vertical, elevation_rad);
}

double twoWayPattern(const TransducerPattern& pattern, double horizontal_rad, double elevation_rad) {
  const double one_way = oneWayPattern(pattern, horizontal_rad, elevation_rad);
  return one_way * one_way;
}

double equivalentBeamWidth_rad(const BeamPattern& pattern) {
  pattern.validate();
  // p² = exp(−2 ln 2 |x|^n), x = 2θ/W: ∫ exp(−a|x|^n) dx = 2 Γ(1 + 1/n) a^(−1/n), dθ = (W/2) dx.
  const double inverse_exponent = 1.0 / pattern.exponent;
  return pattern.width_rad * std::tgamma(1.0 + inverse_exponent) *
         std::pow(2.0 * std::numbers::ln2, -inverse_exponent);
}

void ApertureSampling::validate() const {
  require(rays >= 1, "aperture sampling: rays must be >= 1, got " + std::to_string(rays));
  require(std::isfinite(extent) && extent > 0.0, "aperture sampling: extent must be > 0, got " + std::to_string(extent));
}

double apertureStep_rad(const ApertureSampling& sampling, double width_rad) {
  sampling.validate();
  validateWidth(width_rad, "aperture sampling: width_rad");
  const double span_rad = sampling.extent * width_rad;
  return span_rad / sampling.rays;
}

double apertureAngle_rad(const ApertureSampling& sampling, double width_rad, int index) {
  const double step_rad = apertureStep_rad(sampling, width_rad);
  require(index >= 0 && index < sampling.rays, "aperture sampling: index " + std::to_string(index) +
                                                   " outside 0 … " + std::to_string(sampling.rays - 1));
  const double span_rad = sampling.extent * width_rad;
  return -0.5 * span_rad + (index + 0.5) * step_rad;
}

double elevationPatternIntegral(const BeamPattern& vertical, const ApertureSampling& sampling) {
  vertical.validate();
  const double step_rad = apertureStep_rad(sampling, vertical.width_rad);
  double integral = 0.0;
  for (int j = 0; j < sampling.rays; ++j) {
    const double v = apertureAngle_rad(sampling, vertical.width_rad, j);
    const double p = oneWayPattern(vertical, v);
    integral += p * p * std::cos(v) * step_rad;
  }
  return integral;
}

}  // namespace sonarmap
