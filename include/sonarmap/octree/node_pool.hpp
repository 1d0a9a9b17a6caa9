#pragma once
/// @file node_pool.hpp
/// Storage of octree nodes: 8-byte nodes kept in blocks of 8 siblings (paper §5.6).
///
/// A node holds its log-odds (float32) and one 32-bit index of its children's block — the
/// "single pointer to an array of 8 children" of paper §5.6, with an index instead of a pointer
/// so a node is 8 bytes instead of OctoMap's 24 plus a 64-byte pointer array per inner node.
/// A child that does not exist (unknown space) has a NaN log-odds. Block 0 is never a child block:
/// its slot 0 holds the root, so `children == 0` means "no children".

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

/// Log-odds value that marks a node as not existing (unknown).
inline constexpr float kUnknownLogOdds = std::numeric_limits<float>::quiet_NaN();

/// One octree node: its log-odds and the index of its block of 8 children (0 = none). The top
/// bit of `link` marks an inner node whose subtree changed since the last lazy synchronisation.
struct OcTreeNode {
  static constexpr std::uint32_t kDirtyBit = 1U << 31;
  static constexpr std::uint32_t kBlockMask = kDirtyBit - 1;

  float log_odds = kUnknownLogOdds;
  std::uint32_t link = 0;

  bool exists() const { return !std::isnan(log_odds); }
  bool hasChildren() const { return (link & kBlockMask) != 0; }
  /// Index of the children's block, 0 when there are none.
  std::uint32_t block() const { return link & kBlockMask; }
  bool dirty() const { return (link & kDirtyBit) != 0; }
};
static_assert(sizeof(OcTreeNode) == 8, "a node is one float and one 32-bit index");

/// Reference to a node: block index × 8 + slot. The root is reference 0.
using NodeRef = std::uint32_t;
inline constexpr NodeRef kRootRef = 0;

/// Blocks of 8 sibling nodes with a free list, addressed by 32-bit indices.
class NodePool {
 public:
  using Block = std::array<OcTreeNode, 8>;

  NodePool() : blocks_(1) {}

  OcTreeNode& at(NodeRef ref) { return blocks_[ref >> 3][ref & 7U]; }
  const OcTreeNode& at(NodeRef ref) const { return blocks_[ref >> 3][ref & 7U]; }

  /// Reference of child `index` (0…7) of a node whose children block is `block`.
  static NodeRef childRef(std::uint32_t block, unsigned index) { return (block << 3) | index; }

  /// Allocates a block of 8 children, each with log-odds `fill` (NaN: none exist) and no children.
  /// @throws ValueError when more than 2^29 blocks would be needed (indices stay below the dirty bit).
  std::uint32_t allocate(float fill) {
    std::uint32_t block;
    if (!free_.empty()) {
      block = free_.back();
      free_.pop_back();
    } else {
      if (blocks_.size() >= (std::size_t{1} << 29)) throw ValueError("octree exceeds 2^29 node blocks");
      block = static_cast<std::uint32_t>(blocks_.size());
      blocks_.emplace_back();
    }
    for (auto& node : blocks_[block]) node = OcTreeNode{fill, 0};
    ++in_use_;
    return block;
  }

  /// Returns a block to the free list. Its nodes' own children must already be released.
  void release(std::uint32_t block) {
    free_.push_back(block);
    --in_use_;
  }

  /// Drops every node, including the root.
  void clear() {
    blocks_.assign(1, Block{});
    free_.clear();
    in_use_ = 0;
  }

  std::size_t blocksInUse() const { return in_use_; }

  /// Bytes allocated for nodes and the free list (capacity, not only what is in use).
  std::size_t bytesAllocated() const {
    return blocks_.capacity() * sizeof(Block) + free_.capacity() * sizeof(std::uint32_t);
  }

  /// Bytes of the blocks in use plus the root's block: the map's own size.
  std::size_t bytesInUse() const { return (in_use_ + 1) * sizeof(Block); }


 private:
  std::vector<Block> blocks_;
  std::vector<std::uint32_t> free_;
  std::size_t in_use_ = 0;
};

}  // namespace sonarmap
