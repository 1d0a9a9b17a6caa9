// Keys sized by depth, coordinate/key conversion and the log-odds model (paper §5.1, §5.2).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "sonarmap/core/key_coder.hpp"
#include "sonarmap/core/log_odds.hpp"

namespace sonarmap {
namespace {

TEST(Key, IndexWidthFollowsDepth) {
  static_assert(sizeof(Key<8>::Index) == 1);
  static_assert(sizeof(Key<9>::Index) == 2);
  static_assert(sizeof(Key<16>::Index) == 2);
  static_assert(sizeof(Key<17>::Index) == 4);
  static_assert(sizeof(Key<33>::Index) == 8);
  static_assert(sizeof(Key<64>::Index) == 8);
  static_assert(sizeof(Key<65>::Index) == 16);
  static_assert(sizeof(Key<16>) == 6, "OctoMap's 48-bit key");
  SUCCEED();
}

TEST(KeyCoder, MatchesOctoMapConventionAtDepth16) {
  const KeyCoder<16> coder(0.02);
  EXPECT_EQ(*coder.indexOf(0.0), 32768);
  EXPECT_EQ(*coder.indexOf(0.0199), 32768);
  EXPECT_EQ(*coder.indexOf(-0.0001), 32767);
  EXPECT_EQ(*coder.indexOf(1.0), 32768 + 50);
  EXPECT_DOUBLE_EQ(coder.centerOf(Key16::Index{32768}), 0.01);
  EXPECT_DOUBLE_EQ(coder.centerOf(Key16::Index{32767}), -0.01);
}

TEST(KeyCoder, RejectsOutsideExtentInsteadOfWrapping) {
  const KeyCoder<16> coder(0.1);  // extent ±3276.8 m
  EXPECT_TRUE(coder.indexOf(3276.7).has_value());
  EXPECT_FALSE(coder.indexOf(3276.8).has_value());
  EXPECT_TRUE(coder.indexOf(-3276.8).has_value());
  EXPECT_FALSE(coder.indexOf(-3276.81).has_value());
  EXPECT_FALSE(coder.indexOf(std::numeric_limits<double>::quiet_NaN()).has_value());
  EXPECT_FALSE(coder.indexOf(std::numeric_limits<double>::infinity()).has_value());
  EXPECT_THROW(coder.keyOfChecked({0.0, 5000.0, 0.0}), OutOfMapError);
}

TEST(KeyCoder, InvalidResolutionThrows) {
  EXPECT_THROW(KeyCoder<16>(0.0), ValueError);
  EXPECT_THROW(KeyCoder<16>(-0.1), ValueError);
  EXPECT_THROW(KeyCoder<16>(std::nan("")), ValueError);
}

template <int Depth>
void expectRoundTrip(double resolution_m, double coord_m) {
  const KeyCoder<Depth> coder(resolution_m);
  const auto key = coder.keyOf({coord_m, -coord_m, 0.5 * coord_m});
  ASSERT_TRUE(key.has_value()) << "depth " << Depth;
  const Eigen::Vector3d center = coder.centerOf(*key);
  EXPECT_NEAR(center.x(), coord_m, resolution_m) << "depth " << Depth;
  EXPECT_NEAR(center.y(), -coord_m, resolution_m) << "depth " << Depth;
  EXPECT_EQ(coder.keyOf(center), key) << "depth " << Depth;
}

TEST(KeyCoder, DeepTreesAddressFarBeyondDepth16) {
  expectRoundTrip<8>(0.1, 12.3);          // extent ±12.8 m
  expectRoundTrip<16>(0.01, 300.0);
  expectRoundTrip<32>(0.01, 1.0e6);       // a 1000 km map at 1 cm
  expectRoundTrip<64>(0.001, 1.0e12);
  expectRoundTrip<100>(0.001, 1.0e12);    // wide (128-bit) keys; doubles limit exact coordinates to 2^53 voxels
  EXPECT_FALSE(KeyCoder<8>(0.1).indexOf(12.9).has_value());
}

/// keyInto gives keyOf's answer: the same key, or false where keyOf gives none.
template <int Depth>
void expectKeyIntoMatchesKeyOf(double resolution_m, double extent_m) {
  const KeyCoder<Depth> coder(resolution_m);
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> coordinate(-extent_m, extent_m);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 20000; ++i) points.emplace_back(coordinate(random), coordinate(random), coordinate(random));
  // Cell boundaries, either side of zero, the map's edges, and what is not a number.
  const double edge_m = KeyCoder<Depth>::offset() * resolution_m;
  for (const double v : {0.0, -0.0, resolution_m, -resolution_m, 0.5 * resolution_m, -0.5 * resolution_m, edge_m,
                         -edge_m, std::nextafter(edge_m, 0.0), std::nextafter(-edge_m, -2.0 * edge_m),
                         std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    points.emplace_back(v, 0.25, -0.25);
    points.emplace_back(0.1, v, 0.1);
    points.emplace_back(-0.1, -0.1, v);
  }
  for (const Eigen::Vector3d& point : points) {
    typename KeyCoder<Depth>::KeyType key;
    const auto expected = coder.keyOf(point);
    ASSERT_EQ(coder.keyInto(point, key), expected.has_value()) << point.transpose();
    if (expected) {
      EXPECT_EQ(key, *expected) << point.transpose();
    }
  }
}

TEST(KeyCoder, KeyIntoMatchesKeyOf) {
  expectKeyIntoMatchesKeyOf<16>(0.02, 700.0);  // beyond the map's ±655.36 m too
  expectKeyIntoMatchesKeyOf<16>(0.05, 10.0);
  expectKeyIntoMatchesKeyOf<8>(0.1, 15.0);
  expectKeyIntoMatchesKeyOf<21>(0.013, 1e5);
  expectKeyIntoMatchesKeyOf<60>(1e-3, 1e9);
}

TEST(ChildIndex, XIsBit0YBit1ZBit2) {
  Key16 key{{0x8000, 0x0000, 0x8000}};
  EXPECT_EQ(childIndex(key, 0), 5U);
  key = Key16{{0x0001, 0x0001, 0x0000}};
  EXPECT_EQ(childIndex(key, 15), 3U);
  EXPECT_EQ(childIndex(key, 14), 0U);
}

TEST(MortonCode, RoundTripsAndOrdersAsTheTreeIsWalked) {
  const Key16 key{{0xFFFF, 0x1234, 0x8001}};
  EXPECT_EQ(keyOfMortonCode<16>(mortonCode(key)), key);
  EXPECT_EQ(mortonCode(Key<21>{{0x1FFFFF, 0x1FFFFF, 0x1FFFFF}}), (std::uint64_t{1} << 63) - 1);
  // Level by level, the code's top three bits are the child index: a depth-first walk's order.
  const Key16 a{{0x7FFF, 0xFFFF, 0x7FFF}};  // child 2 at level 0
  const Key16 b{{0x8000, 0x0000, 0x0000}};  // child 1 at level 0
  EXPECT_EQ(childIndex(a, 0), 2U);
  EXPECT_EQ(childIndex(b, 0), 1U);
  EXPECT_LT(mortonCode(b), mortonCode(a));
  EXPECT_EQ(mortonCode(Key16{{1, 0, 0}}), 1U);
  EXPECT_EQ(mortonCode(Key16{{0, 1, 0}}), 2U);
  EXPECT_EQ(mortonCode(Key16{{0, 0, 1}}), 4U);
  EXPECT_EQ(mortonCode(Key16{{2, 0, 0}}), 8U);
}

/// The codes of the byte tables against the bit-interleaving formula, both ways, on random keys.
template <int Depth>
void expectMortonMatchesInterleaving() {
  std::mt19937_64 random(Depth);
  using Index = typename Key<Depth>::Index;
  for (int i = 0; i < 20000; ++i) {
    Key<Depth> key;
    for (int axis = 0; axis < 3; ++axis) key[axis] = static_cast<Index>(random() & ((std::uint64_t{1} << Depth) - 1));
    const std::uint64_t interleaved = detail::spreadEveryThirdBit(key[0]) | (detail::spreadEveryThirdBit(key[1]) << 1) |
                                      (detail::spreadEveryThirdBit(key[2]) << 2);
    ASSERT_EQ(mortonCode(key), interleaved);
    ASSERT_EQ(keyOfMortonCode<Depth>(interleaved), key);
  }
}

TEST(MortonCode, ByteTablesMatchBitInterleaving) {
  expectMortonMatchesInterleaving<1>();
  expectMortonMatchesInterleaving<8>();
  expectMortonMatchesInterleaving<16>();
  expectMortonMatchesInterleaving<21>();
}

TEST(LogOdds, OctoMapDefaults) {
  const LogOddsModel model = LogOddsModel::from({});
  EXPECT_NEAR(model.hit, 0.8473, 1e-4);
  EXPECT_NEAR(model.miss, -0.4055, 1e-4);
  EXPECT_NEAR(model.clamp_min, -2.0, 1e-3);
  EXPECT_NEAR(model.clamp_max, 3.511, 1e-3);  // logit(0.971), OctoMap's value
  EXPECT_FLOAT_EQ(model.update(3.4F, 1.0F), model.clamp_max);
  EXPECT_FLOAT_EQ(model.update(-1.9F, -1.0F), model.clamp_min);
  EXPECT_TRUE(model.isStable(model.clamp_max, 0.5F));
  EXPECT_FALSE(model.isStable(model.clamp_max, -0.5F));
  EXPECT_TRUE(model.isStable(0.3F, 0.0F));
}

TEST(LogOdds, TwoThresholdsLeaveAnUnknownBand) {
  OccupancyParams params;
  params.free_below = 0.4;
  params.occupied_above = 0.6;
  const LogOddsModel model = LogOddsModel::from(params);
  EXPECT_EQ(model.classify(logOdds(0.7)), Occupancy::kOccupied);
  EXPECT_EQ(model.classify(logOdds(0.5)), Occupancy::kUnknown);
  EXPECT_EQ(model.classify(logOdds(0.3)), Occupancy::kFree);
}

TEST(LogOdds, InvalidParamsThrow) {
  OccupancyParams params;
  params.prob_hit = 0.4;
  EXPECT_THROW(LogOddsModel::from(params), ValueError);
  params = {};
  params.clamp_min = 1.2;
  EXPECT_THROW(LogOddsModel::from(params), ValueError);
  params = {};
  params.free_below = 0.7;  // above occupied_above
  EXPECT_THROW(LogOddsModel::from(params), ValueError);
}

}  // namespace
}  // namespace sonarmap
