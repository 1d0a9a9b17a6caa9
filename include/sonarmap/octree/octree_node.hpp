#pragma once
/// @file octree_node.hpp
/// One octree node as NodePool stores it (node_pool.hpp says how the nodes are laid out).

#include <cmath>
#include <cstdint>
#include <limits>

namespace sonarmap {

/// Log-odds value that marks a node as not existing (unknown).
inline constexpr float kUnknownLogOdds = std::numeric_limits<float>::quiet_NaN();

/// One octree node: its log-odds and the slot of its children's array (0 = none). The top bit of
/// `link` marks an inner node whose subtree changed since the last lazy synchronisation.
struct OcTreeNode {
  static constexpr std::uint32_t kDirtyBit = 1U << 31;
  static constexpr std::uint32_t kArrayMask = kDirtyBit - 1;

  float log_odds = kUnknownLogOdds;
  std::uint32_t link = 0;

  bool exists() const { return !std::isnan(log_odds); }
  bool hasChildren() const { return (link & kArrayMask) != 0; }
  /// Slot of the children's array header, 0 when there are none.
  std::uint32_t array() const { return link & kArrayMask; }
  bool dirty() const { return (link & kDirtyBit) != 0; }
};
static_assert(sizeof(OcTreeNode) == 8, "a node is one float and one 32-bit index");

}  // namespace sonarmap
