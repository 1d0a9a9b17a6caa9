#pragma once
/// @file occupancy_octree_impl.hpp
/// Member definitions of OccupancyOctree (included by occupancy_octree.hpp).

#include <algorithm>
#include <array>

namespace sonarmap {

template <int Depth>
bool OccupancyOctree<Depth>::updateNode(const KeyType& key, float delta_log_odds) {
  if (delta_log_odds == 0.0F) return false;
  std::array<NodeRef, Depth + 1> path;
  path[0] = kRootRef;
  int level = 0;
  int fresh_from = Depth + 1;  // first level created by this update
  NodeRef ref = kRootRef;
  if (!pool_.at(kRootRef).exists()) {
    pool_.at(kRootRef).log_odds = 0.0F;
    fresh_from = 0;
  } else {
    // Descend through existing nodes to the deepest one containing the key.
    while (level < Depth && pool_.at(ref).hasChildren()) {
      const NodeRef child = NodePool::childRef(pool_.at(ref).children, childIndex(key, level));
      if (!pool_.at(child).exists()) break;
      ref = child;
      path[++level] = ref;
    }
    const OcTreeNode& deepest = pool_.at(ref);
    const bool is_leaf = level == Depth || !deepest.hasChildren();
    if (options_.stability_check && is_leaf && model_.isStable(deepest.log_odds, delta_log_odds)) return false;
  }
  // Create (or expand a pruned leaf into) the missing levels down to the finest voxel.
  while (level < Depth) {
    if (!pool_.at(ref).hasChildren()) {
      const float fill = level >= fresh_from ? kUnknownLogOdds : pool_.at(ref).log_odds;
      const std::uint32_t block = pool_.allocate(fill);
      pool_.at(ref).children = block;
    }
    ref = NodePool::childRef(pool_.at(ref).children, childIndex(key, level));
    path[++level] = ref;
    if (!pool_.at(ref).exists()) {
      pool_.at(ref).log_odds = 0.0F;
      fresh_from = std::min(fresh_from, level);
    }
  }
  OcTreeNode& leaf = pool_.at(ref);
  leaf.log_odds = model_.update(leaf.log_odds, delta_log_odds);
  if (options_.lazy) return true;
  // Eager: fix the inner nodes bottom-up; stop once nothing above can change.
  for (int l = Depth - 1; l >= 0; --l) {
    const float before = pool_.at(path[l]).log_odds;
    const bool pruned = options_.prune && tryPrune(path[l]);
    if (!pruned) {
      OcTreeNode& inner = pool_.at(path[l]);
      inner.log_odds = aggregateChildren(inner);
      if (inner.log_odds == before && l + 1 < fresh_from) break;
    }
  }
  return true;
}

template <int Depth>
float OccupancyOctree<Depth>::aggregateChildren(const OcTreeNode& parent) const {
  float max = -std::numeric_limits<float>::infinity();
  float sum = 0.0F;
  int count = 0;
  for (unsigned i = 0; i < 8; ++i) {
    const float value = pool_.at(NodePool::childRef(parent.children, i)).log_odds;
    if (std::isnan(value)) continue;
    max = std::max(max, value);
    sum += value;
    ++count;
  }
  if (count == 0) return 0.0F;
  return options_.aggregation == InnerAggregation::kMax ? max : sum / static_cast<float>(count);
}

template <int Depth>
bool OccupancyOctree<Depth>::tryPrune(NodeRef ref) {
  const std::uint32_t block = pool_.at(ref).children;
  const OcTreeNode& first = pool_.at(NodePool::childRef(block, 0));
  if (!first.exists() || first.hasChildren()) return false;
  for (unsigned i = 1; i < 8; ++i) {
    const OcTreeNode& child = pool_.at(NodePool::childRef(block, i));
    if (child.hasChildren() || !(child.log_odds == first.log_odds)) return false;  // NaN never equal
  }
  OcTreeNode& node = pool_.at(ref);
  node.log_odds = first.log_odds;
  node.children = 0;
  pool_.release(block);
  return true;
}

template <int Depth>
void OccupancyOctree<Depth>::updateInnerOccupancy() {
  if (!empty()) syncSubtree(kRootRef);
}

template <int Depth>
void OccupancyOctree<Depth>::syncSubtree(NodeRef ref) {
  const std::uint32_t block = pool_.at(ref).children;
  if (block == 0) return;
  for (unsigned i = 0; i < 8; ++i) {
    const NodeRef child = NodePool::childRef(block, i);
    if (pool_.at(child).hasChildren()) syncSubtree(child);
  }
  if (options_.prune && tryPrune(ref)) return;
  pool_.at(ref).log_odds = aggregateChildren(pool_.at(ref));
}

template <int Depth>
void OccupancyOctree<Depth>::createChildren(NodeRef ref) {
  if (pool_.at(ref).hasChildren()) return;
  const std::uint32_t block = pool_.allocate(kUnknownLogOdds);
  pool_.at(ref).children = block;
}

template <int Depth>
std::optional<float> OccupancyOctree<Depth>::search(const KeyType& key, int depth) const {
  NodeRef ref = kRootRef;
  if (!pool_.at(ref).exists()) return std::nullopt;
  const int target = std::clamp(depth, 0, Depth);
  for (int level = 0; level < target && pool_.at(ref).hasChildren(); ++level) {
    ref = NodePool::childRef(pool_.at(ref).children, childIndex(key, level));
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
  if (!empty()) visitLeaves(kRootRef, KeyType{}, 0, visit);
}

template <int Depth>
template <class Visitor>
void OccupancyOctree<Depth>::visitLeaves(NodeRef ref, const KeyType& key, int depth, Visitor& visit) const {
  const OcTreeNode& node = pool_.at(ref);
  if (!node.hasChildren()) {
    visit(LeafView<Depth>{key, depth, node.log_odds});
    return;
  }
  using Index = typename KeyType::Index;
  const int bit = Depth - 1 - depth;
  for (unsigned i = 0; i < 8; ++i) {
    const NodeRef child = NodePool::childRef(node.children, i);
    if (!pool_.at(child).exists()) continue;
    KeyType child_key = key;
    for (int axis = 0; axis < 3; ++axis) {
      if ((i >> axis) & 1U) child_key[axis] = static_cast<Index>(child_key[axis] | (Index{1} << bit));
    }
    visitLeaves(child, child_key, depth + 1, visit);
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
    const NodeRef child = NodePool::childRef(node.children, i);
    if (pool_.at(child).exists()) countSubtree(child, counts);
  }
}

}  // namespace sonarmap
