#pragma once
/// @file dda.hpp
/// 3D digital differential analyser (DDA) over octree keys: the voxels a segment crosses, in order
/// (paper §6.1, after Amanatides & Woo 1987, "A Fast Voxel Traversal Algorithm for Ray Tracing").
///
/// Initialisation: the origin voxel, the step direction per axis, `tMax` = distance in metres along
/// the ray to the first voxel boundary of each axis and `tDelta` = resolution / |direction| = metres
/// along the ray between two boundaries of that axis (the paper scales A&W's unit voxel by the
/// resolution). Incremental phase: step the key component whose `tMax` is smallest, then add its
/// `tDelta`. Keys are stepped as integers (paper §6.1, last paragraph); only `t` is floating point.
///
/// End condition (paper §6.1): stop when the end voxel is reached, or when the next boundary lies
/// farther along the ray than the end point (travelled distance > |end - origin|). Floating-point
/// error can trigger the second case one or two boundaries early, with the end voxel not yet
/// reached (paper fig. 11); the walk then "snaps" to the end voxel (paper fig. 12) by the key steps
/// still missing, one face step at a time. Each axis has an exact budget of |Δkey| steps, so the
/// walk never steps past the end key on any axis: keys stay in the box spanned by the origin and
/// end keys (no wrap-around at the map border), the last key is always the end key, and
/// consecutive keys are always face neighbours.
///
/// Unlike OctoMap's `computeRayKeys`, the end voxel IS visited (last); callers that want free
/// space only skip the last key.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/core/key.hpp"
#include "sonarmap/core/key_coder.hpp"

