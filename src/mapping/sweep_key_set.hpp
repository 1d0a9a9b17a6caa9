#pragma once
// Deduplication of one sweep's cells: a bitmap over the sweep's box of keys when that box is
// small enough, a hash set otherwise (a tilted or far-ranging sweep). Internal to the mapper.

#include <absl/container/flat_hash_set.h>

#include "sonarmap/core/dense_key_set.hpp"

namespace sonarmap {

class SweepKeySet {
 public:
  /// Largest box kept as a bitmap: 2^26 voxels, 8 MiB.
  static constexpr std::size_t kMaxDenseVoxels = std::size_t{1} << 26;

  /// Empties the set for keys within [lo, hi].
  void reset(const Key16& lo, const Key16& hi) {
    sparse_.clear();
    dense_.reset(lo, hi, kMaxDenseVoxels);
  }
  /// @return true when `key` was not in the set before.
  bool insert(const Key16& key) { return dense_.usable() ? dense_.insert(key) : sparse_.insert(key).second; }

  /// Calls `body(set)` with the concrete set, both offering `insert(key) -> bool`, so hot loops
  /// are compiled once per kind instead of branching per key.
  template <class Body>
  void withSet(Body&& body) {
    if (dense_.usable()) {
      body(dense_);
    } else {
      body(sparse_);
    }
  }

 private:
  DenseKeySet<16> dense_;
  absl::flat_hash_set<Key16, KeyHash<16>> sparse_;
};

/// Uniform insert for the sets SweepKeySet::withSet hands out.
inline bool insertKey(DenseKeySet<16>& set, const Key16& key) { return set.insert(key); }
inline bool insertKey(absl::flat_hash_set<Key16, KeyHash<16>>& set, const Key16& key) { return set.insert(key).second; }

}  // namespace sonarmap
