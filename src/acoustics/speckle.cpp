/// @file speckle.cpp
/// Gamma speckle in power, in dB and in A/D counts (see speckle.hpp).

#include "sonarmap/acoustics/speckle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <unsupported/Eigen/SpecialFunctions>

#include "checks.hpp"
#include "sonarmap/acoustics/decibels.hpp"

namespace sonarmap {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// dB per neper of power: 10 / ln 10.
constexpr double kDbPerNeper = 10.0 / std::numbers::ln10;

using acoustics_checks::nonNegative;
using acoustics_checks::positive;
using acoustics_checks::require;

void requireLooks(double looks) { require(positive(looks), "speckle: looks must be > 0", looks); }

void requireRelativePower(double relative_power) {
  require(relative_power >= 0.0, "speckle: relative_power must be >= 0", relative_power);
}

void requireProbability(double probability) {
  require(probability >= 0.0 && probability <= 1.0, "speckle: probability must be in [0, 1]", probability);
}

void requireLevel(double level_db) { require(!std::isnan(level_db), "speckle: level_db is NaN"); }

/// ln of the density of ln X at t = ln x: ln(f(x) · x) = L ln L + L t − L eᵗ − ln Γ(L).
double logDensityOfLog(double t, double looks) {
  return looks * std::log(looks) + looks * t - looks * std::exp(t) - Eigen::numext::lgamma(looks);
}

/// Both tails at one relative power, each computed where it is the smaller one (so that the mass
/// between two points is a difference of small numbers, not of numbers near 1).
struct Tails {
  double below = 0.0;  // Pr[X ≤ x]
  double above = 1.0;  // Pr[X > x]
};

Tails tailsAt(double relative_power, double looks) {
  Tails tails;
  if (relative_power < 1.0) {
    tails.below = Eigen::numext::igamma(looks, looks * relative_power);
    tails.above = 1.0 - tails.below;
  } else {
    tails.above = Eigen::numext::igammac(looks, looks * relative_power);
    tails.below = 1.0 - tails.above;
  }
  return tails;
}

/// Pr[lower < X ≤ upper] for lower ≤ upper.
double massBetween(const Tails& lower, const Tails& upper) {
  double mass = 0.0;
  if (lower.above < 0.5) {
    mass = lower.above - upper.above;
  } else if (upper.below < 0.5) {
    mass = upper.below - lower.below;
  } else {
    mass = 1.0 - lower.below - upper.above;
  }
  return std::max(mass, 0.0);
}

void requireQuantisedArguments(double mean_power, double looks, const ReceiverScale& scale) {
  requireLooks(looks);
  scale.validate();
  require(nonNegative(mean_power), "speckle: mean_power must be >= 0 and finite", mean_power);
}

/// The tails at the boundary below counts k (1…255): intensity k − 1/2, as a power relative to the mean.
Tails boundaryTails(int counts, double mean_level_db, double looks, const ReceiverScale& scale) {
  const double level_db = levelOfIntensity(scale, counts - 0.5);
  return tailsAt(powerOfLevel(level_db - mean_level_db), looks);
}

}  // namespace

double specklePdf(double relative_power, double looks) {
  requireLooks(looks);
  requireRelativePower(relative_power);
  if (relative_power == 0.0) return looks < 1.0 ? kInfinity : (looks == 1.0 ? 1.0 : 0.0);
  if (std::isinf(relative_power)) return 0.0;
  return std::exp(logDensityOfLog(std::log(relative_power), looks)) / relative_power;
}

double speckleCdf(double relative_power, double looks) {
  requireLooks(looks);
  requireRelativePower(relative_power);
  if (std::isinf(relative_power)) return 1.0;
  return Eigen::numext::igamma(looks, looks * relative_power);
}

double speckleSurvival(double relative_power, double looks) {
  requireLooks(looks);
  requireRelativePower(relative_power);
  if (std::isinf(relative_power)) return 0.0;
  return Eigen::numext::igammac(looks, looks * relative_power);
}

