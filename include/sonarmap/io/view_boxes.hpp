#pragma once
/// @file view_boxes.hpp
/// The boxes a 3D viewer draws for one occupancy class of a map: every leaf of that class as one
/// box of its real size (a pruned leaf is one bigger box), or, when there are more than a cap, the
/// nodes of a coarser level of the octree that hold such a leaf (downsampling).
///
/// Downsampling to depth d: a leaf finer than d is replaced by its ancestor at depth d, one box per
/// ancestor however many leaves it holds; a leaf at depth d or coarser stays as it is. With the
/// octree's default max aggregation (OctreeOptions::aggregation) these depth-d boxes are exactly the
/// inner nodes at depth d that an occupied leaf makes occupied. The deepest d whose box count fits the
/// cap is chosen, so a map is coarsened no more than needed. Boxes never overlap.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// One box of the viewer: a node of the depth-16 octree (a leaf, or an ancestor after downsampling).
struct ViewBox {
  Key<16> key;    ///< finest key of the box's lowest corner (OctoMap's key layout, key_coder.hpp)
  int depth = 16; ///< tree depth of the node: 16 is one voxel of `resolution_m`, 15 two voxels wide…
};

/// Boxes of one occupancy class, in a deterministic order (the tree's depth-first order when not
/// downsampled, else sorted by depth then z, y, x of the key).
struct ViewBoxes {
  std::vector<ViewBox> boxes;
  std::size_t leaves = 0;     ///< leaves of that class in the map (pruned leaves count once)
  int level = 16;             ///< deepest depth drawn: 16 when every leaf is its own box
  bool downsampled() const { return level < 16; }
};

/// The boxes of the leaves that `tree` classifies as `occupancy` (kOccupied or kFree; the tree's
/// thresholds, LogOddsModel::classify), at most `max_boxes` of them: downsampled to the deepest
/// level that fits as the file comment says (level 0, the root, is one box, so one always fits).
/// @throws ValueError when `max_boxes` is 0 or `occupancy` is kUnknown.
ViewBoxes collectViewBoxes(const OcTree16& tree, Occupancy occupancy, std::size_t max_boxes);

/// Lowest corner of a box in metres (map frame).
Eigen::Vector3d boxCorner_m(const OcTree16& tree, const ViewBox& box);

/// Edge length of a box in metres: resolution · 2^(16 − depth).
double boxEdge_m(const OcTree16& tree, const ViewBox& box);

}  // namespace sonarmap
