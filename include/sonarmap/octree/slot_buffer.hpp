#pragma once
/// @file slot_buffer.hpp
/// The array of octree node slots (NodePool's storage): a growable array of trivially copyable
/// 8-byte nodes whose growth does not copy them. A std::vector grows by allocating a new block and
/// copying, so while a tree of N bytes grows to 2N both blocks are resident: the peak of a large
/// insertion was twice its tree. Here a block of 1 MiB or more is anonymous memory (POSIX mmap)
/// and grows with Linux's mremap, which moves the block's pages to the larger range without
/// copying them (mremap(2)); smaller blocks live on the heap (realloc). Capacity that has not been
/// written is address space, not resident memory.

#include <cstddef>

#include "sonarmap/octree/octree_node.hpp"

namespace sonarmap {

/// Contiguous slots of OcTreeNode; indices and pointers are invalidated by growth.
class SlotBuffer {
 public:
  SlotBuffer() = default;
  SlotBuffer(const SlotBuffer& other);
  SlotBuffer(SlotBuffer&& other) noexcept;
  SlotBuffer& operator=(SlotBuffer other) noexcept;
  ~SlotBuffer();

  void swap(SlotBuffer& other) noexcept;

  OcTreeNode& operator[](std::size_t i) { return data_[i]; }
  const OcTreeNode& operator[](std::size_t i) const { return data_[i]; }
  OcTreeNode* begin() { return data_; }
  const OcTreeNode* begin() const { return data_; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }

  /// Makes the capacity at least `slots` (never shrinks). @throws std::bad_alloc.
  void reserve(std::size_t slots);
  /// Grows or shrinks to `slots`; new slots are `OcTreeNode{}` (unknown, no children). Grows the
  /// capacity to at least twice the old one when it must grow. @throws std::bad_alloc.
  void resize(std::size_t slots);
  /// `slots` copies of `value`, keeping the capacity.
  void assign(std::size_t slots, const OcTreeNode& value);
  /// Frees every slot and the block.
  void release() noexcept;

 private:
  static constexpr std::size_t kMappedBytes = std::size_t{1} << 20;  ///< blocks from here on are mapped
  OcTreeNode* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

}  // namespace sonarmap