namespace {
/// The x whose lower tail (upper = false) or upper tail (upper = true) holds `target` ∈ (0, 1);
double solveQuantile(double target, bool upper, double looks) {
  // Solve g(t) = 0 for t = ln x, g increasing: the tail against its target.
  auto g = [&](double t) {
    const double scaled = looks * std::exp(t);
    return upper ? target - Eigen::numext::igammac(looks, scaled) : Eigen::numext::igamma(looks, scaled) - target;
  };
  // Start: Wilson–Hilferty's cube-root normal approximation, or where it fails (few looks, far
  // lower tail) the lower tail's leading term F ≈ (L x)^L / Γ(L + 1).
  const double c = 1.0 / (9.0 * looks);
  const double normal = upper ? -Eigen::numext::ndtri(target) : Eigen::numext::ndtri(target);  // Φ⁻¹(probability)
  const double cube_root = 1.0 - c + normal * std::sqrt(c);
  double t = cube_root > 0.05 ? 3.0 * std::log(cube_root)
                              : (std::log(target) + Eigen::numext::lgamma(looks + 1.0)) / looks - std::log(looks);
  // Bracket the root, then Newton steps that fall back to bisection when they leave the bracket.
  double low = t, high = t;
  for (double step = 1.0; g(low) > 0.0 && step < 4096.0; step *= 2.0) low = t - step;
  for (double step = 1.0; g(high) < 0.0 && step < 4096.0; step *= 2.0) high = t + step;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double value = g(t);
    if (value == 0.0) break;
    (value < 0.0 ? low : high) = t;
    double next = t - value / std::exp(logDensityOfLog(t, looks));
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    const bool converged = std::abs(next - t) <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t));
    t = next;
    if (converged) break;
  }
  return std::exp(t);
}
}  // namespace

double speckleQuantile(double probability, double looks) {
  requireLooks(looks);
  requireProbability(probability);
  if (probability == 0.0) return 0.0;
  if (probability == 1.0) return kInfinity;
  const bool upper = probability > 0.5;
  return solveQuantile(upper ? 1.0 - probability : probability, upper, looks);
}

double speckleSurvivalQuantile(double exceedance, double looks) {
  requireLooks(looks);
  requireProbability(exceedance);
  if (exceedance == 0.0) return kInfinity;
  if (exceedance == 1.0) return 0.0;
  if (exceedance >= 0.5) return speckleQuantile(1.0 - exceedance, looks);
  return solveQuantile(exceedance, true, looks);
}

double speckleLevelPdf(double level_db, double looks) {
  requireLooks(looks);
  requireLevel(level_db);
  if (std::isinf(level_db)) return 0.0;
  return std::exp(logDensityOfLog(level_db / kDbPerNeper, looks)) / kDbPerNeper;
}

double speckleLevelCdf(double level_db, double looks) {
  requireLevel(level_db);
  return speckleCdf(powerOfLevel(level_db), looks);
}

double speckleLevelSurvival(double level_db, double looks) {
  requireLevel(level_db);
  return speckleSurvival(powerOfLevel(level_db), looks);
}

double speckleLevelQuantile_db(double probability, double looks) {
  return levelOfPower(speckleQuantile(probability, looks));
}

double speckleLevelMean_db(double looks) {
  requireLooks(looks);
  return kDbPerNeper * (Eigen::numext::digamma(looks) - std::log(looks));
}

double speckleLevelVariance_db2(double looks) {
  requireLooks(looks);
  return kDbPerNeper * kDbPerNeper * Eigen::numext::polygamma(1.0, looks);
}

double speckleTailMeanExcess_db(double exceedance) {
  require(exceedance > 0.0 && exceedance < 1.0, "speckle: exceedance must be in (0, 1)", exceedance);
  const double q = -std::log(exceedance);
  return kDbPerNeper * std::exp(q) * -std::expint(-q);  // E1(q) = −Ei(−q)
}

double quantisedSpeckleProbability(int counts, double mean_power, double looks, const ReceiverScale& scale) {
  requireQuantisedArguments(mean_power, looks, scale);
  require(counts >= 0 && counts <= 255, "speckle: counts must be in 0…255", counts);
  if (mean_power == 0.0) return counts == 0 ? 1.0 : 0.0;
  const double mean_level_db = levelOfPower(mean_power);
  if (counts == 0) return boundaryTails(1, mean_level_db, looks, scale).below;
  if (counts == 255) return boundaryTails(255, mean_level_db, looks, scale).above;
  return massBetween(boundaryTails(counts, mean_level_db, looks, scale),
                     boundaryTails(counts + 1, mean_level_db, looks, scale));
}

std::array<double, 256> quantisedSpeckleDistribution(double mean_power, double looks, const ReceiverScale& scale) {
  requireQuantisedArguments(mean_power, looks, scale);
  std::array<double, 256> probabilities{};
  if (mean_power == 0.0) {
    probabilities[0] = 1.0;
    return probabilities;
  }
  const double mean_level_db = levelOfPower(mean_power);
  Tails lower = boundaryTails(1, mean_level_db, looks, scale);
  probabilities[0] = lower.below;
  for (int counts = 1; counts < 255; ++counts) {
    const Tails upper = boundaryTails(counts + 1, mean_level_db, looks, scale);
    probabilities[static_cast<std::size_t>(counts)] = massBetween(lower, upper);
    lower = upper;
  }
  probabilities[255] = lower.above;
  return probabilities;
}

}  // namespace sonarmap
