// 3D DDA over keys (paper §6.1, Amanatides & Woo 1987): unit cases at depths 8, 16, 32, 64, 100.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "raycast/segment_reference.hpp"
#include "sonarmap/raycast/dda.hpp"

namespace sonarmap {
namespace {

template <class DepthConstant>
class raycastDda : public ::testing::Test {
 protected:
  static constexpr int kDepth = DepthConstant::value;
  using KeyT = Key<kDepth>;
  const KeyCoder<kDepth> coder{0.1};  // depth 8 spans ±12.8 m: all cases stay within ±1 m

  std::vector<KeyT> keys(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m) const {
    std::vector<KeyT> out;
    EXPECT_TRUE(rayKeysDDA(coder, origin_m, end_m, out));
    return out;
  }
  test::Cell cell(const KeyT& key) const { return test::cellOf(key); }

  // First key = origin's key, last = end's key, face steps only, |Δ|₁ + 1 keys, monotone per axis.
  void expectWellFormed(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m) const {
    const auto ray = keys(origin_m, end_m);
    ASSERT_FALSE(ray.empty());
    const test::Cell from = cell(coder.keyOfChecked(origin_m));
    const test::Cell to = cell(coder.keyOfChecked(end_m));
    EXPECT_EQ(cell(ray.front()), from);
    EXPECT_EQ(cell(ray.back()), to);
    std::int64_t l1 = 0;
    for (int axis = 0; axis < 3; ++axis) l1 += std::abs(to[axis] - from[axis]);
    EXPECT_EQ(static_cast<std::int64_t>(ray.size()), l1 + 1);
    for (std::size_t i = 1; i < ray.size(); ++i) {
      const test::Cell a = cell(ray[i - 1]);
      const test::Cell b = cell(ray[i]);
      int changed = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const std::int64_t step = b[axis] - a[axis];
        if (step == 0) continue;
        ++changed;
        EXPECT_EQ(std::abs(step), 1);
        EXPECT_EQ(step > 0, to[axis] > from[axis]) << "axis " << axis << " moves away from the end";
      }
      EXPECT_EQ(changed, 1) << "keys " << i - 1 << " and " << i << " are not face neighbours";
    }
  }
};

using Depths = ::testing::Types<std::integral_constant<int, 8>, std::integral_constant<int, 16>,
                                std::integral_constant<int, 32>, std::integral_constant<int, 64>,
                                std::integral_constant<int, 100>>;
TYPED_TEST_SUITE(raycastDda, Depths);

TYPED_TEST(raycastDda, AxisAlignedRaysVisitEveryVoxelInOrder) {
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      Eigen::Vector3d origin(0.05, -0.15, 0.25);
      Eigen::Vector3d end = origin;
      end[axis] += sign * 0.9;  // 9 boundaries crossed
      const auto ray = this->keys(origin, end);
      ASSERT_EQ(ray.size(), 10U);
      const test::Cell first = this->cell(ray.front());
      for (std::size_t i = 0; i < ray.size(); ++i) {
        test::Cell expected = first;
        expected[axis] += static_cast<std::int64_t>(sign) * static_cast<std::int64_t>(i);
        EXPECT_EQ(this->cell(ray[i]), expected);
      }
      this->expectWellFormed(origin, end);
    }
  }
}

TYPED_TEST(raycastDda, DiagonalAndObliqueRays) {
  this->expectWellFormed({0.05, 0.05, 0.05}, {0.35, 0.35, 0.35});  // through voxel corners
  this->expectWellFormed({0.01, 0.02, 0.03}, {0.93, 0.51, 0.27});
  this->expectWellFormed({-0.77, 0.41, -0.13}, {0.66, -0.58, 0.92});
  // Exact order for an oblique ray in the xy plane: (0.05, 0.02) → (0.25, 0.13) m crosses x = 0.1
  // at 25 % of its length, y = 0.1 at 72.7 % and x = 0.2 at 75 %.
  const auto ray = this->keys({0.05, 0.02, 0.05}, {0.25, 0.13, 0.05});
  ASSERT_EQ(ray.size(), 4U);
  const test::Cell c0 = this->cell(ray[0]);
  EXPECT_EQ(this->cell(ray[1]), (test::Cell{c0[0] + 1, c0[1], c0[2]}));
  EXPECT_EQ(this->cell(ray[2]), (test::Cell{c0[0] + 1, c0[1] + 1, c0[2]}));
  EXPECT_EQ(this->cell(ray[3]), (test::Cell{c0[0] + 2, c0[1] + 1, c0[2]}));
}

