#pragma once
// A least-significant-digit radix sort of 64-bit integers by their high bits (Knuth, TAOCP vol. 3,
// §5.2.5), for the mapper's per-sweep lists of cell codes. Internal to the library.
//
// On the lists a sweep produces (10^5 codes whose high bits span a small box of keys) it is
// several times faster than std::sort: one pass counts every byte of every value, and a byte that
// is the same in all values needs no pass at all.

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace sonarmap {

/// Sorts `values` ascending by bits [low_bit, 64) of each value; values equal there keep their
/// input order (stable), whatever their bits below `low_bit`. One pass per byte that differs
/// between values; `scratch` is working memory, reused between calls.
/// @param low_bit 0 … 64, a multiple of 8. @throws std::bad_alloc.
inline void radixSortHighBits(std::vector<std::uint64_t>& values, int low_bit, std::vector<std::uint64_t>& scratch) {
  constexpr int kBytes = 8;
  const int first_byte = low_bit / 8;
  if (values.size() < 2 || first_byte >= kBytes) return;
  std::array<std::array<std::size_t, 256>, kBytes> counts{};
  for (const std::uint64_t v : values) {
    for (int b = first_byte; b < kBytes; ++b) ++counts[static_cast<std::size_t>(b)][(v >> (8 * b)) & 0xFFU];
  }
  scratch.resize(values.size());
  const std::uint64_t some = values.front();
  for (int b = first_byte; b < kBytes; ++b) {
    std::array<std::size_t, 256>& count = counts[static_cast<std::size_t>(b)];
    if (count[(some >> (8 * b)) & 0xFFU] == values.size()) continue;  // one digit throughout: in order
    std::size_t offset = 0;
    for (std::size_t& c : count) offset += std::exchange(c, offset);  // counts → first positions
    for (const std::uint64_t v : values) scratch[count[(v >> (8 * b)) & 0xFFU]++] = v;
    values.swap(scratch);
  }
}

}  // namespace sonarmap
