#pragma once
// A set of keys inside a box of keys, each kept once: one bit per voxel of the box when the box
// is small enough (a scan's cells are marked with a shift and an OR, no hashing), a hash set
// otherwise (a far-reaching or tilted scan). Internal to the library: the generalisation of the
// mapper's SweepCells (any depth, erase, merge of per-thread sets, ordered visits).
//
// The bitmap is made of bricks of 4 × 4 × 4 voxels aligned to multiples of 4 (a node at depth
// Depth − 2), one 64-bit word each. A word stores its voxels x fastest (bit x + 4y + 16z, cheap
// to compute per marked key); visits convert it to the octree's child order (Morton order: x, y,
// z bits interleaved) with a table, once per word. Bricks are stored x fastest, then y, then z,
// and are visited in that order, each as one Morton-ordered word (OccupancyOctree::updateBrick
// applies it with one descent). The hash set visits its keys as the same bricks in the same
// order, so a dense and a sparse set of the same keys drive identical updates.

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <vector>

#include <absl/container/flat_hash_set.h>

#include "sonarmap/core/key.hpp"

namespace sonarmap {

template <int Depth>
class KeyMarks {
 public:
  using KeyType = Key<Depth>;
  using Index = typename KeyType::Index;

  /// Largest box kept as a bitmap by default: 2^27 voxels, 16 MiB.
  static constexpr std::size_t kMaxDenseVoxels = std::size_t{1} << 27;

  /// Empties the set for keys within [lo, hi] (inclusive; lo ≤ hi on every axis). A bitmap when
  /// the box, grown to whole bricks, holds at most `max_dense_voxels` voxels; a hash set otherwise.
  void reset(const KeyType& lo, const KeyType& hi, std::size_t max_dense_voxels = kMaxDenseVoxels) {
    sparse_.clear();
    bits_.clear();
    dense_ = true;
    const std::size_t max_bricks = max_dense_voxels / 64;
    std::size_t bricks = 1;
    for (int axis = 0; axis < 3; ++axis) {
      lo_[axis] = static_cast<Index>(lo[axis] & ~Index{3});
      const Index span = static_cast<Index>((hi[axis] - lo_[axis]) >> 2);  // bricks − 1
      if (span >= max_bricks || bricks > max_bricks / (static_cast<std::size_t>(span) + 1)) {
        dense_ = false;
        return;
      }
      bricks_[axis] = static_cast<std::size_t>(span) + 1;
      bricks *= bricks_[axis];
    }
    stride_y_ = bricks_[0];
    stride_z_ = bricks_[0] * bricks_[1];
    bits_.assign(bricks, 0);
  }

  bool dense() const { return dense_; }

  /// Bytes the set holds: the bitmap's words, or the hash set's slots (a key and a control byte
  /// each, Abseil's layout).
  std::size_t memoryBytes() const {
    return dense_ ? bits_.size() * sizeof(std::uint64_t) : sparse_.capacity() * (sizeof(KeyType) + 1);
  }

  /// Calls `body(mark)` where `mark(key)` adds a key of the box, the concrete set's insert, so a
  /// traversal loop is compiled once per kind instead of branching per key. `mark(key,
  /// SteppedAxis<A>{})` (A = 0, 1, 2) adds a key that differs from the key marked just before
  /// along axis A only, by one (a DDA step, see traverseDDASteps): cheaper, as only that axis'
  /// part of the brick and bit position changes.
  template <class Body>
  void marking(Body&& body) {
    if (!dense_) {
      body([this](const KeyType& key, auto...) { sparse_.insert(key); });
      return;
    }
    // Consecutive keys of a ray mostly share a brick: gather their bits in a register and store
    // them when the brick changes, instead of a load-or-store chain per key.
    std::size_t current = 0;  // word of the brick at lo_
    KeyType current_key = lo_;
    std::uint64_t pending = 0;
    unsigned row = 0;  // bit of the last key in its brick's word
    const std::size_t strides[3] = {1, stride_y_, stride_z_};
    std::uint64_t* const bits = bits_.data();  // a local: not reloaded from the vector after each store
    body([&](const KeyType& key, auto... stepped) {
      if constexpr (sizeof...(stepped) == 1 && (decltype(stepped)::value + ... + 0) >= 0) {
        constexpr int kAxis = (decltype(stepped)::value + ...);
        constexpr unsigned kShift = 2 * kAxis;
        const unsigned low = key[kAxis] & 3U;
        row = (row & ~(3U << kShift)) | (low << kShift);
        if (((key[kAxis] ^ current_key[kAxis]) >> 2) != 0) {  // the next brick along this axis
          bits[current] |= pending;
          pending = 0;
          current = low == 0 ? current + strides[kAxis] : current - strides[kAxis];
          current_key[kAxis] = key[kAxis];
        }
      } else {
        const auto differ = (key[0] ^ current_key[0]) | (key[1] ^ current_key[1]) | (key[2] ^ current_key[2]);
        if ((differ >> 2) != 0) {  // another brick
          bits[current] |= pending;
          current = word(key);
          current_key = key;
          pending = 0;
        }
        row = rowIndex(key);
      }
      pending |= std::uint64_t{1} << row;
    });
    if (pending != 0) bits[current] |= pending;  // nothing marked: the box may even be empty
  }

