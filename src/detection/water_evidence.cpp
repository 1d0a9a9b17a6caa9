/// @file water_evidence.cpp
/// The water's measured excess distribution and each bin's evidence (see water_evidence.hpp).

#include "sonarmap/detection/water_evidence.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// ln k for the whole counts a band's histogram holds, looked up (k < 2¹⁶; beyond, std::log): the
/// evidence is rebuilt at every range bin of every sweep.
double lnCount(std::uint32_t k) {
  static const std::vector<double> table = [] {
    std::vector<double> t(1U << 16);
    t[0] = -INFINITY;
    for (std::size_t i = 1; i < t.size(); ++i) t[i] = std::log(static_cast<double>(i));
    return t;
  }();
  return k < table.size() ? table[k] : std::log(static_cast<double>(k));
}

}  // namespace

WaterEvidence::WaterEvidence(std::span<const std::uint32_t> histogram, double min_tail_scale_counts) {
  if (histogram.size() != static_cast<std::size_t>(kExcessValues)) {
    throw ValueError("WaterEvidence: the histogram must hold " + std::to_string(kExcessValues) + " excess values, got " +
                     std::to_string(histogram.size()));
  }
  if (std::isnan(min_tail_scale_counts)) throw ValueError("WaterEvidence: the least tail scale is NaN");
  const double least_scale = std::max(1.0, min_tail_scale_counts);
  // The evidence is rebuilt at every range bin of every sweep: whole-count sums in integers (exact,
  // and equal to summing them in double, exact below 2⁵³), the tail's from the histogram's moment
  // Σ count × i instead of a pass over the tail.
  std::uint64_t moment = 0;
  for (std::size_t i = 0; i < histogram.size(); ++i) {
    samples_ += histogram[i];
    moment += static_cast<std::uint64_t>(histogram[i]) * i;
  }
  if (samples_ == 0) return;
  const auto total = static_cast<double>(samples_);
  while (histogram[static_cast<std::size_t>(lowest_index_)] == 0) ++lowest_index_;  // samples_ > 0: one is not
  // The body's end: the 90th percentile (nearest rank).
  const auto rank = static_cast<std::uint64_t>(std::llround(0.9 * (total - 1.0)));
  std::uint64_t seen = 0;
  std::uint64_t seen_moment = 0;
  int q = lowest_index_;
  for (; q < kExcessValues; ++q) {
    const std::uint64_t count = histogram[static_cast<std::size_t>(q)];
    seen += count;
    seen_moment += count * static_cast<std::uint64_t>(q);
    if (seen > rank) break;
  }
  // The tail beyond it: its share and mean excess, Σ count × (i − q) over i > q.
  const std::uint64_t tail_samples = samples_ - seen;
  const auto tail_excess = static_cast<double>(moment - seen_moment - static_cast<std::uint64_t>(q) * tail_samples);
  body_end_ = q - 255;
  body_index_ = q;
  tail_scale_ = tail_samples > 0 ? std::max(least_scale, tail_excess / static_cast<double>(tail_samples)) : least_scale;
  const double tail_share = std::max(static_cast<double>(tail_samples), 1.0) / total;
  const double ln_uniform = -std::log(256.0);
  const double ln_total = std::log(total);
  const double ln_min = std::log(kMinProbability);
  // Per count of the tail: P_t (1 − e^(−1/m)) e^(−(x − 1)/m) at x counts beyond the body's end,
  // λ = ln(1/256) − ln p rising by 1/m a count up to ln(1/256) − ln p_min (logLikelihoodRatio).
  max_llr_ = ln_uniform - ln_min;
  tail_first_llr_ = ln_uniform - (std::log(tail_share) + std::log1p(-std::exp(-1.0 / tail_scale_)));
  // The body, non-decreasing in the excess: a gap in the histogram takes the next louder value's
  // evidence, the body's end at most the tail's first.
  float next = static_cast<float>(std::min(tail_first_llr_, max_llr_));
  for (int i = q; i >= lowest_index_; --i) {
    const double ln_p = lnCount(histogram[static_cast<std::size_t>(i)]) - ln_total;
    next = std::min(static_cast<float>(ln_uniform - std::max(ln_p, ln_min)), next);
    llr_[static_cast<std::size_t>(i)] = next;
  }
}

}  // namespace sonarmap
