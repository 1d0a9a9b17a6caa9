#pragma once
// Numerical integration for the acoustics tests: composite Simpson's rule.

#include <cstddef>

namespace sonarmap::test {

/// ∫ f over [a, b] by composite Simpson's rule on `intervals` (made even) intervals.
template <typename Function>
double simpson(Function f, double a, double b, std::size_t intervals = 20000) {
  if (intervals % 2 == 1) ++intervals;
  const double h = (b - a) / static_cast<double>(intervals);
  double sum = f(a) + f(b);
  for (std::size_t i = 1; i < intervals; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * f(a + static_cast<double>(i) * h);
  return sum * h / 3.0;
}

}  // namespace sonarmap::test
