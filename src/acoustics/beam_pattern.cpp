/// @file beam_pattern.cpp
/// The beam pattern and the integrals over it (see beam_pattern.hpp).

#include "sonarmap/acoustics/beam_pattern.hpp"

#include <cmath>
#include <numbers>

#include "checks.hpp"

namespace sonarmap {
namespace {

using acoustics_checks::positive;
using acoustics_checks::require;

bool validWidth(double width_rad) { return width_rad > 0.0 && width_rad < std::numbers::pi; }

}  // namespace

void BeamPattern::validate() const {
  require(validWidth(width_rad), "beam pattern: width_rad must be in (0, π)", width_rad);
  require(positive(exponent), "beam pattern: exponent must be > 0", exponent);
}

double oneWayPattern(const BeamPattern& pattern, double angle_rad) {
  pattern.validate();
  require(!std::isnan(angle_rad), "beam pattern: the angle is NaN");
  return std::exp2(-std::pow(std::abs(2.0 * angle_rad / pattern.width_rad), pattern.exponent));
}

double twoWayPattern(const BeamPattern& pattern, double angle_rad) {
  const double one_way = oneWayPattern(pattern, angle_rad);
  return one_way * one_way;
}

void TransducerPattern::validate() const {
  require(validWidth(horizontal.width_rad), "beam pattern, horizontal: width_rad must be in (0, π)", horizontal.width_rad);
  require(positive(horizontal.exponent), "beam pattern, horizontal: exponent must be > 0", horizontal.exponent);
  require(validWidth(vertical.width_rad), "beam pattern, vertical: width_rad must be in (0, π)", vertical.width_rad);
  require(positive(vertical.exponent), "beam pattern, vertical: exponent must be > 0", vertical.exponent);
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
  require(rays >= 1, "aperture sampling: rays must be >= 1", rays);
  require(positive(extent), "aperture sampling: extent must be > 0", extent);
}

double apertureStep_rad(const ApertureSampling& sampling, double width_rad) {
  sampling.validate();
  require(validWidth(width_rad), "aperture sampling: width_rad must be in (0, π)", width_rad);
  const double span_rad = sampling.extent * width_rad;
  return span_rad / sampling.rays;
}

double apertureAngle_rad(const ApertureSampling& sampling, double width_rad, int index) {
  const double step_rad = apertureStep_rad(sampling, width_rad);
  require(index >= 0 && index < sampling.rays, "aperture sampling: index must be in 0 … rays − 1", index);
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
