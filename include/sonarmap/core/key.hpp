#pragma once
/// @file key.hpp
/// Octree keys: one unsigned integer per axis, as wide as the tree is deep (paper §5.1).
///
/// A key addresses a voxel at the finest level of a tree of depth `Depth`. Each axis uses the
/// smallest unsigned integer with at least `Depth` bits: 8, 16, 32 or 64 bits, and an unsigned
/// 128-bit integer (the "wide key") for depths 65…128. Bit (Depth-1-level) of each component
/// selects the child at `level` below the root, with x in bit 0, y in bit 1 and z in bit 2 of the
/// child index — OctoMap's layout, so a depth-16 tree is interchangeable with OctoMap's.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <type_traits>

namespace sonarmap {

/// Deepest tree the library supports (keys of 128 bits per axis).
inline constexpr int kMaxDepth = 128;

/// The 128-bit "wide key" index for depths 65…128 (a GCC/Clang extension).
__extension__ typedef unsigned __int128 WideKeyIndex;

namespace detail {
template <int Depth>
struct KeyIndexFor {
  static_assert(Depth >= 1 && Depth <= kMaxDepth, "tree depth must be within 1..128");
  using type = std::conditional_t<
      (Depth <= 8), std::uint8_t,
      std::conditional_t<(Depth <= 16), std::uint16_t,
                         std::conditional_t<(Depth <= 32), std::uint32_t,
                                            std::conditional_t<(Depth <= 64), std::uint64_t,
                                                               WideKeyIndex>>>>;
};
}  // namespace detail

/// Integer type of one key component for a tree of `Depth` levels.
template <int Depth>
using KeyIndex = typename detail::KeyIndexFor<Depth>::type;

/// A voxel key: three integer indices (x, y, z) at the finest level of a tree of depth `Depth`.
template <int Depth>
struct Key {
  using Index = KeyIndex<Depth>;
  static constexpr int kDepth = Depth;

  std::array<Index, 3> k{};

  constexpr Index& operator[](std::size_t axis) { return k[axis]; }
  constexpr const Index& operator[](std::size_t axis) const { return k[axis]; }
  friend constexpr bool operator==(const Key& a, const Key& b) = default;
};

/// Index 0…7 of the child that contains `key` at `level` levels below the root (0 = root's
/// children). Bit 0 is x, bit 1 is y, bit 2 is z (OctoMap's `computeChildIdx`).
template <int Depth>
constexpr unsigned childIndex(const Key<Depth>& key, int level) {
  const int bit = Depth - 1 - level;
  return static_cast<unsigned>((key[0] >> bit) & 1U) |
         (static_cast<unsigned>((key[1] >> bit) & 1U) << 1) |
         (static_cast<unsigned>((key[2] >> bit) & 1U) << 2);
}

/// Grows the box [lo, hi] (inclusive, per axis) so that it holds `key`.
template <int Depth>
constexpr void growKeyBox(Key<Depth>& lo, Key<Depth>& hi, const Key<Depth>& key) {
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (key[axis] < lo[axis]) lo[axis] = key[axis];
    if (key[axis] > hi[axis]) hi[axis] = key[axis];
  }
}

/// A key of depth ≤ 21 packed without loss into one 64-bit word: x | y << Depth | z << 2 Depth
/// (48 bits for OctoMap's depth 16, paper §5.1). Cheaper to hash, compare and sort than the array;
/// sorting packed keys orders them by z, then y, then x.
template <int Depth>
  requires(Depth <= 21)
constexpr std::uint64_t packKey(const Key<Depth>& key) noexcept {
  return static_cast<std::uint64_t>(key[0]) | (static_cast<std::uint64_t>(key[1]) << Depth) |
         (static_cast<std::uint64_t>(key[2]) << (2 * Depth));
}

/// The key packKey() packed.
template <int Depth>
  requires(Depth <= 21)
constexpr Key<Depth> unpackKey(std::uint64_t packed) noexcept {
  constexpr std::uint64_t mask = (std::uint64_t{1} << Depth) - 1;
  using Index = typename Key<Depth>::Index;
  return Key<Depth>{{static_cast<Index>(packed & mask), static_cast<Index>((packed >> Depth) & mask),
                     static_cast<Index>((packed >> (2 * Depth)) & mask)}};
}

