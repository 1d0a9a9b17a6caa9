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
/// still missing, one face step at a time, x first, then y, then z. Each axis has an exact budget
/// of |Δkey| steps, so the walk never steps past the end key on any axis: keys stay in the box
/// spanned by the origin and end keys (no wrap-around at the map border), the last key is always
/// the end key, and consecutive keys are always face neighbours. Equal `tMax` (a ray through an
/// edge or a corner) step x before y before z.
///
/// Unlike OctoMap's `computeRayKeys`, the end voxel IS visited (last); callers that want free
/// space only skip the last key.
///
/// Implementation: each axis' state is a scalar DdaAxis (x, y and z), selected by comparisons
/// rather than by indexing arrays with a run-time axis, and each key handed to the visitor is
/// assembled from the three indices; detail::traverseDDASteps also tells the visitor, at compile
/// time, which axis was stepped. The hot loop thus stays in registers, with no store-to-load
/// round trip through memory per voxel. The budget of an axis is its end key index.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/core/key.hpp"
#include "sonarmap/core/key_coder.hpp"

namespace sonarmap {

/// The axis a DDA visit stepped along, known at compile time: 0, 1, 2 for x, y, z; -1 for the
/// origin's voxel (no step).
template <int A>
using SteppedAxis = std::integral_constant<int, A>;

namespace detail {

/// DDA state of one axis (Amanatides & Woo 1987, §3; paper §6.1). Distances `t_*` are metres along
/// the ray from the origin; indices are key components (finest level) of this axis.
template <class Index>
struct DdaAxis {
  Index index = 0;  ///< current voxel
  Index end = 0;    ///< end voxel: the budget, never stepped past
  Index step = 0;   ///< +1 or all ones (unsigned modular -1): the key step towards `end`
  double t_max = std::numeric_limits<double>::infinity();  ///< to the next boundary; +inf at `end`
  double t_delta = 0.0;  ///< between two boundaries of this axis: resolution / |direction|

  /// Steps `index` one voxel towards `end`. Adding all ones subtracts 1 modulo 2^bits; the index
  /// stays between the origin's and the end's, so it never actually wraps.
  void advance() { index = static_cast<Index>(index + step); }

