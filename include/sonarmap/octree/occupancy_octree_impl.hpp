#pragma once
/// @file occupancy_octree_impl.hpp
/// Member definitions of OccupancyOctree (included by occupancy_octree.hpp).

#include <algorithm>
#include <array>
#include <bit>

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
bool OccupancyOctree<Depth>::updateNode(const KeyType& key, float delta_log_odds, bool lazy_eval) {
  if (delta_log_odds == 0.0F) return false;
  auto& path = path_;
  int fresh_from = Depth + 1;  // first level created by this update
  int level = 0;
  if (!pool_.at(kRootRef).exists()) {
    pool_.at(kRootRef).log_odds = 0.0F;
    path[0] = kRootRef;
    fresh_from = 0;
  } else {
    // Start from the deepest node shared with the previous update's path, then descend through
    // existing nodes to the deepest one containing the key.
    level = cachedLevels(key);
    path[0] = kRootRef;
    while (level < Depth && pool_.at(path[level]).hasChildren()) {
      const NodeRef child = NodePool::childRef(pool_.at(path[level]).block(), childIndex(key, level));
      if (!pool_.at(child).exists()) break;
      path[++level] = child;
    }
    cached_key_ = key;
    cached_levels_ = level;
    const OcTreeNode& deepest = pool_.at(path[level]);
    const bool is_leaf = level == Depth || !deepest.hasChildren();
    if (options_.stability_check && is_leaf && model_.isStable(deepest.log_odds, delta_log_odds)) return false;
  }
  // Create (or expand a pruned leaf into) the missing levels down to the finest voxel.
  for (; level < Depth; ++level) {
    const NodeRef ref = path[level];
    if (!pool_.at(ref).hasChildren()) {
      const float fill = level >= fresh_from ? kUnknownLogOdds : pool_.at(ref).log_odds;
      const std::uint32_t block = pool_.allocate(fill);
      pool_.at(ref).link = block;
    }
    const NodeRef child = NodePool::childRef(pool_.at(ref).block(), childIndex(key, level));
    path[level + 1] = child;
    if (!pool_.at(child).exists()) {
      pool_.at(child).log_odds = 0.0F;
      fresh_from = std::min(fresh_from, level + 1);
    }
  }
  cached_key_ = key;
  cached_levels_ = Depth;
  OcTreeNode& leaf = pool_.at(path[Depth]);
  const float before = leaf.log_odds;
  leaf.log_odds = model_.update(before, delta_log_odds);
  if (detect_changes_) [[unlikely]] {
    recordChange(changes_, model_, key, fresh_from <= Depth, before, leaf.log_odds);
  }
  if (options_.lazy || lazy_eval) {
    markPathDirty();
  } else {
    updateAncestors(fresh_from);
  }
  return true;
}

template <int Depth>
void OccupancyOctree<Depth>::markPathDirty() {
  // Ancestors of a dirty node are dirty: stop at the first one already marked.
  for (int l = Depth - 1; l >= 0; --l) {
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
typename OccupancyOctree<Depth>::ChildSummary OccupancyOctree<Depth>::summarize(std::uint32_t block) const {
  const OcTreeNode* children = &pool_.at(NodePool::childRef(block, 0));
  float max = -std::numeric_limits<float>::infinity();
  float sum = 0.0F;
  int count = 0;
  bool leaves_equal = true;
  for (unsigned i = 0; i < 8; ++i) {
    const OcTreeNode& child = children[i];
    leaves_equal = leaves_equal && !child.hasChildren() && child.log_odds == children[0].log_odds;  // NaN never equal
    if (!child.exists()) continue;
    max = std::max(max, child.log_odds);
    sum += child.log_odds;
    ++count;
  }
  if (count == 0) return {0.0F, false};
  const float aggregate = options_.aggregation == InnerAggregation::kMax ? max : sum / static_cast<float>(count);
  return {aggregate, leaves_equal};
}

template <int Depth>
float OccupancyOctree<Depth>::aggregateChildren(const OcTreeNode& parent) const {
  return summarize(parent.block()).aggregate;
}

template <int Depth>
bool OccupancyOctree<Depth>::refreshInner(NodeRef ref, bool keep_dirty) {
  const std::uint32_t block = pool_.at(ref).block();
  const ChildSummary summary = summarize(block);
  OcTreeNode& node = pool_.at(ref);
  node.log_odds = summary.aggregate;
  if (!(options_.prune && summary.prunable)) {
    node.link = keep_dirty ? (node.link | block) : block;  // clean unless kept dirty
    return false;
  }
  node.link = 0;  // all 8 equal leaves: the node becomes the leaf
  pool_.release(block);
  return true;
}

template <int Depth>
void OccupancyOctree<Depth>::updateInnerOccupancy() {
  cached_levels_ = -1;  // pruning may free nodes on the cached path
  const bool all = !options_.lazy;
  const OcTreeNode& root = pool_.at(kRootRef);
  if (root.hasChildren() && (root.dirty() || all)) syncSubtree(kRootRef, all);
}

template <int Depth>
void OccupancyOctree<Depth>::updateDirtyInnerOccupancy() {
  cached_levels_ = -1;
  const OcTreeNode& root = pool_.at(kRootRef);
  if (root.hasChildren() && root.dirty()) syncSubtree(kRootRef, false);
}

template <int Depth>
void OccupancyOctree<Depth>::syncSubtree(NodeRef ref, bool all) {
  // Post-order over the subtrees that changed since the last synchronisation (dirty nodes);
  // a clean subtree is already consistent. `all` visits every inner node (eager trees).
  const std::uint32_t block = pool_.at(ref).block();
  if (block == 0) return;
  for (unsigned i = 0; i < 8; ++i) {
    const OcTreeNode& child = pool_.at(NodePool::childRef(block, i));
    if (child.hasChildren() && (child.dirty() || all)) syncSubtree(NodePool::childRef(block, i), all);
  }
  refreshInner(ref);
}

template <int Depth>
void OccupancyOctree<Depth>::createChildren(NodeRef ref) {
  cached_levels_ = -1;
  if (pool_.at(ref).hasChildren()) return;
  const std::uint32_t block = pool_.allocate(kUnknownLogOdds);
  pool_.at(ref).link = block;
}

template <int Depth>
std::optional<float> OccupancyOctree<Depth>::search(const KeyType& key, int depth) const {
  NodeRef ref = kRootRef;
  if (!pool_.at(ref).exists()) return std::nullopt;
  const int target = std::clamp(depth, 0, Depth);
  for (int level = 0; level < target && pool_.at(ref).hasChildren(); ++level) {
    ref = NodePool::childRef(pool_.at(ref).block(), childIndex(key, level));
    if (!pool_.at(ref).exists()) return std::nullopt;
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
  for (unsigned i = 0; i < 8; ++i) {
    const NodeRef child = NodePool::childRef(node.block(), i);
    if (!pool_.at(child).exists()) continue;
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
  if (!empty()) countSubtree(kRootRef, result);
  return result;
}

template <int Depth>
void OccupancyOctree<Depth>::countSubtree(NodeRef ref, NodeCounts& counts) const {
  ++counts.nodes;
  const OcTreeNode& node = pool_.at(ref);
  if (!node.hasChildren()) {
    ++counts.leaves;
    return;
  }
  ++counts.inner;
  for (unsigned i = 0; i < 8; ++i) {
    const NodeRef child = NodePool::childRef(node.block(), i);
    if (pool_.at(child).exists()) countSubtree(child, counts);
  }
}

}  // namespace sonarmap
