#pragma once
/// @file occupancy_octree_impl.hpp
/// Member definitions of OccupancyOctree (included by occupancy_octree.hpp).

#include <algorithm>
#include <array>
#include <bit>
#include <string>
#include <utility>

namespace sonarmap {

template <int Depth>
int OccupancyOctree<Depth>::cachedLevels(const KeyType& key) const {
  if (cached_levels_ < 0) return 0;
  using Index = typename KeyType::Index;
  const Index differ = static_cast<Index>((key[0] ^ cached_key_[0]) | (key[1] ^ cached_key_[1]) | (key[2] ^ cached_key_[2]));
  // Levels whose child index agrees: those above the highest differing bit.
  int common = Depth;
  if (differ != 0) {
    if constexpr (Depth <= 64) {
      common = Depth - 1 - (std::bit_width(static_cast<std::uint64_t>(differ)) - 1);
    } else {
      const auto high = static_cast<std::uint64_t>(differ >> 64);
      const int bit = high != 0 ? 64 + std::bit_width(high) - 1 : std::bit_width(static_cast<std::uint64_t>(differ)) - 1;
      common = Depth - 1 - bit;
    }
  }
  return std::min(common, cached_levels_);
}

template <int Depth>
int OccupancyOctree<Depth>::descend(const KeyType& key, int target, int& fresh_from) {
  path_[0] = kRootRef;
  if (!pool_.at(kRootRef).exists()) {
    pool_.at(kRootRef).log_odds = 0.0F;
    fresh_from = 0;
    return 0;
  }
  // Start from the deepest node shared with the previous update's path, then descend through
  // existing nodes to the deepest one containing the key.
  int level = std::min(cachedLevels(key), target);
  while (level < target) {
    const NodeRef child = pool_.childRef(pool_.at(path_[level]), childIndex(key, level));
    if (child == kNoNodeRef) break;
    path_[++level] = child;
  }
  cached_key_ = key;
  cached_levels_ = level;
  return level;
}

template <int Depth>
void OccupancyOctree<Depth>::createPath(const KeyType& key, int level, int target, int& fresh_from) {
  // Create (or expand a pruned leaf into) the missing levels down to `target`.
  for (; level < target; ++level) {
    const NodeRef ref = path_[level];
    const unsigned index = childIndex(key, level);
    if (level < fresh_from && !pool_.at(ref).hasChildren()) {  // a pruned leaf: all 8 children inherit it
      pool_.createChildren(ref, 0xFFU, pool_.at(ref).log_odds);
      path_[level + 1] = pool_.childRef(pool_.at(ref), index);
    } else {
      path_[level + 1] = pool_.addChild(ref, index, 0.0F);
      fresh_from = std::min(fresh_from, level + 1);
    }
  }
  cached_key_ = key;
  cached_levels_ = target;
}

template <int Depth>
bool OccupancyOctree<Depth>::updateNode(const KeyType& key, float delta_log_odds, bool lazy_eval) {
  if (delta_log_odds == 0.0F) return false;
  int fresh_from = Depth + 1;  // first level created by this update
  const int level = descend(key, Depth, fresh_from);
  if (fresh_from > Depth && options_.stability_check) {
    const OcTreeNode& deepest = pool_.at(path_[level]);
    const bool is_leaf = level == Depth || !deepest.hasChildren();
    if (is_leaf && model_.isStable(deepest.log_odds, delta_log_odds)) return false;
  }
  createPath(key, level, Depth, fresh_from);
  OcTreeNode& leaf = pool_.at(path_[Depth]);
  const float before = leaf.log_odds;
  leaf.log_odds = model_.update(before, delta_log_odds);
  if (detect_changes_) [[unlikely]] {
    recordChange(changes_, model_, key, fresh_from <= Depth, before, leaf.log_odds);
  }
  if (options_.lazy || lazy_eval) {
    markPathDirty(Depth);
  } else {
    updateAncestors(fresh_from);
  }
  return true;
}

template <int Depth>
void OccupancyOctree<Depth>::updateCube(const KeyType& key, int depth, float delta_log_odds) {
  if (delta_log_odds == 0.0F) return;
  depth = std::clamp(depth, 0, Depth);
  if (depth == Depth || !options_.prune || detect_changes_) {  // every voxel needs its own leaf or record
    if (Depth - depth > kMaxVoxelwiseCubeLevels) {
      throw ValueError("updateCube: a cube of 2^" + std::to_string(Depth - depth) +
                       " voxels per edge needs pruning on and change detection off");
    }
    forEachVoxelOfCube(key, depth, [&](const KeyType& voxel) { updateNode(voxel, delta_log_odds, true); });
    return;
  }
  int fresh_from = Depth + 1;
  const int level = descend(key, depth, fresh_from);
  if (coveredByStableLeaf(level, fresh_from, delta_log_odds)) return;
  createPath(key, level, depth, fresh_from);
  const NodeRef target = path_[depth];
  bool changed = level < depth;  // nodes were created or expanded on the way
  if (depth >= fresh_from) {
    pool_.at(target).log_odds = model_.update(0.0F, delta_log_odds);  // unknown space: one new leaf
  } else {
    changed = updateSubtree(target, delta_log_odds) || changed;
  }
  if (changed) markPathDirty(depth);
}

template <int Depth>
bool OccupancyOctree<Depth>::coveredByStableLeaf(int level, int fresh_from, float delta_log_odds) const {
  // A leaf containing the whole cube, already clamped in the update's direction: the update would
  // change no value (the stability check of §5.3, for a whole cube at once).
  const OcTreeNode& deepest = pool_.at(path_[level]);
  return fresh_from > Depth && !deepest.hasChildren() && model_.isStable(deepest.log_odds, delta_log_odds);
}

template <int Depth>
void OccupancyOctree<Depth>::updateBrick(const KeyType& corner, std::uint64_t voxels, float delta_log_odds) {
  static_assert(Depth >= 2, "a brick spans the two finest levels");
  if (voxels == 0 || delta_log_odds == 0.0F) return;
  if (!options_.prune || detect_changes_) {  // voxel by voxel, for their own leaves or change records
    for (unsigned b = 0; b < 64; ++b) {
      if (((voxels >> b) & 1U) != 0) updateNode(brickKey(corner, b), delta_log_odds, true);
    }
    return;
  }
  if (voxels == ~std::uint64_t{0}) {
    updateCube(corner, Depth - 2, delta_log_odds);
    return;
  }
  int fresh_from = Depth + 1;
  const int level = descend(corner, Depth - 2, fresh_from);
  if (coveredByStableLeaf(level, fresh_from, delta_log_odds)) return;
  createPath(corner, level, Depth - 2, fresh_from);
  const float fresh = model_.update(0.0F, delta_log_odds);
  bool changed = level < Depth - 2;  // nodes were created or expanded on the way
  if (Depth - 2 >= fresh_from) {
    buildFreshBrick(path_[Depth - 2], voxels, fresh);
  } else {
    changed = mergeBrick(path_[Depth - 2], voxels, delta_log_odds, fresh) || changed;
  }
  if (changed) markPathDirty(Depth - 2);
}

template <int Depth>
bool OccupancyOctree<Depth>::mergeBrick(NodeRef brick, std::uint64_t voxels, float delta_log_odds, float fresh) {
  // A known brick: update its voxels in place, one octet (node one level up) at a time. Marks
  // dirty, and reports, only what changed: clamped voxels seen again leave the sync nothing to do.
  bool changed = !pool_.at(brick).hasChildren();
  if (changed) pool_.createChildren(brick, 0xFFU, pool_.at(brick).log_odds);  // expand a pruned leaf
  for (unsigned octet = 0; octet < 8; ++octet) {
    const auto bits = static_cast<unsigned>((voxels >> (8 * octet)) & 0xFFU);
    if (bits == 0) continue;
    const NodeRef child = pool_.childRef(pool_.at(brick), octet);
    if (child != kNoNodeRef) {
      changed = mergeOctet(child, bits, delta_log_odds, fresh) || changed;
    } else if (bits == 0xFFU) {
      pool_.addChild(brick, octet, fresh);  // unknown: one leaf
      changed = true;
    } else {
      pool_.createChildren(pool_.addChild(brick, octet, fresh), bits, fresh);  // in sync, not prunable
      changed = true;
    }
  }
  if (changed) pool_.at(brick).link |= OcTreeNode::kDirtyBit;
  return changed;
}

template <int Depth>
bool OccupancyOctree<Depth>::mergeOctet(NodeRef node, unsigned bits, float delta_log_odds, float fresh) {
  if (!pool_.at(node).hasChildren()) {
    if (bits == 0xFFU) return updateLeaf(node, delta_log_odds);  // the whole leaf
    if (model_.isStable(pool_.at(node).log_odds, delta_log_odds)) return false;
    pool_.createChildren(node, 0xFFU, pool_.at(node).log_odds);  // expand a pruned leaf
    pool_.at(node).link |= OcTreeNode::kDirtyBit;
  }
  bool changed = false;
  const unsigned mask = pool_.childMask(pool_.at(node));
  if ((bits & ~mask) == 0) {
    // Every voxel has its leaf (the usual case once known): none is added, so the children stay
    // where they are, consecutive slots in child order.
    NodeRef leaf = NodePool::firstChild(pool_.at(node));
    for (unsigned rest = mask; rest != 0; rest &= rest - 1, ++leaf) {
      if (((bits >> std::countr_zero(rest)) & 1U) != 0) changed = updateLeaf(leaf, delta_log_odds) || changed;
    }
  } else {
    for (unsigned rest = bits; rest != 0; rest &= rest - 1) {
      const auto i = static_cast<unsigned>(std::countr_zero(rest));
      const NodeRef leaf = pool_.childRef(pool_.at(node), i);  // again after each addChild: arrays move
      if (leaf == kNoNodeRef) {
        pool_.addChild(node, i, fresh);
        changed = true;
      } else {
        changed = updateLeaf(leaf, delta_log_odds) || changed;
      }
    }
  }
  if (changed) pool_.at(node).link |= OcTreeNode::kDirtyBit;
  return changed || pool_.at(node).dirty();
}

template <int Depth>
bool OccupancyOctree<Depth>::updateLeaf(NodeRef leaf, float delta_log_odds) {
  const float before = pool_.at(leaf).log_odds;
  pool_.at(leaf).log_odds = model_.update(before, delta_log_odds);
  return pool_.at(leaf).log_odds != before;
}

template <int Depth>
void OccupancyOctree<Depth>::buildFreshBrick(NodeRef brick, std::uint64_t voxels, float log_odds) {
  // The brick's node is new: give it exactly its children, each exactly its own (no array grows).
  // Every node built holds `log_odds`, the max and the mean of its children, and none can be
  // pruned (a full brick goes to updateCube, a full octet is one leaf): all are already in sync.
  unsigned octets = 0;
  for (unsigned octet = 0; octet < 8; ++octet) octets |= ((voxels >> (8 * octet)) & 0xFFU) != 0 ? 1U << octet : 0U;
  pool_.createChildren(brick, octets, log_odds);
  pool_.at(brick).log_odds = log_odds;
  NodeRef child = NodePool::firstChild(pool_.at(brick));
  for (unsigned rest = octets; rest != 0; rest &= rest - 1, ++child) {
    const auto bits = static_cast<unsigned>((voxels >> (8 * std::countr_zero(rest))) & 0xFFU);
    if (bits != 0xFFU) pool_.createChildren(child, bits, log_odds);  // else a whole octet: one leaf
  }
}

template <int Depth>
typename OccupancyOctree<Depth>::KeyType OccupancyOctree<Depth>::brickKey(const KeyType& corner, unsigned bit) {
  using Index = typename KeyType::Index;
  KeyType key;
  for (unsigned axis = 0; axis < 3; ++axis) {
    const auto low = static_cast<Index>(((bit >> axis) & 1U) | (((bit >> (axis + 3)) & 1U) << 1));
    key[axis] = static_cast<Index>((corner[axis] & ~Index{3}) | low);
  }
  return key;
}

template <int Depth>
bool OccupancyOctree<Depth>::updateSubtree(NodeRef ref, float delta_log_odds) {
  // Each leaf stands for equal voxels; unknown children become leaves of their own size. Marks
  // dirty, and reports, only what changed.
  if (!pool_.at(ref).hasChildren()) return updateLeaf(ref, delta_log_odds);
  const unsigned mask = pool_.childMask(pool_.at(ref));
  const NodeRef first = NodePool::firstChild(pool_.at(ref));
  const unsigned count = pool_.childCount(pool_.at(ref));
  bool changed = mask != 0xFFU;
  for (NodeRef child = first; child < first + count; ++child) changed = updateSubtree(child, delta_log_odds) || changed;
  const float fresh = model_.update(0.0F, delta_log_odds);
  for (unsigned i = 0; i < 8; ++i) {
    if (((mask >> i) & 1U) == 0) pool_.addChild(ref, i, fresh);
  }
  if (changed) pool_.at(ref).link |= OcTreeNode::kDirtyBit;
  return changed;
}

template <int Depth>
template <class Visitor>
void OccupancyOctree<Depth>::forEachVoxelOfCube(const KeyType& key, int depth, Visitor&& visit) {
  using Index = typename KeyType::Index;
  const int bits = Depth - depth;  // ≤ kMaxVoxelwiseCubeLevels
  const std::uint32_t edge = std::uint32_t{1} << bits;
  const auto low = static_cast<Index>(edge - 1);
  KeyType voxel;
  for (std::uint32_t x = 0; x < edge; ++x)
    for (std::uint32_t y = 0; y < edge; ++y)
      for (std::uint32_t z = 0; z < edge; ++z) {
        voxel[0] = static_cast<Index>((key[0] & ~low) | x);
        voxel[1] = static_cast<Index>((key[1] & ~low) | y);
        voxel[2] = static_cast<Index>((key[2] & ~low) | z);
        visit(std::as_const(voxel));
      }
}

template <int Depth>
void OccupancyOctree<Depth>::markPathDirty(int below) {
  // Ancestors of a dirty node are dirty: stop at the first one already marked.
  for (int l = below - 1; l >= 0; --l) {
    OcTreeNode& inner = pool_.at(path_[l]);
    if (inner.dirty()) return;
    inner.link |= OcTreeNode::kDirtyBit;
  }
}

template <int Depth>
void OccupancyOctree<Depth>::updateAncestors(int fresh_from) {
  // Fix the inner nodes bottom-up; stop once nothing above can change.
  for (int l = Depth - 1; l >= 0; --l) {
    const float before = pool_.at(path_[l]).log_odds;
    if (refreshInner(path_[l], /*keep_dirty=*/true)) {
      cached_levels_ = std::min(cached_levels_, l);  // the pruned children are gone
      continue;
    }
    if (pool_.at(path_[l]).log_odds == before && l + 1 < fresh_from) break;
  }
}

template <int Depth>
typename OccupancyOctree<Depth>::ChildSummary OccupancyOctree<Depth>::summarize(const OcTreeNode& parent) const {
  const unsigned count = pool_.childCount(parent);
  const OcTreeNode* children = &pool_.at(NodePool::firstChild(parent));
  float max = -std::numeric_limits<float>::infinity();
  float sum = 0.0F;
  bool leaves_equal = count == 8;
  for (unsigned k = 0; k < count; ++k) {
    const OcTreeNode& child = children[k];
    leaves_equal = leaves_equal && !child.hasChildren() && child.log_odds == children[0].log_odds;
    max = std::max(max, child.log_odds);
    sum += child.log_odds;
  }
  if (count == 0) return {0.0F, false};
  const float aggregate = options_.aggregation == InnerAggregation::kMax ? max : sum / static_cast<float>(count);
  return {aggregate, leaves_equal};
}

template <int Depth>
float OccupancyOctree<Depth>::aggregateChildren(const OcTreeNode& parent) const {
  return summarize(parent).aggregate;
}

template <int Depth>
bool OccupancyOctree<Depth>::refreshInner(NodeRef ref, bool keep_dirty) {
  const ChildSummary summary = summarize(pool_.at(ref));
  OcTreeNode& node = pool_.at(ref);
  node.log_odds = summary.aggregate;
  if (!(options_.prune && summary.prunable)) {
    if (!keep_dirty) node.link &= ~OcTreeNode::kDirtyBit;
    return false;
  }
  pool_.releaseChildren(ref);  // all 8 equal leaves: the node becomes the leaf
  return true;
}

template <int Depth>
void OccupancyOctree<Depth>::updateInnerOccupancy() {
  cached_levels_ = -1;  // pruning may free nodes on the cached path
  const bool all = !options_.lazy;
  const OcTreeNode& root = pool_.at(kRootRef);
  if (root.hasChildren() && (root.dirty() || all)) syncSubtree(kRootRef, all);
  shrinkIfMostlyFree();
}

template <int Depth>
void OccupancyOctree<Depth>::shrinkIfMostlyFree() {
  if (pool_.freeSlots() > 4 * (pool_.bytesInUse() / sizeof(OcTreeNode))) shrinkToFit();
}

template <int Depth>
void OccupancyOctree<Depth>::updateDirtyInnerOccupancy() {
  cached_levels_ = -1;
  const OcTreeNode& root = pool_.at(kRootRef);
  if (root.hasChildren() && root.dirty()) syncSubtree(kRootRef, false);
  shrinkIfMostlyFree();
}

template <int Depth>
void OccupancyOctree<Depth>::syncSubtree(NodeRef ref, bool all) {
  // Post-order over the subtrees that changed since the last synchronisation (dirty nodes);
  // a clean subtree is already consistent. `all` visits every inner node (eager trees).
  const OcTreeNode& node = pool_.at(ref);
  if (!node.hasChildren()) return;
  const NodeRef first = NodePool::firstChild(node);
  const unsigned count = pool_.childCount(node);
  for (NodeRef child = first; child < first + count; ++child) {
    if (pool_.at(child).hasChildren() && (pool_.at(child).dirty() || all)) syncSubtree(child, all);
  }
  refreshInner(ref);
}

template <int Depth>
void OccupancyOctree<Depth>::createChildren(NodeRef ref, unsigned mask) {
  cached_levels_ = -1;
  if (ref == kNoNodeRef || pool_.at(ref).hasChildren()) throw ValueError("createChildren needs an existing childless node");
  if ((mask & 0xFFU) != 0) pool_.createChildren(ref, mask & 0xFFU, 0.0F);
}

template <int Depth>
std::optional<float> OccupancyOctree<Depth>::search(const KeyType& key, int depth) const {
  NodeRef ref = kRootRef;
  if (!pool_.at(ref).exists()) return std::nullopt;
  const int target = std::clamp(depth, 0, Depth);
  for (int level = 0; level < target && pool_.at(ref).hasChildren(); ++level) {
    ref = pool_.childRef(pool_.at(ref), childIndex(key, level));
    if (ref == kNoNodeRef) return std::nullopt;
  }
  return pool_.at(ref).log_odds;
}

template <int Depth>
Occupancy OccupancyOctree<Depth>::occupancyOf(const KeyType& key) const {
  const auto value = search(key);
  return value ? model_.classify(*value) : Occupancy::kUnknown;
}

template <int Depth>
template <class Visitor>
void OccupancyOctree<Depth>::forEachLeaf(Visitor&& visit) const {
  using Index = typename KeyType::Index;
  const auto all = static_cast<Index>(~Index{0});  // the box spans every key of the map
  forEachLeafInBox(KeyType{}, KeyType{{all, all, all}}, visit);
}

template <int Depth>
template <class Visitor>
void OccupancyOctree<Depth>::forEachLeafInBox(const KeyType& min_key, const KeyType& max_key, Visitor&& visit) const {
  for (int axis = 0; axis < 3; ++axis) {
    if (min_key[axis] > max_key[axis]) return;
  }
  if (!empty()) visitLeavesInBox(kRootRef, KeyType{}, 0, min_key, max_key, visit);
}

template <int Depth>
template <class Visitor>
void OccupancyOctree<Depth>::visitLeavesInBox(NodeRef ref, const KeyType& key, int depth, const KeyType& lo,
                                              const KeyType& hi, Visitor& visit) const {
  // `key` is the lowest corner of a node that intersects the box.
  const OcTreeNode& node = pool_.at(ref);
  if (!node.hasChildren()) {
    visit(LeafView<Depth>{key, depth, node.log_odds});
    return;
  }
  using Index = typename KeyType::Index;
  const int bit = Depth - 1 - depth;
  const Index last = static_cast<Index>((Index{1} << bit) - 1);  // a child spans [corner, corner + last]
  NodeRef child = NodePool::firstChild(node);
  for (unsigned mask = pool_.childMask(node); mask != 0; mask &= mask - 1, ++child) {
    const auto i = static_cast<unsigned>(std::countr_zero(mask));
    KeyType child_key = key;
    bool inside = true;
    for (int axis = 0; axis < 3; ++axis) {
      if ((i >> axis) & 1U) child_key[axis] = static_cast<Index>(child_key[axis] | (Index{1} << bit));
      inside = inside && child_key[axis] <= hi[axis] && static_cast<Index>(child_key[axis] + last) >= lo[axis];
    }
    if (inside) visitLeavesInBox(child, child_key, depth + 1, lo, hi, visit);
  }
}

template <int Depth>
NodeCounts OccupancyOctree<Depth>::counts() const {
  NodeCounts result;
  if (empty()) return result;
  result.nodes = 1;
  if (pool_.at(kRootRef).hasChildren()) {
    countSubtree(kRootRef, result);
  } else {
    result.leaves = 1;
  }
  return result;
}

template <int Depth>
void OccupancyOctree<Depth>::countSubtree(NodeRef ref, NodeCounts& counts) const {
  // `ref` has children: counted here, and their leaves without a call each (most nodes are leaves).
  ++counts.inner;
  const OcTreeNode& node = pool_.at(ref);
  const NodeRef first = NodePool::firstChild(node);
  const unsigned count = pool_.childCount(node);
  counts.nodes += count;
  for (NodeRef child = first; child < first + count; ++child) {
    if (pool_.at(child).hasChildren()) {
      countSubtree(child, counts);
    } else {
      ++counts.leaves;
    }
  }
}

}  // namespace sonarmap
