#pragma once
/// @file speckle.hpp
/// The statistics of fully developed speckle: how the power of one echo (or of the noise) in one
/// bin scatters about its mean, in power, in dB and in the counts a log-compressed A/D writes.
///
/// Many scatterers of random phase in a resolution cell sum to a complex Gaussian field, whose
/// power (intensity) is exponential about its mean; the mean of L independent looks of it is
/// Gamma distributed with shape L and mean 1 (Goodman, "Statistical properties of laser speckle
/// patterns", in Dainty (ed.), Laser Speckle and Related Phenomena, Springer 1975): for X = P / P̄,
///     f(x) = L^L x^(L−1) e^(−L x) / Γ(L),  F(x) = P(L, L x),  1 − F(x) = Q(L, L x),
/// P and Q the regularised lower and upper incomplete gamma functions; E[X] = 1, Var[X] = 1/L.
/// L = 1 is the exponential, F(x) = 1 − e^(−x). L need not be a whole number (an effective
/// number of looks of correlated samples). The simulator's speckle and noise factors (the moving
/// mean of speckle_looks exponential draws, msis_simulator.hpp step 5) have this marginal.
///
/// In dB, Y = 10 log10 X (the level re the mean, dB):
///     f_Y(y) = f(x) · x · ln 10 / 10,  x = 10^(y/10),   F_Y(y) = F(10^(y/10)),
///     E[Y] = (10 / ln 10) (ψ(L) − ln L),   Var[Y] = (10 / ln 10)² ψ₁(L),
/// ψ and ψ₁ the digamma and trigamma functions (the log moments of a Gamma variate, E[ln X] =
/// ψ(L) − ln L and Var[ln X] = ψ₁(L): Johnson, Kotz & Balakrishnan, Continuous Univariate
/// Distributions vol. 1, 2nd ed. 1994, ch. 17). L = 1: mean −2.51 dB, standard deviation 5.57 dB,
/// the classic figures of single-look speckle.
///
/// Special functions: Eigen's unsupported SpecialFunctions module (Eigen::numext::igamma, igammac,
/// lgamma, digamma, polygamma; Cephes' algorithms), about 1e-14 relative. Quantiles invert the
/// distribution function numerically (safeguarded Newton in ln x, on the smaller tail): the
/// distribution at the quantile is within about 1e-13 (relative) of the probability asked.

#include <array>

#include "sonarmap/acoustics/receiver_model.hpp"

namespace sonarmap {

/// Density of X = P / P̄ (`relative_power`, ≥ 0) with `looks` looks (> 0): L^L x^(L−1) e^(−Lx) / Γ(L).
/// At x = 0: +infinity for L < 1, 1 for L = 1, 0 for L > 1.
/// @throws ValueError when looks is not > 0 and finite or relative_power is negative or NaN.
double specklePdf(double relative_power, double looks);

/// Pr[X ≤ relative_power] = P(L, L x).
/// @throws ValueError as specklePdf.
double speckleCdf(double relative_power, double looks);

/// Pr[X > relative_power] = Q(L, L x), accurate far into the upper tail (not 1 − speckleCdf).
/// @throws ValueError as specklePdf.
double speckleSurvival(double relative_power, double looks);

/// The x with Pr[X ≤ x] = `probability` ([0, 1]; 0 gives 0, 1 gives +infinity).
/// @throws ValueError when looks is not > 0 and finite or probability is outside [0, 1].
double speckleQuantile(double probability, double looks);

/// The x with Pr[X > x] = `exceedance` ([0, 1]; 0 gives +infinity, 1 gives 0), solved on the upper
/// tail itself so that a tiny exceedance (a false-alarm probability of 10⁻¹²) keeps its precision,
/// which 1 − exceedance would lose. One look: −ln(exceedance).
/// @throws ValueError when looks is not > 0 and finite or exceedance is outside [0, 1].
double speckleSurvivalQuantile(double exceedance, double looks);

/// Density of the level Y = 10 log10 X at `level_db` (dB re the mean power, any real, ±infinity
/// give 0), per dB.
/// @throws ValueError when looks is not > 0 and finite or level_db is NaN.
double speckleLevelPdf(double level_db, double looks);

/// Pr[Y ≤ level_db] = speckleCdf(10^(level_db/10)).
/// @throws ValueError as speckleLevelPdf.
double speckleLevelCdf(double level_db, double looks);

/// Pr[Y > level_db] = speckleSurvival(10^(level_db/10)).
/// @throws ValueError as speckleLevelPdf.
double speckleLevelSurvival(double level_db, double looks);

/// The level with Pr[Y ≤ level] = `probability`, dB re the mean (−infinity for 0, +infinity for 1).
/// @throws ValueError as speckleQuantile.
double speckleLevelQuantile_db(double probability, double looks);

/// E[Y] = (10 / ln 10)(ψ(L) − ln L), dB re the mean power (≤ 0: the mean of the level lies below
/// the level of the mean).
/// @throws ValueError when looks is not > 0 and finite.
double speckleLevelMean_db(double looks);

/// Var[Y] = (10 / ln 10)² ψ₁(L), dB².
/// @throws ValueError when looks is not > 0 and finite.
double speckleLevelVariance_db2(double looks);

/// The mean of a single-look speckle level above its own (1 − `exceedance`) quantile, dB over that
/// quantile: E[Y − y_q | Y > y_q] with Pr[Y > y_q] = exceedance. For exponential power the excess
/// over the quantile is exponential again (memoryless), so with q = −ln(exceedance)
///     E = (10 / ln 10) · e^q · E1(q),   E1 the exponential integral (Abramowitz & Stegun 5.1.1);
/// exceedance 0.1 (the tail beyond the 90th percentile): 1.41 dB. Fully developed speckle has the
/// lightest tail water can have in dB (reverberation, fish and interference only add to it), so
/// this is the least tail the evidence detector grants water it has seen too little of
/// (water_evidence.hpp).
/// @throws ValueError when exceedance is not in (0, 1).
double speckleTailMeanExcess_db(double exceedance);

/// The probability that the A/D (`scale`, receiver_model.hpp) writes `counts` (0…255) for a bin
/// of power P = mean_power · X, X speckle of `looks` looks: the counts are
/// round(a · 10 log10 P + b) clipped to 0…255, a = 255 / ad_span_db, b = −a · ad_low_db
/// (countsOfPower), so counts k in 1…254 take Pr[k − 1/2 ≤ a · 10 log10 P + b < k + 1/2] and the
/// clipped ends take their whole tails: 0 everything below 1/2 (P = 0 included), 255 everything
/// from 254.5 up. `mean_power` ≥ 0 in the units the scale's levels are re (0: counts 0 surely).
/// @throws ValueError when counts is outside 0…255, mean_power is negative or not finite, looks is
///         not > 0 and finite, or the scale is invalid.
double quantisedSpeckleProbability(int counts, double mean_power, double looks, const ReceiverScale& scale);

/// quantisedSpeckleProbability for every counts 0…255 at once (index = counts); they add up to 1.
/// @throws ValueError as quantisedSpeckleProbability.
std::array<double, 256> quantisedSpeckleDistribution(double mean_power, double looks, const ReceiverScale& scale);

}  // namespace sonarmap
