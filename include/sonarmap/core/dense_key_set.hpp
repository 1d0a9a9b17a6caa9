#pragma once
/// @file dense_key_set.hpp
/// A set of keys inside a fixed axis-aligned box of voxels, one bit per voxel: deduplicates the
/// cells of a sweep or scan far faster than a hash set when the box is small (a horizontal 5 m
/// sonar sweep at 2 cm is 500 × 500 × 1 voxels, 31 KiB).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "sonarmap/core/key.hpp"

namespace sonarmap {

template <int Depth>
class DenseKeySet {
 public:
  using KeyType = Key<Depth>;

  /// Empties the set and sets its box to [lo, hi] (inclusive, per axis).
  /// @return false, leaving the set unusable, when lo > hi on an axis or the box holds more than
  ///         `max_voxels` voxels.
  bool reset(const KeyType& lo, const KeyType& hi, std::size_t max_voxels) {
    std::size_t voxels = 1;
    for (int axis = 0; axis < 3; ++axis) {
      if (hi[axis] < lo[axis]) return usable_ = false;
      const auto extent = static_cast<std::size_t>(hi[axis] - lo[axis]) + 1;
      if (extent > max_voxels || voxels > max_voxels / extent) return usable_ = false;
      voxels *= extent;
      extent_[axis] = extent;
    }
    lo_ = lo;
    bits_.assign((voxels + 63) / 64, 0);
    return usable_ = true;
  }

  /// True when the last reset() succeeded.
  bool usable() const { return usable_; }

  /// True when `key` lies in the box.
  bool inBox(const KeyType& key) const {
    for (int axis = 0; axis < 3; ++axis) {
      if (key[axis] < lo_[axis] || static_cast<std::size_t>(key[axis] - lo_[axis]) >= extent_[axis]) return false;
    }
    return true;
  }

  /// Adds `key`, which must lie in the box. @return true when it was not in the set before.
  bool insert(const KeyType& key) {
    const std::size_t i = index(key);
    const std::uint64_t mask = std::uint64_t{1} << (i & 63U);
    const bool fresh = (bits_[i >> 6] & mask) == 0;
    bits_[i >> 6] |= mask;
    return fresh;
  }

  /// Calls `visit(const KeyType&)` for every key in the set, x fastest, then y, then z: neighbours
  /// in space follow each other, which keeps tree descents short.
  template <class Visitor>
  void forEach(Visitor&& visit) const {
    for (std::size_t word = 0; word < bits_.size(); ++word) {
      for (std::uint64_t bits = bits_[word]; bits != 0; bits &= bits - 1) {
        std::size_t i = word * 64 + static_cast<std::size_t>(std::countr_zero(bits));
        KeyType key;
        for (int axis = 0; axis < 3; ++axis) {
          key[axis] = static_cast<typename KeyType::Index>(lo_[axis] + i % extent_[axis]);
          i /= extent_[axis];
        }
        visit(std::as_const(key));
      }
    }
  }

  /// True when `key` (in the box) is in the set.
  bool contains(const KeyType& key) const {
    const std::size_t i = index(key);
    return (bits_[i >> 6] >> (i & 63U)) & 1U;
  }

 private:
  std::size_t index(const KeyType& key) const {
    return static_cast<std::size_t>(key[0] - lo_[0]) +
           extent_[0] * (static_cast<std::size_t>(key[1] - lo_[1]) + extent_[1] * static_cast<std::size_t>(key[2] - lo_[2]));
  }

  KeyType lo_{};
  std::size_t extent_[3] = {0, 0, 0};
  std::vector<std::uint64_t> bits_;
  bool usable_ = false;
};

}  // namespace sonarmap
