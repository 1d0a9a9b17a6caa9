#pragma once
/// @file statistics.hpp
/// Order statistics shared by the evaluator, the live command and the benchmarks.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace sonarmap {

/// The value at fraction `fraction` ∈ [0, 1] of the sorted `values`, interpolated linearly between
/// the order statistics at 0-based rank (n − 1) · fraction (NumPy's default "linear" percentile; the
/// median of an even count is the mean of the middle two). 0 when `values` is empty. Reorders
/// `values` (std::nth_element, O(n)); units are those of the values.
inline double percentile(std::vector<double>& values, double fraction) {
  if (values.empty()) return 0.0;
  const double rank = std::clamp(fraction, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(rank));
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(below);
  std::nth_element(values.begin(), at, values.end());
  if (below + 1 >= values.size()) return *at;
  const double next = *std::min_element(at + 1, values.end());
  return *at + (rank - static_cast<double>(below)) * (next - *at);
}

}  // namespace sonarmap
