// Random cross-check of DDA and Bresenham ray traversal against a brute-force segment–voxel
// reference (paper §6.1, §6.2; Amanatides & Woo 1987).
//
// Misses: voxels the segment certainly crosses that a traversal does not visit.
// Extras: visited voxels the segment certainly does not touch.
// Voxels touched only within the reference's tolerance band (faces, edges, corners grazed within
// 1e-9 voxel) are ambiguous and count as neither.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "raycast/segment_reference.hpp"
#include "sonarmap/raycast/bresenham.hpp"
#include "sonarmap/raycast/dda.hpp"

namespace sonarmap {
namespace {

using test::Cell;
using test::Touch;

struct Segment {
  Eigen::Vector3d origin_m;
  Eigen::Vector3d end_m;
  double resolution_m;
};

std::string describe(const Segment& s) {
  std::ostringstream out;
  out.precision(17);
  out << "origin " << s.origin_m.transpose() << " m, end " << s.end_m.transpose() << " m, res " << s.resolution_m;
  return out.str();
}

// Lengths 0–5 m, resolution 0.02–0.1 m, origins in ±20 m. One segment in four is "grid-aligned":
// coordinates snapped to voxel boundaries and direction components zeroed, to exercise rays that
// start, run or end exactly on boundaries.
Segment randomSegment(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Segment s;
  s.resolution_m = 0.02 + 0.08 * unit(rng);
  const bool grid_aligned = unit(rng) < 0.25;
  const auto snap = [&](double v) { return unit(rng) < 0.5 ? std::round(v / s.resolution_m) * s.resolution_m : v; };
  Eigen::Vector3d direction(gauss(rng), gauss(rng), gauss(rng));
  for (int axis = 0; axis < 3; ++axis) {
    s.origin_m[axis] = -20.0 + 40.0 * unit(rng);
    if (grid_aligned) {
      s.origin_m[axis] = snap(s.origin_m[axis]);
      if (unit(rng) < 0.3) direction[axis] = 0.0;
    }
  }
  if (direction.norm() == 0.0) direction.x() = 1.0;
  s.end_m = s.origin_m + 5.0 * unit(rng) * direction.normalized();
  if (grid_aligned) {
    for (int axis = 0; axis < 3; ++axis) {
      if (direction[axis] != 0.0) s.end_m[axis] = snap(s.end_m[axis]);
    }
  }
  return s;
}

struct Tally {
  std::int64_t rays = 0;
  std::int64_t crossed = 0;    // certainly crossed voxels, summed over rays
  std::int64_t visited = 0;    // visited voxels, summed over rays
  std::int64_t ambiguous = 0;  // visited voxels the reference calls ambiguous
  std::int64_t misses = 0;
  std::int64_t extras = 0;
  std::int64_t slices = 0;     // Σ (max|Δkey| + 1): main-axis slices, for Bresenham
  std::int64_t broken_rays = 0;  // rays failing a structural check
  std::string first_broken;

