#pragma once
/// @file random.hpp
/// Private to the simulator: random numbers that do not depend on the standard library's
/// distribution implementations (only std::mt19937_64 itself, whose output the standard fixes).

#include <cmath>
#include <cstdint>
#include <random>

namespace sonarmap::sim {

/// Exponential draws from one std::mt19937_64 stream.
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  /// Exponential with mean 1 by inversion: −log(v), v = (k + 1) · 2⁻⁵³ in (0, 1], k the top 53
  /// bits of one 64-bit draw (v is uniform on that grid; never 0, so the result is finite, ≤ 36.7).
  double exponential() { return -std::log(static_cast<double>((engine_() >> 11) + 1) * 0x1.0p-53); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace sonarmap::sim
