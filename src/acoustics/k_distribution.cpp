/// @file k_distribution.cpp
/// The K distribution of reverberation power (see k_distribution.hpp).

#include "sonarmap/acoustics/k_distribution.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <unsupported/Eigen/SpecialFunctions>

#include "checks.hpp"

namespace sonarmap {
namespace {

using acoustics_checks::require;

static_assert(kMaxKDistributionShape == 100.0, "the message below names the largest shape");

void requireArguments(double relative_power, double shape) {
  require(shape > 0.0 && shape <= kMaxKDistributionShape, "K distribution: shape must be in (0, 100]", shape);
  require(relative_power >= 0.0, "K distribution: relative_power must be >= 0", relative_power);
}

}  // namespace

double kDistributionPdf(double relative_power, double shape) {
  requireArguments(relative_power, shape);
  if (relative_power == 0.0) return shape > 1.0 ? shape / (shape - 1.0) : std::numeric_limits<double>::infinity();
  if (std::isinf(relative_power)) return 0.0;
  const double scaled = shape * relative_power;
  const double bessel = std::cyl_bessel_k(std::abs(shape - 1.0), 2.0 * std::sqrt(scaled));
  // Where K overflows the argument is so small that K_ν(u) ≈ Γ(ν)/2 (2/u)^ν holds (ν = α − 1 > 1
  // there), and the density is its value at 0.
  if (std::isinf(bessel)) return shape / (shape - 1.0);
  const double log_density = std::numbers::ln2 - Eigen::numext::lgamma(shape) - std::log(relative_power) +
                             0.5 * (shape + 1.0) * std::log(scaled) + std::log(bessel);
  return std::exp(log_density);
}

double kDistributionSurvival(double relative_power, double shape) {
  requireArguments(relative_power, shape);
  if (relative_power == 0.0) return 1.0;
  if (std::isinf(relative_power)) return 0.0;
  const double scaled = shape * relative_power;
  const double bessel = std::cyl_bessel_k(shape, 2.0 * std::sqrt(scaled));
  // K overflows only for an argument so small that the mass below it is under 1e-300.
  if (std::isinf(bessel)) return 1.0;
  if (bessel == 0.0) return 0.0;
  return std::exp(std::numbers::ln2 - Eigen::numext::lgamma(shape) + 0.5 * shape * std::log(scaled) + std::log(bessel));
}

}  // namespace sonarmap
