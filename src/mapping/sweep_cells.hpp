#pragma once
// The cells of one sweep: those its free rays cross and its hit cells, each kept once. A bitmap
// over the sweep's box of keys when the box is small enough, hash sets otherwise (a tilted or
// far-ranging sweep). Internal to the mapper.

#include <algorithm>
#include <vector>

#include <absl/container/flat_hash_set.h>

#include "sonarmap/core/dense_key_set.hpp"

namespace sonarmap {

class SweepCells {
 public:
  /// Largest box kept as a bitmap: 2^26 voxels, 8 MiB per set.
  static constexpr std::size_t kMaxDenseVoxels = std::size_t{1} << 26;

  /// Empties the sets for keys within [lo, hi].
  void reset(const Key16& lo, const Key16& hi) {
    crossed_sparse_.clear();
    hit_sparse_.clear();
    dense_ = crossed_dense_.reset(lo, hi, kMaxDenseVoxels) && hit_dense_.reset(lo, hi, kMaxDenseVoxels);
  }

  void addHit(const Key16& key) {
    if (dense_) {
      hit_dense_.insert(key);
    } else {
      hit_sparse_.insert(key);
    }
  }

  /// Calls `body(mark)` where `mark(key)` records a crossed cell, the concrete set's insert, so the
  /// traversal loop is compiled once per kind instead of branching per key.
  template <class Body>
  void marking(Body&& body) {
    if (dense_) {
      body([this](const Key16& key) { crossed_dense_.insert(key); });
    } else {
      body([this](const Key16& key) { crossed_sparse_.insert(key); });
    }
  }

  /// Calls `visit(key)` once for every crossed cell that is not a hit cell, x fastest, then y,
  /// then z, so that consecutive cells are neighbours in the octree.
  template <class Visitor>
  void forEachFree(Visitor&& visit) {
    if (dense_) {
      crossed_dense_.forEach([&](const Key16& key) {
        if (!hit_dense_.contains(key)) visit(key);
      });
      return;
    }
    ordered_.assign(crossed_sparse_.begin(), crossed_sparse_.end());
    std::sort(ordered_.begin(), ordered_.end(), [](const Key16& a, const Key16& b) {
      return std::tie(a[2], a[1], a[0]) < std::tie(b[2], b[1], b[0]);
    });
    for (const Key16& key : ordered_) {
      if (!hit_sparse_.contains(key)) visit(key);
    }
  }

 private:
  bool dense_ = false;
  DenseKeySet<16> crossed_dense_, hit_dense_;
  absl::flat_hash_set<Key16, KeyHash<16>> crossed_sparse_, hit_sparse_;
  std::vector<Key16> ordered_;
};

}  // namespace sonarmap