TYPED_TEST(raycastDda, NegativeDirections) {
  this->expectWellFormed({0.35, 0.25, -0.15}, {-0.42, -0.31, 0.18});
  this->expectWellFormed({0.99, 0.99, 0.99}, {-0.99, -0.99, -0.99});
  const auto ray = this->keys({0.35, 0.0, 0.0}, {-0.05, 0.0, 0.0});
  ASSERT_EQ(ray.size(), 5U);  // cells 3, 2, 1, 0, -1
  EXPECT_EQ(this->cell(ray.front())[0], 3);
  EXPECT_EQ(this->cell(ray.back())[0], -1);
}

TYPED_TEST(raycastDda, ZeroLengthAndSameVoxelVisitOneKey) {
  const Eigen::Vector3d p(0.123, -0.456, 0.789);
  const auto ray = this->keys(p, p);
  ASSERT_EQ(ray.size(), 1U);
  EXPECT_EQ(ray[0], this->coder.keyOfChecked(p));
  EXPECT_EQ(this->keys({0.11, 0.12, 0.13}, {0.19, 0.11, 0.18}).size(), 1U);
}

TYPED_TEST(raycastDda, RaysStartingAndEndingOnBoundaries) {
  // Origin exactly on the boundary x = 0 (cell 0 by floor): forward and backward.
  auto ray = this->keys({0.0, 0.05, 0.05}, {0.25, 0.05, 0.05});
  ASSERT_EQ(ray.size(), 3U);
  EXPECT_EQ(this->cell(ray.front())[0], 0);
  EXPECT_EQ(this->cell(ray.back())[0], 2);
  ray = this->keys({0.0, 0.05, 0.05}, {-0.25, 0.05, 0.05});
  ASSERT_EQ(ray.size(), 4U);  // 0 (the origin's own voxel), -1, -2, -3
  EXPECT_EQ(this->cell(ray.back())[0], -3);
  // Ends on boundaries, runs along a boundary plane, passes through edges and corners.
  this->expectWellFormed({0.05, 0.05, 0.05}, {0.3, 0.05, 0.05});
  this->expectWellFormed({0.35, 0.05, 0.05}, {0.1, 0.2, 0.05});
  this->expectWellFormed({0.0, 0.0, 0.0}, {0.4, 0.4, 0.0});
  this->expectWellFormed({0.0, 0.0, 0.0}, {-0.3, -0.3, -0.3});
  this->expectWellFormed({0.1, 0.2, 0.3}, {0.7, -0.4, 0.3});
  for (int i = -12; i <= 12; ++i) {  // end points k·res, computed as users compute them
    this->expectWellFormed({0.05, 0.05, 0.05}, {i * 0.1, 0.05 - i * 0.1, 0.3});
    this->expectWellFormed({i * 0.1, i * 0.2, -i * 0.1}, {-0.05, 0.0, 0.0});
  }
}

