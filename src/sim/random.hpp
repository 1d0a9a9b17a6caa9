#pragma once
/// @file random.hpp
/// Private to the simulator: random numbers that do not depend on the standard library's
/// distribution implementations (only std::mt19937_64 itself, whose output the standard fixes).

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace sonarmap::sim {

/// Exponential, uniform and Gaussian draws from one std::mt19937_64 stream.
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  /// Exponential with mean 1 by inversion: −log(v), v = (k + 1) · 2⁻⁵³ in (0, 1], k the top 53
  /// bits of one 64-bit draw (v is uniform on that grid; never 0, so the result is finite, ≤ 36.7).
  double exponential() { return -std::log(uniform()); }

  /// Uniform on (0, 1]: (k + 1) · 2⁻⁵³, k the top 53 bits of one 64-bit draw.
  double uniform() { return static_cast<double>((engine_() >> 11) + 1) * 0x1.0p-53; }

  /// Standard normal (mean 0, σ 1) by the Box–Muller transform (Box & Muller 1958):
  /// √(−2 log u₁) · cos(2π u₂) from two uniform() draws, in that order; the sine half is not kept,
  /// so every call takes exactly two 64-bit draws.
  double gaussian() {
    const double radius = std::sqrt(-2.0 * std::log(uniform()));
    return radius * std::cos(2.0 * std::numbers::pi * uniform());
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace sonarmap::sim
