#pragma once
/// @file segment_reference.hpp
/// Brute-force reference for ray traversal tests: which voxels a segment really crosses.
///
/// Works in voxel units (coordinate_m / resolution_m, computed as KeyCoder::keyOf computes it), so a
/// voxel with signed cell index c (= key - 2^(Depth-1)) is the unit cube [c, c+1]^3. Each candidate
/// voxel gets a segment–box slab test against the cube shrunk and grown by a tolerance band:
///   crossed   — the segment meets the shrunk cube: it certainly passes through the voxel;
///   ambiguous — it meets the grown cube but not the shrunk one: it only touches a face, edge or
///               corner within the tolerance, where floating-point rounding decides;
///   untouched — otherwise.
/// Candidates are found slice by slice (x, then y within the x slice, then z) from conservative
/// intervals, which only avoids testing the whole bounding box; every verdict is the slab test.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>

#include <Eigen/Core>

#include "sonarmap/core/key.hpp"

namespace sonarmap::test {

using Cell = std::array<std::int64_t, 3>;  // signed voxel index per axis: key - 2^(Depth-1)

enum class Touch { kUntouched, kAmbiguous, kCrossed };

/// Signed cell of a key (test coordinates are small, so it fits int64 for every depth).
template <int Depth>
Cell cellOf(const Key<Depth>& key) {
  using Index = typename Key<Depth>::Index;
  const Index half = Index{1} << (Depth - 1);
  Cell cell{};
  for (int axis = 0; axis < 3; ++axis) {
    cell[axis] = key[axis] >= half ? static_cast<std::int64_t>(key[axis] - half)
                                   : -static_cast<std::int64_t>(half - key[axis]);
  }
  return cell;
}

/// Clips the parameter interval [s0, s1] of p(s) = p0 + s·d to lo <= p(s) <= hi on one axis.
/// @return false if the clipped interval is empty.
inline bool clipSlab(double p0, double d, double lo, double hi, double& s0, double& s1) {
  if (d == 0.0) return p0 >= lo && p0 <= hi;
  double a = (lo - p0) / d;
  double b = (hi - p0) / d;
  if (a > b) std::swap(a, b);
  s0 = std::max(s0, a);
  s1 = std::min(s1, b);
  return s0 <= s1;
}

/// Does the segment p0 + s·d, s in [0, 1], meet the closed box [lo, hi]^3 (voxel units)?
inline bool segmentMeetsBox(const Eigen::Vector3d& p0, const Eigen::Vector3d& d, const Eigen::Vector3d& lo,
                            const Eigen::Vector3d& hi) {
  double s0 = 0.0;
  double s1 = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (!clipSlab(p0[axis], d[axis], lo[axis], hi[axis], s0, s1)) return false;
  }
  return true;
}

/// Classifies voxel `cell` against the segment p0 → p1 (voxel units) with tolerance band `tol`.
inline Touch classify(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Cell& cell, double tol) {
  const Eigen::Vector3d d = p1 - p0;
  const Eigen::Vector3d lo(static_cast<double>(cell[0]), static_cast<double>(cell[1]), static_cast<double>(cell[2]));
  const Eigen::Vector3d one = Eigen::Vector3d::Ones();
  if (segmentMeetsBox(p0, d, lo + tol * one, lo + (1.0 - tol) * one)) return Touch::kCrossed;
  if (segmentMeetsBox(p0, d, lo - tol * one, lo + (1.0 + tol) * one)) return Touch::kAmbiguous;
  return Touch::kUntouched;
}

/// Every voxel the segment from `origin_m` to `end_m` crosses or touches within `tol` voxel units,
/// with its verdict (untouched voxels are left out). `resolution_m` > 0.
inline std::map<Cell, Touch> referenceVoxels(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m,
                                             double resolution_m, double tol = 1e-9) {
  const double inv_resolution = 1.0 / resolution_m;
  const Eigen::Vector3d p0 = origin_m * inv_resolution;
  const Eigen::Vector3d p1 = end_m * inv_resolution;
  const Eigen::Vector3d d = p1 - p0;
  const double margin = 1e-6;  // candidate search only: much wider than tol

  // Cells whose closed extent [c - margin, c + 1 + margin] the coordinate range [v0, v1] meets.
  const auto cell_range = [margin](double v0, double v1) {
    return std::array<std::int64_t, 2>{static_cast<std::int64_t>(std::floor(std::min(v0, v1) - 1.0 - margin)),
                                       static_cast<std::int64_t>(std::floor(std::max(v0, v1) + margin))};
  };
  std::map<Cell, Touch> result;
  const auto xs = cell_range(p0.x(), p1.x());
  for (std::int64_t cx = xs[0]; cx <= xs[1]; ++cx) {
    double sx0 = 0.0;
    double sx1 = 1.0;
    const double x = static_cast<double>(cx);
    if (!clipSlab(p0.x(), d.x(), x - margin, x + 1.0 + margin, sx0, sx1)) continue;
    const auto ys = cell_range(p0.y() + sx0 * d.y(), p0.y() + sx1 * d.y());
    for (std::int64_t cy = ys[0]; cy <= ys[1]; ++cy) {
      double sy0 = sx0;
      double sy1 = sx1;
      const double y = static_cast<double>(cy);
      if (!clipSlab(p0.y(), d.y(), y - margin, y + 1.0 + margin, sy0, sy1)) continue;
      const auto zs = cell_range(p0.z() + sy0 * d.z(), p0.z() + sy1 * d.z());
      for (std::int64_t cz = zs[0]; cz <= zs[1]; ++cz) {
        const Cell cell{cx, cy, cz};
        const Touch touch = classify(p0, p1, cell, tol);
        if (touch != Touch::kUntouched) result.emplace(cell, touch);
      }
    }
  }
  return result;
}

/// Euclidean distance, in voxel units, between voxel `cell` (unit cube) and the segment p0 → p1
/// (voxel units). Golden-section search: the distance to a convex set along a segment is convex.
inline double voxelSegmentDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Cell& cell) {
  const Eigen::Vector3d lo(static_cast<double>(cell[0]), static_cast<double>(cell[1]), static_cast<double>(cell[2]));
  const Eigen::Vector3d hi = lo + Eigen::Vector3d::Ones();
  const auto distance = [&](double s) {
    const Eigen::Vector3d p = p0 + s * (p1 - p0);
    return (p.cwiseMax(lo).cwiseMin(hi) - p).norm();
  };
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = 0.0;
  double b = 1.0;
  for (int iteration = 0; iteration < 80; ++iteration) {
    const double c = b - ratio * (b - a);
    const double e = a + ratio * (b - a);
    if (distance(c) <= distance(e)) {
      b = e;
    } else {
      a = c;
    }
  }
  return std::min({distance(0.5 * (a + b)), distance(0.0), distance(1.0)});
}

}  // namespace sonarmap::test
