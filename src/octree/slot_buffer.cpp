// Node slots that grow without copying: mmap + mremap for large blocks, realloc for small ones.
#include "sonarmap/octree/slot_buffer.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>

#include <sys/mman.h>

namespace sonarmap {
namespace {

static_assert(std::is_trivially_copyable_v<OcTreeNode>, "slots are moved as bytes");

bool mapped(std::size_t capacity) { return capacity * sizeof(OcTreeNode) >= (std::size_t{1} << 20); }

/// Bytes of a block of `slots`: whole pages when mapped.
std::size_t blockBytes(std::size_t slots) {
  const std::size_t bytes = slots * sizeof(OcTreeNode);
  if (!mapped(slots)) return bytes;
  constexpr std::size_t kPage = 4096;  // a multiple of it is a multiple of any smaller page too
  return (bytes + kPage - 1) / kPage * kPage;
}

void freeBlock(OcTreeNode* data, std::size_t capacity) noexcept {
  if (data == nullptr) return;
  if (mapped(capacity)) {
    ::munmap(data, blockBytes(capacity));
  } else {
    std::free(data);
  }
}

/// A block of `capacity` slots holding the first `size` slots of `data` (of `old_capacity`),
/// which it replaces: moved page by page (mremap) when both are mapped, copied otherwise.
OcTreeNode* regrow(OcTreeNode* data, std::size_t size, std::size_t old_capacity, std::size_t capacity) {
  if (data != nullptr && mapped(old_capacity)) {
#ifdef MREMAP_MAYMOVE
    void* moved = ::mremap(data, blockBytes(old_capacity), blockBytes(capacity), MREMAP_MAYMOVE);
    if (moved == MAP_FAILED) throw std::bad_alloc();
    return static_cast<OcTreeNode*>(moved);
#endif
  }
  if (!mapped(capacity)) {  // both on the heap
    void* grown = std::realloc(data, blockBytes(capacity));
    if (grown == nullptr) throw std::bad_alloc();
    return static_cast<OcTreeNode*>(grown);
  }
  void* block = ::mmap(nullptr, blockBytes(capacity), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (block == MAP_FAILED) throw std::bad_alloc();
  if (size != 0) std::memcpy(block, data, size * sizeof(OcTreeNode));
  freeBlock(data, old_capacity);
  return static_cast<OcTreeNode*>(block);
}

}  // namespace

SlotBuffer::SlotBuffer(const SlotBuffer& other) {
  reserve(other.size_);
  if (other.size_ != 0) std::memcpy(data_, other.data_, other.size_ * sizeof(OcTreeNode));
  size_ = other.size_;
}

SlotBuffer::SlotBuffer(SlotBuffer&& other) noexcept { swap(other); }

SlotBuffer& SlotBuffer::operator=(SlotBuffer other) noexcept {
  swap(other);
  return *this;
}

SlotBuffer::~SlotBuffer() { release(); }

void SlotBuffer::swap(SlotBuffer& other) noexcept {
  std::swap(data_, other.data_);
  std::swap(size_, other.size_);
  std::swap(capacity_, other.capacity_);
}

void SlotBuffer::reserve(std::size_t slots) {
  if (slots <= capacity_) return;
  data_ = regrow(data_, size_, capacity_, slots);
  capacity_ = slots;
}

void SlotBuffer::resize(std::size_t slots) {
  if (slots > capacity_) reserve(std::max(slots, 2 * capacity_));
  if (slots > size_) std::fill(data_ + size_, data_ + slots, OcTreeNode{});
  size_ = slots;
}

void SlotBuffer::assign(std::size_t slots, const OcTreeNode& value) {
  size_ = 0;
  reserve(slots);
  std::fill_n(data_, slots, value);
  size_ = slots;
}

void SlotBuffer::release() noexcept {
  freeBlock(data_, capacity_);
  data_ = nullptr;
  size_ = capacity_ = 0;
}

}  // namespace sonarmap
