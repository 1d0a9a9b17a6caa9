// radixSortHighBits (private to the algorithms layer): the order of std::stable_sort by the high
// bits, with and without bytes shared by every value.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "algorithms/radix_sort.hpp"
#include "sonarmap/core/key.hpp"

namespace sonarmap {
namespace {

void expectStableSortByHighBits(std::vector<std::uint64_t> values, int low_bit) {
  std::vector<std::uint64_t> expected = values;
  const auto high = [low_bit](std::uint64_t v) { return low_bit >= 64 ? 0 : v >> low_bit; };
  std::stable_sort(expected.begin(), expected.end(), [&](std::uint64_t a, std::uint64_t b) { return high(a) < high(b); });
  std::vector<std::uint64_t> scratch;
  radixSortHighBits(values, low_bit, scratch);
  EXPECT_EQ(values, expected) << "low bit " << low_bit;
}

TEST(RadixSort, MatchesStableSortByTheHighBits) {
  std::mt19937_64 random(7);
  std::vector<std::uint64_t> wide(5000), narrow(5000);
  for (std::uint64_t& v : wide) v = random();
  // Cell codes of a small box: most high bytes are the same in every value; many equal cells.
  for (std::uint64_t& v : narrow) v = (0xABCD00000000ULL | (random() % 300)) << 16 | (random() & 0xFFFF);
  for (const int low_bit : {0, 16, 40, 64}) {
    expectStableSortByHighBits(wide, low_bit);
    expectStableSortByHighBits(narrow, low_bit);
  }
  // Hit cells of a box around the map's origin: Morton codes of keys on both sides of 2^15 on every
  // axis differ in every byte, but their top byte takes at most 8 values (the split path).
  std::vector<std::uint64_t> straddling(20000);
  for (std::uint64_t& v : straddling) {
    const auto near_origin = [&] { return static_cast<std::uint16_t>(0x8000 - 175 + random() % 350); };
    v = mortonCode(Key16{{near_origin(), near_origin(), near_origin()}}) << 16 | (random() & 0xFFFF);
  }
  // Parts of one value, of two, and a top byte of more than 16 values (one pass per byte).
  std::vector<std::uint64_t> uneven(3000);
  for (std::size_t i = 0; i < uneven.size(); ++i) {
    const std::uint64_t top = i == 0 ? 0x01 : (i < 3 ? 0x02 : 0x80 + random() % 3);
    uneven[i] = top << 56 | (random() & 0xFFFFFFFFFFULL);
  }
  std::vector<std::uint64_t> many_tops(3000);
  for (std::uint64_t& v : many_tops) v = (random() % 40) << 56 | (random() & 0xFFFFFF);
  for (const int low_bit : {0, 16, 48, 56}) {
    expectStableSortByHighBits(straddling, low_bit);
    expectStableSortByHighBits(uneven, low_bit);
    expectStableSortByHighBits(many_tops, low_bit);
  }
  expectStableSortByHighBits({}, 16);
  expectStableSortByHighBits({42}, 16);
  expectStableSortByHighBits(std::vector<std::uint64_t>(100, 0x123456789ULL), 0);
}

}  // namespace
}  // namespace sonarmap
