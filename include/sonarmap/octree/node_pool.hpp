#pragma once
/// @file node_pool.hpp
/// Storage of octree nodes: 8-byte nodes, each inner node pointing to a compact array holding only
/// its existing children (paper §5.6's "single pointer to an array of children", made compact).
///
/// A node holds its log-odds (float32) and one 32-bit index of its children's array — an index
/// instead of a pointer, so a node is 8 bytes where OctoMap's is 16 plus a 64-byte array of 8
/// pointers per inner node. An array is one header slot followed by the existing children in child
/// order (0…7); the header records which children exist (an 8-bit mask) and the array's capacity
/// (1 to 8 children: exactly the children it holds, so no slot is spare). A path through sparse
/// space thus costs 16 bytes per level instead of OctoMap's 80, a full set of 8 children 72 bytes
/// instead of 192. Adding a child moves the array to the next capacity; freed arrays are reused by
/// capacity. Capacities of 1, 2, 4 and 8 left 9 % of a large multi-scan map's slots spare
/// (docs/performance.md, "Where the memory and time go") for no gain in insertion time.
///
/// All nodes live in one array of slots (SlotBuffer) addressed by 32-bit references. Slot 0 is the root;
/// slot 1 is a permanent "no node" (NaN log-odds) that `childRef` returns for a missing child.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/octree/slot_buffer.hpp"

namespace sonarmap {

/// Reference to a node: its slot. The root is reference 0.
using NodeRef = std::uint32_t;
inline constexpr NodeRef kRootRef = 0;
/// Reference of a child that does not exist: a node that never exists.
inline constexpr NodeRef kNoNodeRef = 1;

/// Nodes in compact children arrays with per-capacity free lists, addressed by 32-bit slots.
class NodePool {
 public:
  NodePool() { clear(); }

  OcTreeNode& at(NodeRef ref) { return slots_[ref]; }
  const OcTreeNode& at(NodeRef ref) const { return slots_[ref]; }

  /// Bit i set when child i of `parent` exists.
  unsigned childMask(const OcTreeNode& parent) const { return parent.hasChildren() ? maskOf(parent.array()) : 0U; }

  /// Number of existing children of `parent`; they occupy firstChild(parent) + 0 … count − 1.
  unsigned childCount(const OcTreeNode& parent) const { return kBitCount[childMask(parent)]; }

  /// Reference of the first existing child of a node that has children.
  static NodeRef firstChild(const OcTreeNode& parent) { return parent.array() + 1; }

  /// Reference of child `index` (0…7) of `parent`, kNoNodeRef when it does not exist.
  NodeRef childRef(const OcTreeNode& parent, unsigned index) const {
    if (!parent.hasChildren()) return kNoNodeRef;
    const std::uint32_t array = parent.array();
    const unsigned mask = maskOf(array);
    if (((mask >> index) & 1U) == 0) return kNoNodeRef;
    return array + 1 + kBitCount[mask & ((1U << index) - 1U)];
  }

  /// Gives the childless node `parent` the children in `mask` (non-zero), each with `log_odds`
  /// and no children. Invalidates C++ references to nodes (not NodeRefs).
  /// @throws ValueError when the pool would exceed 2^31 slots.
  void createChildren(NodeRef parent, unsigned mask, float log_odds);

  /// Adds the missing child `index` to `parent` (which may have no children yet) with `log_odds`
  /// and returns its reference. Moves `parent`'s other children when their array is full
  /// (their NodeRefs change; `parent`'s does not). @throws ValueError as createChildren.
  NodeRef addChild(NodeRef parent, unsigned index, float log_odds);

  /// Frees `parent`'s children array (its children must be childless) and clears its link.
  void releaseChildren(NodeRef parent);

  /// Drops every node, including the root.
  void clear();

  /// Makes room for `slots` more slots (nodes and array headers) at the end without moving the
  /// pool: one allocation, and no copy, before a known amount of growth. Capacity at least
  /// doubles when it grows, so repeated calls stay amortised O(1) per slot. Untouched capacity
  /// is address space, not resident memory. @throws std::bad_alloc.
  void reserve(std::size_t slots);

  /// Rewrites the tree below the root into a new vector, depth first, each array at the smallest
  /// capacity that holds its children: gives back freed arrays and spare capacity. Changes every
  /// NodeRef except the root's.
  void compact();

  /// Slots held by freed arrays, waiting for reuse.
  std::size_t freeSlots() const { return slots_.size() - used_slots_; }

  /// Bytes of the slots in use (root, the "no node" slot and live arrays): the map's own size.
  std::size_t bytesInUse() const { return used_slots_ * sizeof(OcTreeNode); }

  /// Bytes allocated for slots and free lists (capacity, not only what is in use).
  std::size_t bytesAllocated() const;

 private:
  static constexpr unsigned kClasses = 8;
  static constexpr std::array<unsigned, kClasses> kCapacity = {1, 2, 3, 4, 5, 6, 7, 8};
  static constexpr std::uint32_t kMaxSlots = OcTreeNode::kArrayMask;
  static constexpr std::array<std::uint8_t, 256> kBitCount = [] {
    std::array<std::uint8_t, 256> counts{};
    for (unsigned m = 0; m < 256; ++m) counts[m] = static_cast<std::uint8_t>((m & 1U) + (m > 1 ? counts[m >> 1] : 0));
    return counts;
  }();

  /// Capacity class of an array of `children` (1…8) children: one class per count.
  static unsigned classFor(unsigned children) { return children <= 1 ? 0 : children - 1; }
  unsigned maskOf(std::uint32_t array) const { return slots_[array].link & 0xFFU; }
  unsigned classOf(std::uint32_t array) const { return (slots_[array].link >> 8) & 7U; }
  void setHeader(std::uint32_t array, unsigned mask, unsigned cls) { slots_[array] = OcTreeNode{kUnknownLogOdds, mask | (cls << 8)}; }
  /// Slot of a new array of class `cls` (header included), from the free list or the end.
  std::uint32_t allocate(unsigned cls);
  void release(std::uint32_t array);
  /// Copies the subtree at `from` (in `old`) to `to`, appending its arrays (compact()).
  void copySubtree(const SlotBuffer& old, NodeRef from, NodeRef to);

  SlotBuffer slots_;  ///< grows without copying (mremap): no second copy while the tree grows
  std::array<std::vector<std::uint32_t>, kClasses> free_;
  std::size_t used_slots_ = 0;
};

}  // namespace sonarmap