  /// Crosses the next boundary of this axis: advance(), then move `t_max` to the following
  /// boundary, or to +inf once `end` is reached so that the axis is never chosen again.
  void cross() {
    advance();
    if (index == end) {
      t_max = std::numeric_limits<double>::infinity();
    } else {
      t_max += t_delta;
    }
  }
};

/// Initialisation phase (A&W §3) of one axis.
/// @param from, to        key indices of the origin and end voxels on this axis.
/// @param origin_m        this axis' coordinate of the origin, world frame, metres.
/// @param direction_m     this axis' component of end - origin, metres.
/// @param length_m        |end - origin|, metres.
/// @param resolution_m    voxel edge, metres; `inv_resolution` = 1 / resolution_m, the factor
///                        KeyCoder::keyOf multiplies by.
template <class Index>
DdaAxis<Index> makeDdaAxis(Index from, Index to, double origin_m, double direction_m, double length_m,
                           double resolution_m, double inv_resolution) {
  DdaAxis<Index> axis;
  axis.index = from;
  axis.end = to;
  const bool up = to > from;
  axis.step = up ? Index{1} : static_cast<Index>(~Index{0});
  if (from == to) return axis;  // includes zero direction components: never stepped, t_max = +inf
  // floor() is monotone, so direction_m != 0 here and its sign is the sign of the step. Position
  // of the origin inside its voxel, in voxel units, computed as keyOf computes the key.
  const double cell = origin_m * inv_resolution;
  const double fraction = cell - std::floor(cell);  // in [0, 1]
  axis.t_delta = resolution_m * length_m / std::fabs(direction_m);
  axis.t_max = (up ? 1.0 - fraction : fraction) * axis.t_delta;
  return axis;
}

/// Incremental phase (A&W §3): crosses the nearest boundary, calling `visit_current(stepped)`
/// after each step, until every axis is at its end (all `t_max` = +inf) or the nearest boundary
/// lies past `length_m` metres — the paper's distance condition, which also stops at a NaN
/// `t_max`. Ties go to x, then y. `length_m` must be finite (+inf would pass the +inf of finished
/// axes). With kTellAxis, `stepped` is the SteppedAxis crossed (one call per branch); without,
/// it is SteppedAxis<-1> from a single call after the branch, the tighter loop.
template <bool kTellAxis, class Index, class VisitCurrent>
void crossBoundaries(DdaAxis<Index>& x, DdaAxis<Index>& y, DdaAxis<Index>& z, double length_m,
                     VisitCurrent& visit_current) {
  for (;;) {
    const bool y_first = y.t_max < x.t_max;
    const double t_xy = y_first ? y.t_max : x.t_max;
    const bool z_first = z.t_max < t_xy;
    if (!((z_first ? z.t_max : t_xy) <= length_m)) return;
    if constexpr (kTellAxis) {
      if (z_first) {
        z.cross();
        visit_current(SteppedAxis<2>{});
      } else if (y_first) {
        y.cross();
        visit_current(SteppedAxis<1>{});
      } else {
        x.cross();
        visit_current(SteppedAxis<0>{});
      }
    } else {
      if (z_first) {
        z.cross();
      } else if (y_first) {
        y.cross();
      } else {
        x.cross();
      }
      visit_current(SteppedAxis<-1>{});
    }
  }
}

/// Snap (paper §6.1, fig. 12): the key steps `axis` (number A) still owes, one
/// visit_current(SteppedAxis<A>) after each.
template <int A, class Index, class VisitCurrent>
void snapToEnd(DdaAxis<Index>& axis, VisitCurrent& visit_current) {
  while (axis.index != axis.end) {
    axis.advance();
    visit_current(SteppedAxis<A>{});
  }
}

/// The walk of traverseDDA and traverseDDASteps: `visit(key, stepped)` for every key, `stepped`
/// as crossBoundaries<kTellAxis> gives it (SteppedAxis<-1> for the origin's voxel).
template <bool kTellAxis, int Depth, class Visitor>
[[gnu::always_inline]] inline bool walkDDA(const KeyCoder<Depth>& coder, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m,
             Visitor&& visit) {
  Key<Depth> origin_key, end_key;
  if (!coder.keyInto(origin_m, origin_key) || !coder.keyInto(end_m, end_key)) return false;
  visit(std::as_const(origin_key), SteppedAxis<-1>{});
  if (origin_key == end_key) return true;

  // --- Initialisation phase (A&W §3), with t in metres along the ray. ---
  const Eigen::Vector3d direction_m = end_m - origin_m;
  const double length_m = direction_m.norm();  // > 0: the keys differ
  const double resolution_m = coder.resolution_m();
  const double inv_resolution = 1.0 / resolution_m;
  const auto axis = [&](int a) {
    return makeDdaAxis(origin_key[a], end_key[a], origin_m[a], direction_m[a], length_m, resolution_m,
                       inv_resolution);
  };
  auto x = axis(0);
  auto y = axis(1);
  auto z = axis(2);
  const auto visit_current = [&](auto stepped) {
    const Key<Depth> key{{x.index, y.index, z.index}};
    visit(key, stepped);
  };

  // Incremental phase (A&W §3), then the snap (paper §6.1, fig. 12): the steps still owed.
  if (length_m < std::numeric_limits<double>::infinity()) {
    crossBoundaries<kTellAxis>(x, y, z, length_m, visit_current);
  }
  snapToEnd<0>(x, visit_current);
  snapToEnd<1>(y, visit_current);
  snapToEnd<2>(z, visit_current);
  return true;
}

}  // namespace detail

/// traverseDDA, with each visit told the axis it stepped along: `visit(key, SteppedAxis<A>{})`,
/// A = -1 for the first key (the origin's voxel), 0/1/2 when the key differs from the one before
/// along x/y/z only. Callers that keep per-key state can update just that axis' part of it.
/// Same arguments, order and guarantees as traverseDDA.
template <int Depth, class Visitor>
[[gnu::always_inline]] inline bool traverseDDASteps(const KeyCoder<Depth>& coder, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m,
                      Visitor&& visit) {
  return detail::walkDDA<true>(coder, origin_m, end_m, visit);
}

/// Visits the finest-level voxels crossed by the segment from `origin_m` to `end_m` with a 3D DDA.
///
/// @param coder     key convention and resolution of the tree.
/// @param origin_m  start of the segment, world frame, metres (e.g. the sonar head).
/// @param end_m     end of the segment, world frame, metres (e.g. the detected hit). A point,
///                  not a direction.
/// @param visit     callable as `visit(const Key<Depth>&)`; called once per voxel, in order along
///                  the segment, from the origin's voxel to the end's voxel, both included.
///                  Consecutive keys differ by exactly 1 in exactly one component. Its return
///                  value is ignored; an exception it throws propagates and ends the walk. The
///                  key it gets is valid during the call only (copy it to keep it).
/// @return false, without calling `visit`, if either end point is outside the map or not finite
///         (see KeyCoder::keyOf); true otherwise. Equal voxels (including origin == end) visit one
///         key. Throws nothing itself.
///
/// Cost: about two comparisons, one key step and one addition per voxel, all in registers; no
/// allocation, no hashing. Number of keys = |Δx| + |Δy| + |Δz| + 1 in key units. For very deep
/// trees the walk is only as exact as `double` is at the coordinates (53-bit mantissa); keys
/// remain exact and monotone. If |end - origin| overflows `double` (only possible with absurd
/// resolutions, beyond ~1e115 m), no distance is usable and the walk is the snap alone.
template <int Depth, class Visitor>
bool traverseDDA(const KeyCoder<Depth>& coder, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& end_m,
                 Visitor&& visit) {
  return detail::walkDDA<false>(coder, origin_m, end_m, [&visit](const Key<Depth>& key, auto) { visit(key); });
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
