#pragma once
// Helpers shared by the octree tests: keys around the map origin and leaf lists to compare trees.

#include <cstdint>
#include <tuple>
#include <vector>

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap::testing {

/// The depth-16 key (x, y, z) voxels from the map origin's voxel (key 32768 on each axis).
inline Key16 key16(int x, int y, int z) {
  return Key16{{static_cast<std::uint16_t>(32768 + x), static_cast<std::uint16_t>(32768 + y),
                static_cast<std::uint16_t>(32768 + z)}};
}

/// A leaf as a comparable tuple: key x, y, z, depth, log-odds.
using Leaf = std::tuple<std::uint16_t, std::uint16_t, std::uint16_t, int, float>;

inline Leaf asTuple(const LeafView<16>& l) { return {l.key[0], l.key[1], l.key[2], l.depth, l.log_odds}; }

/// Every leaf of `tree` in forEachLeaf order: equal lists mean identical trees.
inline std::vector<Leaf> leavesOf(const OcTree16& tree) {
  std::vector<Leaf> leaves;
  tree.forEachLeaf([&](const LeafView<16>& l) { leaves.push_back(asTuple(l)); });
  return leaves;
}

}  // namespace sonarmap::testing