namespace sonarmap {

/// Visits the finest-level voxels crossed by the segment from `origin_m` to `end_m` with a 3D DDA.
///
/// @param coder     key convention and resolution of the tree.
/// @param origin_m  start of the segment, world frame, metres (e.g. the sonar head).
/// @param end_m     end of the segment, world frame, metres (e.g. the detected hit). A point,
///                  not a direction.
/// @param visit     callable as `visit(const Key<Depth>&)`; called once per voxel, in order along
///                  the segment, from the origin's voxel to the end's voxel, both included.
///                  Consecutive keys differ by exactly 1 in exactly one component. Its return
///                  value is ignored; an exception it throws propagates and ends the walk.
/// @return false, without calling `visit`, if either end point is outside the map or not finite
///         (see KeyCoder::keyOf); true otherwise. Equal voxels (including origin == end) visit one
///         key. Throws nothing itself.
///
/// Cost: one comparison chain and one addition per voxel, no allocation, no hashing. Number of
/// keys = |Δx| + |Δy| + |Δz| + 1 in key units. For very deep trees the walk is only as exact as
/// `double` is at the coordinates (53-bit mantissa); keys remain exact and monotone.
template <int Depth, class Visitor>
bool traverseDDA(const KeyCoder<Depth>& coder, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m,
                 Visitor&& visit) {
  using Index = KeyIndex<Depth>;
  const std::optional<Key<Depth>> origin_key = coder.keyOf(origin_m);
  const std::optional<Key<Depth>> end_key = coder.keyOf(end_m);
  if (!origin_key || !end_key) return false;

  Key<Depth> key = *origin_key;
  visit(std::as_const(key));
  if (key == *end_key) return true;

  // --- Initialisation phase (A&W §3), with t in metres along the ray. ---
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d direction_m = end_m - origin_m;
  const double length_m = direction_m.norm();  // > 0: the keys differ
  const double resolution_m = coder.resolution_m();
  const double inv_resolution = 1.0 / resolution_m;  // the factor KeyCoder::keyOf multiplies by

  std::array<Index, 3> step{};        // +1 or -1 (all ones: unsigned modular -1) per axis
  std::array<Index, 3> remaining{};   // key steps still owed per axis: |end - origin|
  std::array<double, 3> t_max{};      // metres along the ray to the next boundary of each axis
  std::array<double, 3> t_delta{};    // metres along the ray between two boundaries of each axis
  for (int axis = 0; axis < 3; ++axis) {
    const Index from = (*origin_key)[axis];
    const Index to = (*end_key)[axis];
    const bool up = to > from;
    step[axis] = up ? Index{1} : static_cast<Index>(~Index{0});
    remaining[axis] = up ? static_cast<Index>(to - from) : static_cast<Index>(from - to);
    if (remaining[axis] == 0) {  // includes zero direction components: never step this axis
      t_max[axis] = kInfinity;
      continue;
    }
    // floor() is monotone, so direction_m[axis] != 0 here and its sign is the sign of the step.
    // Position of the origin inside its voxel, in voxel units, computed as keyOf computes the key.
    const double cell = origin_m[axis] * inv_resolution;
    const double fraction = cell - std::floor(cell);  // in [0, 1]
    t_delta[axis] = resolution_m * length_m / std::fabs(direction_m[axis]);
    t_max[axis] = (up ? 1.0 - fraction : fraction) * t_delta[axis];
  }

  // Branch-free ±1: adding all ones is -1 modulo 2^bits. The result never actually wraps, because
  // the budget keeps every key between the origin's and the end's.
  const auto advance = [&](int axis) {
    key[axis] = static_cast<Index>(key[axis] + step[axis]);
    visit(std::as_const(key));
  };

  // --- Incremental phase (A&W §3): cross the nearest boundary. ---
  for (;;) {
    const int nearer_xy = t_max[1] < t_max[0] ? 1 : 0;  // written to compile to conditional moves
    const int axis = t_max[2] < t_max[nearer_xy] ? 2 : nearer_xy;
    // End voxel reached: every axis spent its budget and has t_max = +inf. Otherwise the paper's
    // distance condition: the next boundary is past the end point (also catches a NaN t_max).
    if (!(t_max[axis] <= length_m)) break;
    advance(axis);
    if (--remaining[axis] == 0) {
      t_max[axis] = kInfinity;
    } else {
      t_max[axis] += t_delta[axis];
    }
  }

  // --- Snap to the end voxel (paper §6.1, fig. 12): steps floating-point error left owed. ---
  for (int axis = 0; axis < 3; ++axis) {
    for (; remaining[axis] != 0; --remaining[axis]) advance(axis);
  }
  return true;
}

/// Keys of the voxels crossed by the segment from `origin_m` to `end_m` (3D DDA), in order, from
/// the origin's voxel to the end's voxel inclusive. Same arguments and guarantees as traverseDDA.
///
/// @param keys  output; cleared first, then filled. Reuse one vector across rays to avoid
///              reallocation (its capacity is kept).
/// @return false and empty `keys` if either end point is outside the map or not finite.
/// @throws std::bad_alloc (or std::length_error) if the keys do not fit in memory.
template <int Depth>
bool rayKeysDDA(const KeyCoder<Depth>& coder, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m,
                std::vector<Key<Depth>>& keys) {
  keys.clear();
  const std::optional<Key<Depth>> origin_key = coder.keyOf(origin_m);
  const std::optional<Key<Depth>> end_key = coder.keyOf(end_m);
  if (!origin_key || !end_key) return false;
  double count = 1.0;  // |Δx| + |Δy| + |Δz| + 1 keys; double: no overflow at any depth
  for (int axis = 0; axis < 3; ++axis) {
    const auto from = (*origin_key)[axis];
    const auto to = (*end_key)[axis];
    const double span = KeyCoder<Depth>::toDouble(to > from ? to - from : from - to);
    count += span;
  }
  keys.reserve(static_cast<std::size_t>(std::min(count, static_cast<double>(keys.max_size()))));
  return traverseDDA(coder, origin_m, end_m, [&keys](const Key<Depth>& key) { keys.push_back(key); });
}

}  // namespace sonarmap
