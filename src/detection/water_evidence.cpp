/// @file water_evidence.cpp
/// The water's measured excess distribution and each bin's evidence (see water_evidence.hpp).

#include "sonarmap/detection/water_evidence.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

WaterEvidence::WaterEvidence(std::span<const std::uint32_t> histogram) {
  if (histogram.size() != static_cast<std::size_t>(kExcessValues)) {
    throw ValueError("WaterEvidence: the histogram must hold " + std::to_string(kExcessValues) + " excess values, got " +
                     std::to_string(histogram.size()));
  }
  for (const std::uint32_t count : histogram) samples_ += count;
  if (samples_ == 0) return;
  const auto total = static_cast<double>(samples_);
  // The body's end: the 90th percentile (nearest rank).
  const auto rank = static_cast<std::uint64_t>(std::llround(0.9 * (total - 1.0)));
  std::uint64_t seen = 0;
  int q = 0;
  for (; q < kExcessValues; ++q) {
    seen += histogram[static_cast<std::size_t>(q)];
    if (seen > rank) break;
  }
  // The tail beyond it: its share and mean excess.
  std::uint64_t tail_samples = 0;
  double tail_excess = 0.0;
  for (int i = q + 1; i < kExcessValues; ++i) {
    tail_samples += histogram[static_cast<std::size_t>(i)];
    tail_excess += static_cast<double>(histogram[static_cast<std::size_t>(i)]) * (i - q);
  }
  body_end_ = q - 255;
  tail_scale_ = tail_samples > 0 ? std::max(1.0, tail_excess / static_cast<double>(tail_samples)) : 1.0;
  const double tail_share = std::max(static_cast<double>(tail_samples), 1.0) / total;
  const double ln_uniform = -std::log(256.0);
  const double ln_min = std::log(kMinProbability);
  // Per count of the tail: P_t (1 − e^(−1/m)) e^(−(x − 1)/m) at x counts beyond the body's end.
  const double ln_tail_first = std::log(tail_share) + std::log1p(-std::exp(-1.0 / tail_scale_));
  for (int i = kExcessValues - 1; i >= 0; --i) {
    double ln_p;
    if (i > q) {
      ln_p = ln_tail_first - (i - q - 1) / tail_scale_;
    } else {
      const std::uint32_t count = histogram[static_cast<std::size_t>(i)];
      ln_p = count > 0 ? std::log(static_cast<double>(count) / total) : -INFINITY;
    }
    const auto llr = static_cast<float>(ln_uniform - std::max(ln_p, ln_min));
    // Non-decreasing in the excess: a gap in the histogram takes the next louder value's evidence.
    llr_[static_cast<std::size_t>(i)] = i + 1 < kExcessValues ? std::min(llr, llr_[static_cast<std::size_t>(i) + 1]) : llr;
  }
}

}  // namespace sonarmap
