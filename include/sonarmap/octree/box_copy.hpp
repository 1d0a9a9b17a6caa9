#pragma once
/// @file box_copy.hpp
/// A part of an occupancy octree as a tree of its own: the leaves that meet a box of keys, copied
/// with their log-odds, for a reader that needs one region (the live page's map tiles) without
/// copying the whole map.

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Geometry>

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// A tree with the resolution and options of `map` holding every leaf of `map` that meets the key
/// box [min_key, max_key] (inclusive on each axis), whole (a pruned leaf larger than the box is
/// copied at its size), with its log-odds; nothing outside those leaves. Inner nodes are up to
/// date. Cost: the leaves meeting the box (forEachLeafInBox). An empty box (min > max on an axis)
/// gives an empty tree. Nothing is thrown but std::bad_alloc.
template <int Depth>
OccupancyOctree<Depth> copyLeavesInBox(const OccupancyOctree<Depth>& map, const Key<Depth>& min_key,
                                       const Key<Depth>& max_key) {
  OctreeOptions options = map.options();
  options.prune = true;  // a pruned leaf is copied as one cube (updateCube), not voxel by voxel
  options.lazy = false;
  OccupancyOctree<Depth> part(map.resolution_m(), options);
  map.forEachLeafInBox(min_key, max_key, [&part](const LeafView<Depth>& leaf) {
    if (leaf.depth == Depth) {
      part.updateNode(leaf.key, leaf.log_odds, true);
    } else {
      part.updateCube(leaf.key, leaf.depth, leaf.log_odds);
    }
  });
  part.updateInnerOccupancy();
  return part;
}

/// The keys of the voxels meeting `box_m` (metres, the map's frame), clipped to the map's extent:
/// (min key, max key), inclusive. An empty box (Eigen's isEmpty) gives min > max on an axis.
template <int Depth>
std::pair<Key<Depth>, Key<Depth>> keyBoxOf(const KeyCoder<Depth>& coder, const Eigen::AlignedBox3d& box_m) {
  using Index = typename Key<Depth>::Index;
  Key<Depth> min_key{}, max_key{};
  if (box_m.isEmpty()) {
    min_key[0] = 1;
    return {min_key, max_key};
  }
  const double last = 2.0 * KeyCoder<Depth>::offset() - 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    const auto index = [&](double coord_m) {
      const double cell = std::floor(coord_m / coder.resolution_m()) + KeyCoder<Depth>::offset();
      return static_cast<Index>(std::clamp(cell, 0.0, last));
    };
    min_key[axis] = index(box_m.min()[axis]);
    max_key[axis] = index(box_m.max()[axis]);
  }
  return {min_key, max_key};
}

}  // namespace sonarmap
