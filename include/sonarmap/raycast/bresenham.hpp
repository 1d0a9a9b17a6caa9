#pragma once
/// @file bresenham.hpp
/// 3D Bresenham line over octree keys (paper §6.2): integer-only, 26-connected voxel lines.
///
/// The line joins the centres of the origin's and the end's voxels. The main axis is the one with
/// the largest |Δkey|; every iteration steps it by one, and each of the two other axes keeps an
/// integer error accumulator and steps when its ideal position, rounded half up, moves to the next
/// voxel. Several axes can step in the same iteration (diagonal moves), so rays are thinner than
/// DDA's and can cut voxel corners: a "laser-like" line (paper §6.2). The end voxel is never
/// missed, and there are no floating-point decisions after the two keys are computed.
///
/// Arithmetic: instead of signed differences (which need a type wider than the key, and do not
/// exist for 128-bit keys), each axis keeps a direction and the magnitude |Δkey| in an unsigned
/// type as wide as the key (64 bits up to depth 64, 128 bits beyond), and the error update is
/// written so that no intermediate value exceeds |Δkey| of the main axis. Exact for every depth
/// 1…128, no overflow, no wrap-around.

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/core/key.hpp"
#include "sonarmap/core/key_coder.hpp"

namespace sonarmap {

/// Visits the voxels of the 3D Bresenham line from the voxel of `origin_m` to the voxel of `end_m`.
///
/// @param coder     key convention and resolution of the tree.
/// @param origin_m  start of the segment, world frame, metres.
/// @param end_m     end of the segment, world frame, metres (a point, not a direction).
/// @param visit     callable as `visit(const Key<Depth>&)`; called once per voxel in order, from
///                  the origin's voxel to the end's voxel, both included. Exactly
///                  max(|Δx|, |Δy|, |Δz|) + 1 calls (key units); consecutive keys differ by exactly
///                  1 on the main axis and by at most 1 on the others (26-neighbours). At main-axis
///                  step i the minor coordinate b is origin_b + sign·floor(i·|Δb|/|Δmain| + 1/2).
///                  Its return value is ignored; an exception it throws propagates.
/// @return false, without calling `visit`, if either end point is outside the map or not finite;
///         true otherwise. Throws nothing itself.
///
/// Only the voxels of the two end points matter: the line joins voxel centres, so it is the same
/// for any two points inside the same two voxels.
template <int Depth, class Visitor>
bool traverseBresenham(const KeyCoder<Depth>& coder, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m,
                       Visitor&& visit) {
  // Unsigned and at least as wide as the key (the 128-bit key type beyond depth 64): holds any
  // |Δkey| and every accumulator.
  using Wide = std::conditional_t<(Depth <= 64), std::uint64_t, KeyIndex<Depth>>;
  const std::optional<Key<Depth>> origin_key = coder.keyOf(origin_m);
  const std::optional<Key<Depth>> end_key = coder.keyOf(end_m);
  if (!origin_key || !end_key) return false;

  std::array<bool, 3> step_up{};  // direction of each axis: +1 (true) or -1 (false)
  std::array<Wide, 3> delta{};    // |Δkey| per axis
  for (int axis = 0; axis < 3; ++axis) {
    const Wide from = static_cast<Wide>((*origin_key)[axis]);
    const Wide to = static_cast<Wide>((*end_key)[axis]);
    step_up[axis] = to >= from;
    delta[axis] = step_up[axis] ? to - from : from - to;
  }
  // Main axis: largest |Δkey| (the first of equal ones); the other two are the minor axes.
  const int main_axis = delta[0] >= delta[1] ? (delta[0] >= delta[2] ? 0 : 2) : (delta[1] >= delta[2] ? 1 : 2);
  const int minor_a = (main_axis + 1) % 3;
  const int minor_b = (main_axis + 2) % 3;
  const Wide steps = delta[main_axis];

  // Error of minor axis b after i main steps: (i·|Δb| + floor(steps/2)) mod steps, always in
  // [0, steps). The axis steps when i·|Δb| + floor(steps/2) passes a multiple of steps, i.e. when
  // err + |Δb| >= steps, tested as err >= steps - |Δb| so nothing exceeds `steps`. Starting at
  // floor(steps/2) rounds the ideal position half up (classic 2·err form, without the doubling).
  std::array<Wide, 3> error{};
  error[minor_a] = steps / 2;
  error[minor_b] = steps / 2;
  const std::array<Wide, 3> threshold{steps - delta[0], steps - delta[1], steps - delta[2]};

  Key<Depth> key = *origin_key;
  const auto move = [&](int axis) {
    if (step_up[axis]) {
      ++key[axis];
    } else {
      --key[axis];
    }
  };
  const auto advance_minor = [&](int axis) {
    if (error[axis] >= threshold[axis]) {
      error[axis] -= threshold[axis];
      move(axis);
    } else {
      error[axis] += delta[axis];
    }
  };

  visit(std::as_const(key));
  for (Wide i = 0; i < steps; ++i) {
    move(main_axis);
    advance_minor(minor_a);
    advance_minor(minor_b);
    visit(std::as_const(key));
  }
  return true;
}

/// Keys of the 3D Bresenham line from the voxel of `origin_m` to the voxel of `end_m`, in order,
/// both included. Same arguments and guarantees as traverseBresenham.
///
/// @param keys  output; cleared first, then filled (capacity is kept: reuse it across rays).
/// @return false and empty `keys` if either end point is outside the map or not finite.
/// @throws std::bad_alloc (or std::length_error) if the keys do not fit in memory.
template <int Depth>
bool rayKeysBresenham(const KeyCoder<Depth>& coder, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m,
                      std::vector<Key<Depth>>& keys) {
  keys.clear();
  const std::optional<Key<Depth>> origin_key = coder.keyOf(origin_m);
  const std::optional<Key<Depth>> end_key = coder.keyOf(end_m);
  if (!origin_key || !end_key) return false;
  double count = 1.0;  // max(|Δx|, |Δy|, |Δz|) + 1 keys; double: no overflow at any depth
  for (int axis = 0; axis < 3; ++axis) {
    const auto from = (*origin_key)[axis];
    const auto to = (*end_key)[axis];
    const double span = KeyCoder<Depth>::toDouble(to > from ? to - from : from - to);
    count = std::max(count, span + 1.0);
  }
  keys.reserve(static_cast<std::size_t>(std::min(count, static_cast<double>(keys.max_size()))));
  return traverseBresenham(coder, origin_m, end_m, [&keys](const Key<Depth>& key) { keys.push_back(key); });
}

}  // namespace sonarmap