  void compare(const std::map<Cell, Touch>& reference, const std::vector<Cell>& cells) {
    ++rays;
    visited += static_cast<std::int64_t>(cells.size());
    for (const Cell& cell : cells) {
      const auto it = reference.find(cell);
      if (it == reference.end()) {
        ++extras;
      } else if (it->second == Touch::kAmbiguous) {
        ++ambiguous;
      }
    }
    for (const auto& [cell, touch] : reference) {
      if (touch != Touch::kCrossed) continue;
      ++crossed;
      if (std::find(cells.begin(), cells.end(), cell) == cells.end()) ++misses;
    }
  }
  void broken(const std::string& what, const Segment& s) {
    if (broken_rays++ == 0) first_broken = what + " for " + describe(s);
  }
  double missRate() const { return crossed > 0 ? static_cast<double>(misses) / static_cast<double>(crossed) : 0.0; }
  double extraRate() const { return visited > 0 ? static_cast<double>(extras) / static_cast<double>(visited) : 0.0; }
  std::string summary(const std::string& name) const {
    std::ostringstream out;
    out << name << ": rays " << rays << ", crossed voxels " << crossed << ", visited " << visited << ", misses "
        << misses << " (" << 100.0 * missRate() << " %), extras " << extras << " (" << 100.0 * extraRate()
        << " %), visited ambiguous " << ambiguous;
    return out.str();
  }
};

std::int64_t chebyshev(const Cell& a, const Cell& b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

// DDA: first/last keys, face steps, |Δx|+|Δy|+|Δz|+1 keys.
void checkDda(const std::vector<Cell>& cells, const Cell& from, const Cell& to, const Segment& s, Tally& tally) {
  const std::int64_t expected = std::abs(to[0] - from[0]) + std::abs(to[1] - from[1]) + std::abs(to[2] - from[2]) + 1;
  if (cells.front() != from || cells.back() != to) return tally.broken("DDA end keys", s);
  if (static_cast<std::int64_t>(cells.size()) != expected) return tally.broken("DDA key count", s);
  for (std::size_t i = 1; i < cells.size(); ++i) {
    const Cell& a = cells[i - 1];
    const Cell& b = cells[i];
    if (std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) != 1) return tally.broken("DDA step", s);
  }
}

// Bresenham: first/last keys, max|Δ|+1 keys, minor coordinates = centre line rounded half up
// (computed here as floor((2·i·|Δb| + n) / (2n)), independently of the accumulator), visited voxels
// within √2/2 voxel of the true segment, crossed voxels within 2 voxels (Chebyshev) of the line.
// Why these bounds: with n = max|Δ| and the voxel-centre line C(s), each visited centre is within
// 1/2 of C on each minor axis and exact on the main axis; the true segment P(s) is within 1/2 of
// C(s) on every axis (both end points are within half a voxel of their centres). So each visited
// cube is within 1/2 of P on two axes and 0 on the main one: distance <= √2/2. Conversely a crossed
// voxel X with P(s) inside has |i/n - s| <= 1/n for the line voxel at X's main coordinate (index i),
// hence per minor axis |v - X| <= 1/2 (rounding) + |Δb|/n (<= 1) + 1 (X's centre to C(s)) = 5/2,
// i.e. Chebyshev distance <= 2 in integers.
void checkBresenham(const std::vector<Cell>& cells, const Cell& from, const Cell& to, const Segment& s,
                    const std::map<Cell, Touch>& reference, Tally& tally, double& max_distance) {
  std::array<std::int64_t, 3> delta{};
  for (int axis = 0; axis < 3; ++axis) delta[axis] = to[axis] - from[axis];
  const int main = static_cast<int>(std::max_element(delta.begin(), delta.end(), [](auto a, auto b) {
                                      return std::abs(a) < std::abs(b);
                                    }) - delta.begin());
  const std::int64_t n = std::abs(delta[main]);
  tally.slices += n + 1;
  if (cells.front() != from || cells.back() != to) return tally.broken("Bresenham end keys", s);
  if (static_cast<std::int64_t>(cells.size()) != n + 1) return tally.broken("Bresenham key count", s);
  const Eigen::Vector3d p0 = s.origin_m * (1.0 / s.resolution_m);
  const Eigen::Vector3d p1 = s.end_m * (1.0 / s.resolution_m);
  for (std::int64_t i = 0; i <= n; ++i) {
    const Cell& cell = cells[static_cast<std::size_t>(i)];
    for (int axis = 0; axis < 3; ++axis) {
      const std::int64_t sign = delta[axis] < 0 ? -1 : 1;
      const std::int64_t offset = n == 0 ? 0 : (2 * i * std::abs(delta[axis]) + n) / (2 * n);
      if (cell[axis] != from[axis] + sign * offset) return tally.broken("Bresenham rounding", s);
    }
    if (i > 0 && chebyshev(cell, cells[static_cast<std::size_t>(i - 1)]) != 1) return tally.broken("Bresenham step", s);
    const double distance = test::voxelSegmentDistance(p0, p1, cell);
    max_distance = std::max(max_distance, distance);
    if (distance > std::sqrt(0.5) + 1e-9) return tally.broken("Bresenham voxel far from segment", s);
  }
  for (const auto& [cell, touch] : reference) {
    if (touch != Touch::kCrossed) continue;
    const std::int64_t i = std::abs(cell[main] - from[main]);
    if (i > n || chebyshev(cell, cells[static_cast<std::size_t>(i)]) > 2) {
      return tally.broken("crossed voxel far from Bresenham line", s);
    }
  }
}

template <int Depth>
void crossCheck(std::uint32_t seed, int rays) {
  std::mt19937 rng(seed);
  Tally dda;
  Tally bresenham;
  double max_distance = 0.0;
  std::vector<Key<Depth>> keys;
  const auto cells_of = [&keys] {
    std::vector<Cell> cells;
    for (const auto& key : keys) cells.push_back(test::cellOf(key));
    return cells;
  };
  for (int ray = 0; ray < rays; ++ray) {
    const Segment s = randomSegment(rng);
    const KeyCoder<Depth> coder(s.resolution_m);
    const Cell from = test::cellOf(coder.keyOfChecked(s.origin_m));
    const Cell to = test::cellOf(coder.keyOfChecked(s.end_m));
    const auto reference = test::referenceVoxels(s.origin_m, s.end_m, s.resolution_m);

    ASSERT_TRUE(rayKeysDDA(coder, s.origin_m, s.end_m, keys)) << describe(s);
    const std::vector<Cell> dda_cells = cells_of();
    dda.compare(reference, dda_cells);
    checkDda(dda_cells, from, to, s, dda);

    ASSERT_TRUE(rayKeysBresenham(coder, s.origin_m, s.end_m, keys)) << describe(s);
    const std::vector<Cell> bresenham_cells = cells_of();
    bresenham.compare(reference, bresenham_cells);
    checkBresenham(bresenham_cells, from, to, s, reference, bresenham, max_distance);
  }
  const std::string depth = " (depth " + std::to_string(Depth) + ")";
  std::cout << dda.summary("DDA" + depth) << "\n"
            << bresenham.summary("Bresenham" + depth) << ", max voxel-segment distance " << max_distance
            << " voxel\n";
  ::testing::Test::RecordProperty("dda_misses", std::to_string(dda.misses));
  ::testing::Test::RecordProperty("dda_extras", std::to_string(dda.extras));
  ::testing::Test::RecordProperty("bresenham_miss_rate", std::to_string(bresenham.missRate()));
  ::testing::Test::RecordProperty("bresenham_extra_rate", std::to_string(bresenham.extraRate()));

  EXPECT_EQ(dda.broken_rays, 0) << dda.first_broken;
  EXPECT_EQ(bresenham.broken_rays, 0) << bresenham.first_broken;
  // DDA: never misses a crossed voxel. Extras could only come from the end snap (or a swapped
  // order of two near-simultaneous crossings); both happen within floating-point error of a
  // boundary, i.e. in the ambiguous band, so unambiguous extras must stay below 1e-5 of the visits.
  EXPECT_EQ(dda.misses, 0);
  EXPECT_LE(dda.extraRate(), 1e-5);
  // Bresenham: the hard bounds are the per-ray checks above (exact rounding, 26-neighbour steps,
  // max|Δ|+1 keys, visited voxels within √2/2 voxel of the segment, crossed voxels within 2 voxels
  // of the line); a broken line fails them. In aggregate, one voxel per main-axis slice can hit at
  // most Σ(max|Δ|+1) crossed voxels, so the miss rate is at least `miss_floor` (about half for
  // random directions: the segment crosses |Δx|+|Δy|+|Δz|+1 voxels). The upper limits are
  // regression guards, measured ≈ 53 % misses and ≈ 18 % extras plus a margin.
  const double miss_floor = 1.0 - static_cast<double>(bresenham.slices) / static_cast<double>(bresenham.crossed);
  std::cout << "Bresenham (depth " << Depth << "): one voxel per slice implies a miss rate >= " << 100.0 * miss_floor
            << " %\n";
  EXPECT_GE(bresenham.missRate(), miss_floor);
  EXPECT_LT(bresenham.missRate(), 0.6);
  EXPECT_LT(bresenham.extraRate(), 0.25);
}

TEST(raycastCrossCheck, RandomSegmentsDepth16) { crossCheck<16>(20240611U, 5000); }
TEST(raycastCrossCheck, RandomSegmentsDepth32) { crossCheck<32>(7U, 2000); }
TEST(raycastCrossCheck, RandomSegmentsDepth64) { crossCheck<64>(64U, 1000); }

}  // namespace
}  // namespace sonarmap