  void insert(const KeyType& key) {
    if (dense_) {
      bits_[word(key)] |= rowBit(key);
    } else {
      sparse_.insert(key);
    }
  }

  void erase(const KeyType& key) {
    if (dense_) {
      bits_[word(key)] &= ~rowBit(key);
    } else {
      sparse_.erase(key);
    }
  }

  /// Whether `key` is in the set (false for a key outside the box).
  bool contains(const KeyType& key) const {
    if (!dense_) return sparse_.contains(key);
    for (int axis = 0; axis < 3; ++axis) {
      if (key[axis] < lo_[axis] || static_cast<std::size_t>((key[axis] - lo_[axis]) >> 2) >= bricks_[axis]) return false;
    }
    return (bits_[word(key)] & rowBit(key)) != 0;
  }

  /// Removes every key of `other`, reset with the same box and limit (so of the same kind), and
  /// returns the number of keys left (counted on the way: no extra pass).
  std::size_t subtract(const KeyMarks& other) {
    if (!dense_) {
      for (const KeyType& key : other.sparse_) sparse_.erase(key);
      return sparse_.size();
    }
    std::size_t left = 0;
    for (std::size_t w = 0; w < bits_.size(); ++w) {
      bits_[w] &= ~other.bits_[w];
      if (bits_[w] != 0) left += static_cast<std::size_t>(std::popcount(bits_[w]));
    }
    return left;
  }

  /// Adds every key of `other`, reset with the same box and limit (so of the same kind).
  void merge(const KeyMarks& other) {
    if (dense_) {
      for (std::size_t w = 0; w < bits_.size(); ++w) bits_[w] |= other.bits_[w];
    } else {
      sparse_.insert(other.sparse_.begin(), other.sparse_.end());
    }
  }

  /// Calls `visit(corner, bits)` once per brick holding keys, brick by brick (x fastest, then y,
  /// then z): `corner` is the brick's lowest key, bit b of `bits` its key at Morton index b
  /// (bitIndex).
  template <class Visitor>
  void forEachBrick(Visitor&& visit) {
    if (dense_) {
      forEachWord([&](std::uint64_t bits, const KeyType& corner) { visit(corner, bits); });
      return;
    }
    ordered_.assign(sparse_.begin(), sparse_.end());
    std::sort(ordered_.begin(), ordered_.end(), visitLess);
    for (std::size_t i = 0; i < ordered_.size();) {
      const KeyType corner = brickCorner(ordered_[i]);
      std::uint64_t bits = 0;
      for (; i < ordered_.size() && brickCorner(ordered_[i]) == corner; ++i) bits |= bit(ordered_[i]);
      visit(corner, bits);
    }
  }

  /// Orders keys as forEachBrick visits them: by brick z, y, x, then Morton order in the brick.
  static bool visitLess(const KeyType& a, const KeyType& b) {
    const auto brick = [](const KeyType& k) { return std::tuple(k[2] >> 2, k[1] >> 2, k[0] >> 2); };
    if (brick(a) != brick(b)) return brick(a) < brick(b);
    return bitIndex(a) < bitIndex(b);
  }

