// 3D Bresenham over keys (paper §6.2): unit cases at depths 8, 16, 32, 64, 100, and the integer
// arithmetic at full-map spans for 64- and 128-bit keys.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "raycast/segment_reference.hpp"
#include "sonarmap/raycast/bresenham.hpp"

namespace sonarmap {
namespace {

template <class DepthConstant>
class raycastBresenham : public ::testing::Test {
 protected:
  static constexpr int kDepth = DepthConstant::value;
  using KeyT = Key<kDepth>;
  const KeyCoder<kDepth> coder{0.1};

  // Cells relative to the origin's cell.
  std::vector<test::Cell> relativeCells(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m) const {
    std::vector<KeyT> keys;
    EXPECT_TRUE(rayKeysBresenham(coder, origin_m, end_m, keys));
    std::vector<test::Cell> cells;
    if (keys.empty()) return cells;
    const test::Cell base = test::cellOf(keys.front());
    for (const KeyT& key : keys) {
      const test::Cell c = test::cellOf(key);
      cells.push_back({c[0] - base[0], c[1] - base[1], c[2] - base[2]});
    }
    return cells;
  }

  // First/last = end points' keys, max|Δ| + 1 keys, 26-neighbour steps moving the main axis.
  void expectWellFormed(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m) const {
    std::vector<KeyT> keys;
    ASSERT_TRUE(rayKeysBresenham(coder, origin_m, end_m, keys));
    ASSERT_FALSE(keys.empty());
    EXPECT_EQ(keys.front(), coder.keyOfChecked(origin_m));
    EXPECT_EQ(keys.back(), coder.keyOfChecked(end_m));
    const test::Cell from = test::cellOf(keys.front());
    const test::Cell to = test::cellOf(keys.back());
    std::int64_t longest = 0;
    for (int axis = 0; axis < 3; ++axis) longest = std::max(longest, std::abs(to[axis] - from[axis]));
    EXPECT_EQ(static_cast<std::int64_t>(keys.size()), longest + 1);
    for (std::size_t i = 1; i < keys.size(); ++i) {
      const test::Cell a = test::cellOf(keys[i - 1]);
      const test::Cell b = test::cellOf(keys[i]);
      std::int64_t chebyshev = 0;
      for (int axis = 0; axis < 3; ++axis) {
        chebyshev = std::max(chebyshev, std::abs(b[axis] - a[axis]));
        if (b[axis] != a[axis]) {
          EXPECT_EQ(b[axis] > a[axis], to[axis] > from[axis]);
        }
      }
      EXPECT_EQ(chebyshev, 1);
    }
  }
};

using Depths = ::testing::Types<std::integral_constant<int, 8>, std::integral_constant<int, 16>,
                                std::integral_constant<int, 32>, std::integral_constant<int, 64>,
                                std::integral_constant<int, 100>>;
TYPED_TEST_SUITE(raycastBresenham, Depths);

TYPED_TEST(raycastBresenham, AxisAlignedRays) {
  for (int axis = 0; axis < 3; ++axis) {
    for (const std::int64_t sign : {1, -1}) {
      Eigen::Vector3d origin(0.05, -0.15, 0.25);
      Eigen::Vector3d end = origin;
      end[axis] += static_cast<double>(sign) * 0.9;
      const auto cells = this->relativeCells(origin, end);
      ASSERT_EQ(cells.size(), 10U);
      for (std::size_t i = 0; i < cells.size(); ++i) {
        test::Cell expected{0, 0, 0};
        expected[axis] = sign * static_cast<std::int64_t>(i);
        EXPECT_EQ(cells[i], expected);
      }
    }
  }
}

TYPED_TEST(raycastBresenham, DiagonalMovesAllAxesAtOnce) {
  const auto cells = this->relativeCells({0.05, 0.05, 0.05}, {0.35, -0.25, 0.35});  // y cells 0 … -3
  const std::vector<test::Cell> expected{{0, 0, 0}, {1, -1, 1}, {2, -2, 2}, {3, -3, 3}};
  EXPECT_EQ(cells, expected);
}

TYPED_TEST(raycastBresenham, MinorAxesFollowTheCentreLineRoundedHalfUp) {
  // Δ = (4, 2, 0): y = round_half_up(i / 2).
  EXPECT_EQ(this->relativeCells({0.05, 0.05, 0.05}, {0.45, 0.25, 0.05}),
            (std::vector<test::Cell>{{0, 0, 0}, {1, 1, 0}, {2, 1, 0}, {3, 2, 0}, {4, 2, 0}}));
  // Δ = (3, -5, -2), main axis y: x = round_half_up(3i/5), z = -round_half_up(2i/5).
  EXPECT_EQ(this->relativeCells({0.05, 0.05, 0.05}, {0.35, -0.45, -0.15}),
            (std::vector<test::Cell>{{0, 0, 0}, {1, -1, 0}, {1, -2, -1}, {2, -3, -1}, {2, -4, -2}, {3, -5, -2}}));
}

TYPED_TEST(raycastBresenham, WellFormedInEveryDirection) {
  this->expectWellFormed({0.35, 0.25, -0.15}, {-0.42, -0.31, 0.18});
  this->expectWellFormed({0.01, 0.02, 0.03}, {0.93, 0.51, 0.27});
  this->expectWellFormed({0.0, 0.0, 0.0}, {-0.3, -0.3, -0.3});
  this->expectWellFormed({0.99, -0.99, 0.5}, {-0.99, 0.99, -0.5});
  for (int i = -12; i <= 12; ++i) this->expectWellFormed({0.05, 0.05, 0.05}, {i * 0.1, 0.05 - i * 0.07, 0.3});
}

TYPED_TEST(raycastBresenham, ZeroLengthAndSameVoxelVisitOneKey) {
  const Eigen::Vector3d p(0.123, -0.456, 0.789);
  EXPECT_EQ(this->relativeCells(p, p), (std::vector<test::Cell>{{0, 0, 0}}));
  EXPECT_EQ(this->relativeCells({0.11, 0.12, 0.13}, {0.19, 0.11, 0.18}).size(), 1U);
}

TYPED_TEST(raycastBresenham, EndPointsOutsideTheMapOrNotFiniteVisitNothing) {
  const double edge_m = KeyCoder<TestFixture::kDepth>::offset() * 0.1;
  const Eigen::Vector3d inside(0.05, 0.05, 0.05);
  for (const Eigen::Vector3d& outside :
       {Eigen::Vector3d(edge_m, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, -2.0 * edge_m),
        Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0),
        Eigen::Vector3d(0.0, -std::numeric_limits<double>::infinity(), 0.0)}) {
    int visits = 0;
    EXPECT_FALSE(traverseBresenham(this->coder, inside, outside, [&](const auto&) { ++visits; }));
    EXPECT_FALSE(traverseBresenham(this->coder, outside, inside, [&](const auto&) { ++visits; }));
    EXPECT_EQ(visits, 0);
    std::vector<typename TestFixture::KeyT> out(3);
    EXPECT_FALSE(rayKeysBresenham(this->coder, inside, outside, out));
    EXPECT_TRUE(out.empty());
  }
}

TEST(raycastBresenhamWholeMap, CrossesTheWholeDepth8MapWithoutWrapping) {
  const KeyCoder<8> coder(0.5);  // [-64, 64) m
  std::vector<Key<8>> ray;
  ASSERT_TRUE(rayKeysBresenham(coder, {63.9, -64.0, 10.0}, {-64.0, 63.9, -10.0}, ray));
  ASSERT_EQ(ray.size(), 256U);
  EXPECT_EQ(ray.front(), (Key<8>{{255, 0, 148}}));
  EXPECT_EQ(ray.back(), (Key<8>{{0, 255, 108}}));
}

// Full-map spans for 64- and 128-bit keys: |Δ| close to 2^Depth, where a classic 2·error
// accumulator would overflow. Δ = (n, n/2, n/4), so y_i = floor((i+1)/2) and z_i = floor((i+2)/4).
template <int Depth>
void expectExactAtFullSpan() {
  const KeyCoder<Depth> coder(1.0);
  const double edge = std::ldexp(1.0, Depth - 1);
  const double gap = std::ldexp(1.0, Depth - 52);  // keeps every coordinate an exact double
  struct Stop {};
  std::vector<Key<Depth>> ray;
  try {
    traverseBresenham(coder, {-edge, -edge, -edge}, {edge - gap, -gap / 2, -edge / 2 - gap / 4},
                      [&](const Key<Depth>& key) {
                        ray.push_back(key);
                        if (ray.size() == 1000) throw Stop{};
                      });
  } catch (const Stop&) {
  }
  ASSERT_EQ(ray.size(), 1000U);
  for (std::size_t i = 0; i < ray.size(); ++i) {
    EXPECT_EQ(static_cast<std::uint64_t>(ray[i][0]), i);
    EXPECT_EQ(static_cast<std::uint64_t>(ray[i][1]), (i + 1) / 2);
    EXPECT_EQ(static_cast<std::uint64_t>(ray[i][2]), (i + 2) / 4);
  }
}

TEST(raycastBresenhamWholeMap, ExactAtFullSpanDepth64) { expectExactAtFullSpan<64>(); }
TEST(raycastBresenhamWholeMap, ExactAtFullSpanDepth128) { expectExactAtFullSpan<128>(); }

}  // namespace
}  // namespace sonarmap
