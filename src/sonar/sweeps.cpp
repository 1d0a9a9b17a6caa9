/// @file sweeps.cpp
/// splitSweeps (see sweeps.hpp).

#include "sonarmap/sonar/sweeps.hpp"

#include <cmath>
#include <numbers>

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Slack when comparing the accumulated turn with 2π: bearings read from single-precision
/// degrees carry ~1e-6 rad of rounding, far below any head step (≥ 0.05625° ≈ 1e-3 rad).
constexpr double kFullTurnSlack_rad = 1e-5;

/// Bearing difference to − from, wrapped to (−π, π].
double wrappedStep(double from_rad, double to_rad) {
  double step = std::remainder(to_rad - from_rad, kTwoPi);
  return step <= -std::numbers::pi ? step + kTwoPi : step;
}

/// State of the sweep being built.
struct SweepState {
  int direction = 0;        ///< +1 counter-clockwise, −1 clockwise, 0 not known yet
  double turned_rad = 0.0;  ///< accumulated |step| since the sweep's first beam
};

/// Whether beam `next` (reached from `prev` by `step`) starts a new sweep.
bool startsNewSweep(const SweepState& state, double step, const Beam& prev, const Beam& next) {
  if (next.bin_length_m != prev.bin_length_m) return true;
  const int sign = step > 0.0 ? 1 : (step < 0.0 ? -1 : 0);
  if (sign != 0 && state.direction != 0 && sign != state.direction) return true;
  return state.turned_rad + std::abs(step) >= kTwoPi - kFullTurnSlack_rad;
}

}  // namespace

std::vector<SweepRange> splitSweeps(const std::vector<Beam>& beams) {
  std::vector<SweepRange> sweeps;
  if (beams.empty()) return sweeps;
  SweepRange current{0, 1};
  SweepState state;
  for (std::size_t i = 1; i < beams.size(); ++i) {
    const double step = wrappedStep(beams[i - 1].bearing_rad, beams[i].bearing_rad);
    if (startsNewSweep(state, step, beams[i - 1], beams[i])) {
      sweeps.push_back(current);
      current = SweepRange{i, i + 1};
      state = SweepState{};
      continue;
    }
    if (state.direction == 0 && step != 0.0) state.direction = step > 0.0 ? 1 : -1;
    state.turned_rad += std::abs(step);
    current.last_exclusive = i + 1;
  }
  sweeps.push_back(current);
  return sweeps;
}

}  // namespace sonarmap