 private:
  /// Position of a key in its brick's word: x, y, z bits of the key's low two bits interleaved.
  static unsigned bitIndex(const KeyType& key) {
    // Low two bits of a coordinate, 3 bits apart: 0b ab → 0b a00b. Arithmetic, not a table (a
    // local table is rebuilt on the stack per call and stalls the load that follows).
    const auto spread = [](auto c) { return static_cast<unsigned>((c & 1U) | ((c & 2U) << 2)); };
    return spread(key[0]) | (spread(key[1]) << 1) | (spread(key[2]) << 2);
  }
  static std::uint64_t bit(const KeyType& key) { return std::uint64_t{1} << bitIndex(key); }
  /// The key's bit in a stored word: x fastest, then y, then z.
  static std::uint64_t rowBit(const KeyType& key) { return std::uint64_t{1} << rowIndex(key); }
  static unsigned rowIndex(const KeyType& key) {
    return static_cast<unsigned>((key[0] & 3U) | ((key[1] & 3U) << 2) | ((key[2] & 3U) << 4));
  }
  /// kRowToMorton[j][v]: the Morton-order bits of byte j = v of a stored word.
  static constexpr auto kRowToMorton = [] {
    std::array<std::array<std::uint64_t, 256>, 8> table{};
    for (unsigned j = 0; j < 8; ++j)
      for (unsigned v = 0; v < 256; ++v)
        for (unsigned k = 0; k < 8; ++k) {
          if (((v >> k) & 1U) == 0) continue;
          const unsigned p = 8 * j + k, x = p & 3U, y = (p >> 2) & 3U, z = p >> 4;
          const unsigned m = (x & 1U) | ((y & 1U) << 1) | ((z & 1U) << 2) | ((x & 2U) << 2) | ((y & 2U) << 3) | ((z & 2U) << 4);
          table[j][v] |= std::uint64_t{1} << m;
        }
    return table;
  }();
  static std::uint64_t toMorton(std::uint64_t row_bits) {
    std::uint64_t morton = 0;
    for (unsigned j = 0; j < 8; ++j) morton |= kRowToMorton[j][(row_bits >> (8 * j)) & 0xFFU];
    return morton;
  }
  static KeyType brickCorner(const KeyType& key) {
    return KeyType{{static_cast<Index>(key[0] & ~Index{3}), static_cast<Index>(key[1] & ~Index{3}),
                    static_cast<Index>(key[2] & ~Index{3})}};
  }

  std::size_t word(const KeyType& key) const {
    const auto brick = [&](int axis) { return static_cast<std::size_t>((key[axis] - lo_[axis]) >> 2); };
    return brick(0) + stride_y_ * brick(1) + stride_z_ * brick(2);
  }

  /// The key at bit `b` of the brick whose lowest key is `corner`.
  static KeyType keyAt(const KeyType& corner, unsigned b) {
    KeyType key;
    key[0] = static_cast<Index>(corner[0] + ((b & 1U) | ((b >> 2) & 2U)));
    key[1] = static_cast<Index>(corner[1] + (((b >> 1) & 1U) | ((b >> 3) & 2U)));
    key[2] = static_cast<Index>(corner[2] + (((b >> 2) & 1U) | ((b >> 4) & 2U)));
    return key;
  }

  /// Calls `body(bits, corner)` for every non-empty brick word, in storage order.
  template <class Body>
  void forEachWord(Body&& body) const {
    // Running brick coordinates: no division per word.
    std::size_t bx = 0, by = 0, bz = 0;
    for (std::size_t w = 0; w < bits_.size(); ++w) {
      if (bits_[w] != 0) {
        const KeyType corner{{static_cast<Index>(lo_[0] + 4 * bx), static_cast<Index>(lo_[1] + 4 * by),
                              static_cast<Index>(lo_[2] + 4 * bz)}};
        body(toMorton(bits_[w]), corner);
      }
      if (++bx == bricks_[0]) {
        bx = 0;
        if (++by == bricks_[1]) by = 0, ++bz;
      }
    }
  }

  bool dense_ = true;
  KeyType lo_{};                           ///< lowest corner of the bricks (multiples of 4)
  std::size_t bricks_[3] = {0, 0, 0};      ///< bricks per axis
  std::size_t stride_y_ = 0, stride_z_ = 0;  ///< words between bricks one apart along y, z
  std::vector<std::uint64_t> bits_;
  absl::flat_hash_set<KeyType, KeyHash<Depth>> sparse_;
  std::vector<KeyType> ordered_;
};

}  // namespace sonarmap