TYPED_TEST(raycastDda, EndPointsOutsideTheMapOrNotFiniteVisitNothing) {
  const double edge_m = KeyCoder<TestFixture::kDepth>::offset() * 0.1;  // map spans [-edge, edge)
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d inside(0.05, 0.05, 0.05);
  for (const Eigen::Vector3d& outside :
       {Eigen::Vector3d(edge_m, 0.0, 0.0), Eigen::Vector3d(0.0, -2.0 * edge_m, 0.0),
        Eigen::Vector3d(0.0, 0.0, nan), Eigen::Vector3d(inf, 0.0, 0.0)}) {
    int visits = 0;
    EXPECT_FALSE(traverseDDA(this->coder, inside, outside, [&](const auto&) { ++visits; }));
    EXPECT_FALSE(traverseDDA(this->coder, outside, inside, [&](const auto&) { ++visits; }));
    EXPECT_EQ(visits, 0);
    std::vector<typename TestFixture::KeyT> out(3);
    EXPECT_FALSE(rayKeysDDA(this->coder, outside, inside, out));
    EXPECT_TRUE(out.empty());
  }
}

// Equal tMax (through edges and corners) step x before y before z, pinned key by key. The ties are
// exact: the tied axes see the same numbers (all three 0.05), or only exact ones (±0.25 → ±2.5
// voxels, fraction 0.5) and mirrored direction components.
TYPED_TEST(raycastDda, TiesStepXThenYThenZ) {
  const auto cells = [this](const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m) {
    std::vector<test::Cell> out;
    for (const auto& key : this->keys(origin_m, end_m)) out.push_back(this->cell(key));
    return out;
  };
  using C = std::vector<test::Cell>;
  EXPECT_EQ(cells({0.05, 0.05, 0.05}, {0.35, 0.35, 0.35}),
            (C{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {2, 1, 1},  //
               {2, 2, 1}, {2, 2, 2}, {3, 2, 2}, {3, 3, 2}, {3, 3, 3}}));
  EXPECT_EQ(cells({0.35, 0.35, 0.35}, {0.05, 0.05, 0.05}),
            (C{{3, 3, 3}, {2, 3, 3}, {2, 2, 3}, {2, 2, 2}, {1, 2, 2},  //
               {1, 1, 2}, {1, 1, 1}, {0, 1, 1}, {0, 0, 1}, {0, 0, 0}}));
  EXPECT_EQ(cells({0.25, -0.25, 0.05}, {0.55, -0.55, 0.05}),
            (C{{2, -3, 0}, {3, -3, 0}, {3, -4, 0}, {4, -4, 0}, {4, -5, 0}, {5, -5, 0}, {5, -6, 0}}));
  EXPECT_EQ(cells({0.05, 0.25, -0.25}, {0.05, 0.55, -0.55}),
            (C{{0, 2, -3}, {0, 3, -3}, {0, 3, -4}, {0, 4, -4}, {0, 4, -5}, {0, 5, -5}, {0, 5, -6}}));
}

// |end - origin| overflowing double (resolution 1e300 m) leaves no usable distance: the walk is the
// snap alone, x steps, then y, then z, and still ends on the end key (it must not run forever).
TYPED_TEST(raycastDda, OverflowingLengthWalksTheSnapAlone) {
  const KeyCoder<TestFixture::kDepth> coder(1e300);
  std::vector<typename TestFixture::KeyT> ray;
  ASSERT_TRUE(rayKeysDDA(coder, {1.5e300, 2.5e300, -0.5e300}, {4.5e300, 0.5e300, 1.5e300}, ray));
  std::vector<test::Cell> cells;
  for (const auto& key : ray) cells.push_back(this->cell(key));
  EXPECT_EQ(cells, (std::vector<test::Cell>{
                       {1, 2, -1}, {2, 2, -1}, {3, 2, -1}, {4, 2, -1}, {4, 1, -1}, {4, 0, -1}, {4, 0, 0}, {4, 0, 1}}));
}

TYPED_TEST(raycastDda, VisitorSeesTheSameKeysAsRayKeys) {
  const Eigen::Vector3d origin(-0.31, 0.72, 0.05);
  const Eigen::Vector3d end(0.44, -0.18, -0.6);
  std::vector<typename TestFixture::KeyT> visited;
  EXPECT_TRUE(traverseDDA(this->coder, origin, end, [&](const auto& key) { visited.push_back(key); }));
  std::vector<typename TestFixture::KeyT> filled(5);  // cleared first
  EXPECT_TRUE(rayKeysDDA(this->coder, origin, end, filled));
  EXPECT_EQ(visited, filled);
}

