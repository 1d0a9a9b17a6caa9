#pragma once
/// @file k_distribution.hpp
/// The K distribution of reverberation power from a few discrete scatterers per resolution cell
/// (fish, bubbles, patchy seabed): heavier-tailed than fully developed speckle (speckle.hpp).
///
/// For power relative to its mean, X = P / P̄, with shape α > 0 (Abraham & Lyons, "Novel physical
/// interpretations of K-distributed reverberation", IEEE J. Oceanic Eng. 27(4) 800–813, 2002:
/// α is proportional to the number of scatterers in the cell),
///     f(x) = 2 / (Γ(α) x) · (α x)^((α+1)/2) · K_(α−1)(2 √(α x)),
///     Pr[X > x] = 2 / Γ(α) · (α x)^(α/2) · K_α(2 √(α x)),
/// K_ν the modified Bessel function of the second kind; E[X] = 1, E[X²] = 2 (1 + 1/α). As α → ∞
/// it tends to single-look speckle (exponential). The simulator's water scatterers
/// (EchoModelOptions::water_scatterers_per_m) make such a tail from a Poisson number of discrete
/// echoes per bin; their power is not exactly K distributed.
///
/// Special functions: std::cyl_bessel_k (C++17 mathematical special functions, libstdc++) and
/// Eigen's ln Γ (Eigen::numext::lgamma, reentrant).

namespace sonarmap {

/// Largest shape the functions accept (beyond it the distribution is single-look speckle to
/// within the accuracy of the Bessel functions).
inline constexpr double kMaxKDistributionShape = 100.0;

/// Density of X = P / P̄ (`relative_power`, ≥ 0) for shape `shape` (in (0, kMaxKDistributionShape]).
/// At x = 0: α / (α − 1) for α > 1, +infinity for α ≤ 1.
/// @throws ValueError when the shape is outside its range or relative_power is negative or NaN.
double kDistributionPdf(double relative_power, double shape);

/// Pr[X > relative_power].
/// @throws ValueError as kDistributionPdf.
double kDistributionSurvival(double relative_power, double shape);

}  // namespace sonarmap
