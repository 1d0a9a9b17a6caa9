#pragma once
/// @file column_histogram.hpp
/// Private to detection: percentiles of 8-bit intensities by a 256-bin histogram (O(1) to add a
/// value, O(256) per percentile), for the per-range statistics of calibration.hpp.

#include <array>
#include <cmath>
#include <cstdint>

namespace sonarmap::detail {

class IntensityHistogram {
 public:
  void add(std::uint8_t value) {
    ++counts_[value];
    ++total_;
  }
  /// Removes a value added before.
  void remove(std::uint8_t value) {
    --counts_[value];
    --total_;
  }
  void clear() {
    counts_.fill(0);
    total_ = 0;
  }
  std::uint32_t total() const { return static_cast<std::uint32_t>(total_); }

  /// Several percentiles (0…100, ascending) in one scan: out[i] for percentiles[i]; total() > 0.
  template <std::size_t N>
  std::array<float, N> percentiles(const std::array<double, N>& percentiles) const {
    std::array<float, N> out{};
    std::array<std::uint32_t, N> ranks{};
    for (std::size_t i = 0; i < N; ++i) ranks[i] = rankOf(percentiles[i]);
    std::size_t next = 0;
    std::uint32_t seen = 0;
    for (int v = 0; v < 256 && next < N; ++v) {
      seen += counts_[static_cast<std::size_t>(v)];
      while (next < N && seen > ranks[next]) out[next++] = static_cast<float>(v);
    }
    for (; next < N; ++next) out[next] = 255.0f;
    return out;
  }

  /// The `percentile` (0…100) by the nearest-rank rule on the sorted values; total() > 0.
  float percentile(double percentile) const {
    const std::uint32_t rank = rankOf(percentile);
    std::uint32_t seen = 0;
    for (int v = 0; v < 256; ++v) {
      seen += counts_[static_cast<std::size_t>(v)];
      if (seen > rank) return static_cast<float>(v);
    }
    return 255.0f;
  }

 private:
  std::uint32_t rankOf(double percentile) const {
    return static_cast<std::uint32_t>(std::lround(percentile / 100.0 * (total() - 1)));
  }

  std::array<std::uint32_t, 256> counts_{};
  /// Values added. Of another type than the counts: the compiler then knows that a count's store
  /// leaves it unchanged and keeps it in a register over a loop of add().
  std::uint64_t total_ = 0;
};

}  // namespace sonarmap::detail