// traverseDDASteps visits the same keys and names, at compile time, the one axis each step moved
// along (-1 for the origin's voxel only): rays in all octants, through snaps and ties.
TYPED_TEST(raycastDda, StepsNameTheAxisThatMoved) {
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> rays = {
      {{-0.31, 0.72, 0.05}, {0.44, -0.18, -0.6}}, {{0.05, 0.05, 0.05}, {0.95, 0.95, 0.95}},
      {{0.0, 0.0, 0.0}, {-0.7, 0.3, 0.9}},        {{0.12, -0.4, 0.33}, {0.12, -0.4, -0.91}},
      {{0.3, 0.3, 0.3}, {0.3, 0.3, 0.3}}};
  for (const auto& [origin, end] : rays) {
    std::vector<typename TestFixture::KeyT> visited;
    std::vector<int> axes;
    EXPECT_TRUE(traverseDDASteps(this->coder, origin, end, [&](const auto& key, auto stepped) {
      visited.push_back(key);
      axes.push_back(decltype(stepped)::value);
    }));
    EXPECT_EQ(visited, this->keys(origin, end));
    ASSERT_FALSE(axes.empty());
    EXPECT_EQ(axes.front(), -1);
    for (std::size_t i = 1; i < visited.size(); ++i) {
      ASSERT_GE(axes[i], 0);
      const auto a = this->cell(visited[i - 1]);
      const auto b = this->cell(visited[i]);
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(std::abs(b[axis] - a[axis]), axis == axes[i] ? 1 : 0) << "step " << i << " axis " << axis;
      }
    }
  }
}

// The whole map along one axis, corner to corner: no wrap-around at either border.
TEST(raycastDdaWholeMap, CrossesTheWholeMapWithoutWrapping) {
  const KeyCoder<8> coder(0.5);  // [-64, 64) m, 256 voxels per axis
  std::vector<Key<8>> ray;
  ASSERT_TRUE(rayKeysDDA(coder, {-64.0, -63.9, 63.99}, {63.99, 63.9, -64.0}, ray));
  ASSERT_EQ(ray.size(), 3U * 255U + 1U);
  EXPECT_EQ(ray.front(), (Key<8>{{0, 0, 255}}));
  EXPECT_EQ(ray.back(), (Key<8>{{255, 255, 0}}));
  ASSERT_TRUE(rayKeysDDA(coder, {63.75, 0.0, 0.0}, {-64.0, 0.0, 0.0}, ray));
  ASSERT_EQ(ray.size(), 256U);
  for (std::size_t i = 0; i < ray.size(); ++i) EXPECT_EQ(static_cast<std::size_t>(ray[i][0]), 255 - i);
}

// Keys of 128 bits across the whole map: the first steps of a ray spanning ~2^128 voxels.
TEST(raycastDdaWholeMap, WideKeysAcrossTheWholeMap) {
  const KeyCoder<128> coder(1.0);
  const double edge = std::ldexp(1.0, 127);
  struct Stop {};
  std::vector<Key<128>> ray;
  try {
    traverseDDA(coder, {-edge, -edge, -edge}, {0.75 * edge, 0.5 * edge, -0.25 * edge}, [&](const Key<128>& key) {
      ray.push_back(key);
      if (ray.size() == 1000) throw Stop{};
    });
  } catch (const Stop&) {
  }
  ASSERT_EQ(ray.size(), 1000U);
  EXPECT_EQ(ray.front(), (Key<128>{{0, 0, 0}}));
  for (std::size_t i = 1; i < ray.size(); ++i) {
    Key<128>::Index l1 = 0;
    for (int axis = 0; axis < 3; ++axis) l1 += ray[i][axis] - ray[i - 1][axis];  // monotone increasing
    EXPECT_EQ(static_cast<std::uint64_t>(l1), 1U);
  }
}

}  // namespace
}  // namespace sonarmap
