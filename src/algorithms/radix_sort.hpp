#pragma once
// A radix sort of 64-bit integers by their high bits (Knuth, TAOCP vol. 3, §5.2.5), for the
// mapper's per-sweep lists of cell codes. Internal to the library.
//
// On the lists a sweep produces (10^5 codes whose high bits span a small box of keys) it is
// several times faster than std::sort: one pass counts every byte of every value, and a byte that
// is the same in all values needs no pass at all. Morton codes of a box that straddles a power of
// two (a map's keys straddle 2^15 on every axis around its origin) differ in every byte, yet their
// high bytes take only a few values: those are split first (one most-significant-digit pass), and
// each part is then sorted least significant byte first over the bytes that differ within it.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace sonarmap {

namespace detail {
inline unsigned radixDigit(std::uint64_t v, int byte) { return static_cast<unsigned>((v >> (8 * byte)) & 0xFFU); }

/// Stable least-significant-byte-first passes over bytes [first_byte, end_byte) of the `count`
/// values at `data`, skipping bytes that are the same in all of them; `spare` holds as many. The
/// sorted values end in `data`.
inline void radixSortBytes(std::uint64_t* data, std::uint64_t* spare, std::size_t count, int first_byte, int end_byte) {
  if (count < 2 || first_byte >= end_byte) return;
  std::array<std::array<std::size_t, 256>, 8> counts;
  for (int b = first_byte; b < end_byte; ++b) counts[static_cast<std::size_t>(b)].fill(0);
  for (std::size_t i = 0; i < count; ++i) {
    for (int b = first_byte; b < end_byte; ++b) ++counts[static_cast<std::size_t>(b)][radixDigit(data[i], b)];
  }
  std::uint64_t* from = data;
  std::uint64_t* to = spare;
  for (int b = first_byte; b < end_byte; ++b) {
    std::array<std::size_t, 256>& position = counts[static_cast<std::size_t>(b)];
    if (position[radixDigit(data[0], b)] == count) continue;  // one digit throughout: in order
    std::size_t offset = 0;
    for (std::size_t& c : position) offset += std::exchange(c, offset);  // counts → first positions
    for (std::size_t i = 0; i < count; ++i) to[position[radixDigit(from[i], b)]++] = from[i];
    std::swap(from, to);
  }
  if (from != data) std::copy(from, from + count, data);
}
}  // namespace detail

/// Sorts `values` ascending by bits [low_bit, 64) of each value; values equal there keep their
/// input order (stable), whatever their bits below `low_bit`. One pass per byte that differs
/// between values, or, when the highest such byte takes at most 16 values, one pass on it and then
/// one per byte that differs within each of its parts; `scratch` is working memory, reused between
/// calls. @param low_bit 0 … 64, a multiple of 8. @throws std::bad_alloc.
inline void radixSortHighBits(std::vector<std::uint64_t>& values, int low_bit, std::vector<std::uint64_t>& scratch) {
  constexpr int kBytes = 8;
  constexpr std::size_t kMaxParts = 16;
  const int first_byte = low_bit / 8;
  const std::size_t n = values.size();
  if (n < 2 || first_byte >= kBytes) return;
  // The highest byte that differs between values.
  std::uint64_t differ = 0;
  for (const std::uint64_t v : values) differ |= v ^ values.front();
  int top = kBytes - 1;
  while (top >= first_byte && detail::radixDigit(differ, top) == 0) --top;
  if (top < first_byte) return;  // all equal in the sorted bits
  scratch.resize(n);
  if (top == first_byte) return detail::radixSortBytes(values.data(), scratch.data(), n, first_byte, top + 1);
  std::array<std::size_t, 256> part_size{};
  for (const std::uint64_t v : values) ++part_size[detail::radixDigit(v, top)];
  if (std::count_if(part_size.begin(), part_size.end(), [](std::size_t c) { return c != 0; }) > static_cast<std::ptrdiff_t>(kMaxParts)) {
    return detail::radixSortBytes(values.data(), scratch.data(), n, first_byte, top + 1);
  }
  // Split on the top byte into `scratch` (stable), then sort each part in place.
  std::array<std::size_t, 256> part_start{};
  for (std::size_t d = 1; d < 256; ++d) part_start[d] = part_start[d - 1] + part_size[d - 1];
  std::array<std::size_t, 256> position = part_start;
  for (const std::uint64_t v : values) scratch[position[detail::radixDigit(v, top)]++] = v;
  values.swap(scratch);  // the split values in `values`, `scratch` spare
  for (std::size_t d = 0; d < 256; ++d) {
    detail::radixSortBytes(values.data() + part_start[d], scratch.data() + part_start[d], part_size[d], first_byte, top);
  }
}

}  // namespace sonarmap