namespace detail {
/// The low 21 bits of `v` moved to every third bit: bit i goes to bit 3i.
constexpr std::uint64_t spreadEveryThirdBit(std::uint64_t v) noexcept {
  v &= 0x1FFFFF;
  v = (v | v << 32) & 0x1F00000000FFFFULL;
  v = (v | v << 16) & 0x1F0000FF0000FFULL;
  v = (v | v << 8) & 0x100F00F00F00F00FULL;
  v = (v | v << 4) & 0x10C30C30C30C30C3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// The inverse of spreadEveryThirdBit: bit 3i of `v` goes to bit i (the other bits are ignored).
constexpr std::uint64_t gatherEveryThirdBit(std::uint64_t v) noexcept {
  v &= 0x1249249249249249ULL;
  v = (v ^ (v >> 2)) & 0x10C30C30C30C30C3ULL;
  v = (v ^ (v >> 4)) & 0x100F00F00F00F00FULL;
  v = (v ^ (v >> 8)) & 0x1F0000FF0000FFULL;
  v = (v ^ (v >> 16)) & 0x1F00000000FFFFULL;
  v = (v ^ (v >> 32)) & 0x1FFFFF;
  return v;
}
}  // namespace detail

namespace detail {
/// kSpreadByte[v]: spreadEveryThirdBit(v) of a byte, for mortonCode.
inline constexpr auto kSpreadByte = [] {
  std::array<std::uint32_t, 256> table{};
  for (std::uint64_t v = 0; v < 256; ++v) table[v] = static_cast<std::uint32_t>(spreadEveryThirdBit(v));
  return table;
}();

/// kGatherByte[j][v]: the axes' bits held by byte j = v of a Morton code, gathered: x in bits
/// 0…20, y in 21…41, z in 42…62 (bit 8j + k of the code is bit (8j + k) / 3 of axis (8j + k) % 3).
inline constexpr auto kGatherByte = [] {
  std::array<std::array<std::uint64_t, 256>, 8> table{};
  for (unsigned j = 0; j < 8; ++j)
    for (unsigned v = 0; v < 256; ++v)
      for (unsigned k = 0; k < 8; ++k) {
        const unsigned m = 8 * j + k;
        if (((v >> k) & 1U) != 0 && m < 63) table[j][v] |= std::uint64_t{1} << (21 * (m % 3) + m / 3);
      }
  return table;
}();
}  // namespace detail

/// A key of depth ≤ 21 as its Morton code (Z-order, Morton 1966): bit 3i + a of the code is bit i
/// of axis a (x = 0, y = 1, z = 2), 48 bits for depth 16. Ascending codes are the order in which a
/// depth-first walk of the octree meets the voxels (children 0 … 7 at every level, childIndex()),
/// so keys updated in this order share the longest paths from the root. Computed a byte of each
/// axis at a time (a table of 256 spread bytes).
template <int Depth>
  requires(Depth <= 21)
constexpr std::uint64_t mortonCode(const Key<Depth>& key) noexcept {
  const auto spread = [](std::uint64_t v) {
    v &= (std::uint64_t{1} << Depth) - 1;
    std::uint64_t out = 0;
    for (int byte = 0; 8 * byte < Depth; ++byte) {
      out |= static_cast<std::uint64_t>(detail::kSpreadByte[(v >> (8 * byte)) & 0xFFU]) << (24 * byte);
    }
    return out;
  };
  return spread(key[0]) | (spread(key[1]) << 1) | (spread(key[2]) << 2);
}

/// The key whose mortonCode() is `code` (bits beyond 3 · Depth are ignored), a byte of the code at
/// a time (a table of each byte's bits gathered per axis).
template <int Depth>
  requires(Depth <= 21)
constexpr Key<Depth> keyOfMortonCode(std::uint64_t code) noexcept {
  using Index = typename Key<Depth>::Index;
  std::uint64_t axes = 0;
  for (int byte = 0; 8 * byte < 3 * Depth; ++byte) axes |= detail::kGatherByte[static_cast<std::size_t>(byte)][(code >> (8 * byte)) & 0xFFU];
  constexpr std::uint64_t mask = (std::uint64_t{1} << Depth) - 1;
  return Key<Depth>{{static_cast<Index>(axes & mask), static_cast<Index>((axes >> 21) & mask),
                     static_cast<Index>((axes >> 42) & mask)}};
}

/// Hash of a key, for unordered sets of keys (packKey() for depth ≤ 21).
template <int Depth>
struct KeyHash {
  std::size_t operator()(const Key<Depth>& key) const noexcept {
    if constexpr (Depth <= 21) {
      return static_cast<std::size_t>(packKey(key) * 0x9E3779B97F4A7C15ULL);
    } else {
      std::size_t h = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const auto lo = static_cast<std::uint64_t>(key[axis]);
        std::uint64_t hi = 0;
        if constexpr (Depth > 64) hi = static_cast<std::uint64_t>(key[axis] >> 64);
        h ^= std::hash<std::uint64_t>{}(lo ^ (hi * 0xC2B2AE3D27D4EB4FULL)) + 0x9E3779B97F4A7C15ULL +
             (h << 6) + (h >> 2);
      }
      return h;
    }
  }
};

/// The key OctoMap uses: depth 16, uint16 per axis.
using Key16 = Key<16>;

}  // namespace sonarmap
