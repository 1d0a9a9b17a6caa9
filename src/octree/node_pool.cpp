// Compact children arrays: allocation by capacity class, growth, release and compaction.
#include "sonarmap/octree/node_pool.hpp"

#include <algorithm>
#include <utility>

namespace sonarmap {

void NodePool::clear() {
  slots_.assign(2, OcTreeNode{});  // the root (not existing yet) and the "no node" slot
  for (auto& list : free_) list.clear();
  used_slots_ = 2;
}

void NodePool::reserve(std::size_t slots) {
  const std::size_t needed = std::min<std::size_t>(slots_.size() + slots, kMaxSlots);
  if (needed > slots_.capacity()) slots_.reserve(std::max(needed, 2 * slots_.capacity()));
}

std::uint32_t NodePool::allocate(unsigned cls) {
  const std::size_t size = kCapacity[cls] + 1;
  used_slots_ += size;
  if (!free_[cls].empty()) {
    const std::uint32_t array = free_[cls].back();
    free_[cls].pop_back();
    return array;
  }
  if (slots_.size() + size > kMaxSlots) throw ValueError("octree exceeds 2^31 node slots (16 GiB)");
  const auto array = static_cast<std::uint32_t>(slots_.size());
  slots_.resize(slots_.size() + size);
  return array;
}

void NodePool::release(std::uint32_t array) {
  const unsigned cls = classOf(array);
  used_slots_ -= kCapacity[cls] + 1;
  free_[cls].push_back(array);
}

void NodePool::createChildren(NodeRef parent, unsigned mask, float log_odds) {
  const unsigned count = kBitCount[mask & 0xFFU];
  const unsigned cls = classFor(count);
  const std::uint32_t array = allocate(cls);
  setHeader(array, mask & 0xFFU, cls);
  std::fill_n(slots_.begin() + array + 1, count, OcTreeNode{log_odds, 0});
  slots_[parent].link = (slots_[parent].link & OcTreeNode::kDirtyBit) | array;
}

NodeRef NodePool::addChild(NodeRef parent, unsigned index, float log_odds) {
  if (!slots_[parent].hasChildren()) {
    createChildren(parent, 1U << index, log_odds);
    return slots_[parent].array() + 1;
  }
  const std::uint32_t array = slots_[parent].array();
  const unsigned mask = maskOf(array);
  const unsigned count = kBitCount[mask];
  const unsigned rank = kBitCount[mask & ((1U << index) - 1U)];
  const unsigned grown = mask | (1U << index);
  const auto first = slots_.begin() + array + 1;
  if (count < kCapacity[classOf(array)]) {  // room left: shift the later children up by one
    std::copy_backward(first + rank, first + count, first + count + 1);
    first[rank] = OcTreeNode{log_odds, 0};
    setHeader(array, grown, classOf(array));
    return array + 1 + rank;
  }
  const unsigned cls = classOf(array) + 1;
  const std::uint32_t moved = allocate(cls);  // may reallocate slots_: iterators above are stale
  const auto from = slots_.begin() + array + 1;
  const auto to = slots_.begin() + moved + 1;
  std::copy(from, from + rank, to);
  to[rank] = OcTreeNode{log_odds, 0};
  std::copy(from + rank, from + count, to + rank + 1);
  release(array);
  setHeader(moved, grown, cls);
  slots_[parent].link = (slots_[parent].link & OcTreeNode::kDirtyBit) | moved;
  return moved + 1 + rank;
}

void NodePool::releaseChildren(NodeRef parent) {
  release(slots_[parent].array());
  slots_[parent].link = 0;
}

std::size_t NodePool::bytesAllocated() const {
  std::size_t bytes = slots_.capacity() * sizeof(OcTreeNode);
  for (const auto& list : free_) bytes += list.capacity() * sizeof(std::uint32_t);
  return bytes;
}

void NodePool::compact() {
  SlotBuffer old;
  old.swap(slots_);
  slots_.reserve(used_slots_);
  slots_.assign(2, OcTreeNode{});
  for (auto& list : free_) std::vector<std::uint32_t>().swap(list);
  copySubtree(old, kRootRef, kRootRef);
  used_slots_ = slots_.size();
}

void NodePool::copySubtree(const SlotBuffer& old, NodeRef from, NodeRef to) {
  const OcTreeNode node = old[from];
  if (!node.hasChildren()) {
    slots_[to] = node;
    return;
  }
  const unsigned mask = old[node.array()].link & 0xFFU;
  const unsigned count = kBitCount[mask];
  const unsigned cls = classFor(count);
  const auto array = static_cast<std::uint32_t>(slots_.size());
  slots_.resize(slots_.size() + kCapacity[cls] + 1);
  setHeader(array, mask, cls);
  slots_[to] = OcTreeNode{node.log_odds, (node.link & OcTreeNode::kDirtyBit) | array};
  for (unsigned k = 0; k < count; ++k) copySubtree(old, node.array() + 1 + k, array + 1 + k);
}

}  // namespace sonarmap
