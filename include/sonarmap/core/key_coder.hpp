#pragma once
/// @file key_coder.hpp
/// Conversion between world coordinates in metres and voxel keys (paper §5.1).
///
/// `key = floor(coord_m / resolution_m) + 2^(Depth-1)` and the centre of a key is
/// `(key - 2^(Depth-1) + 0.5) * resolution_m`: OctoMap's convention for depth 16
/// (`../shared/docs/formats.md`). The tree addresses coordinates in
/// [-2^(Depth-1) * res, 2^(Depth-1) * res) on each axis; anything outside is rejected
/// (std::nullopt or OutOfMapError), never wrapped. Coordinates are doubles, so beyond 2^53 voxels
/// from the origin (depths above 53) keys are exact but coordinates round to the nearest double.

#include <cmath>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/core/key.hpp"

namespace sonarmap {

/// Converts between metres and keys for a tree of depth `Depth` and a given resolution.
template <int Depth>
class KeyCoder {
 public:
  using KeyType = Key<Depth>;
  using Index = typename KeyType::Index;

  /// @param resolution_m edge of a finest-level voxel in metres; must be finite and > 0.
  /// @throws ValueError if the resolution is not finite and positive.
  explicit KeyCoder(double resolution_m) : resolution_m_(resolution_m), inv_resolution_(1.0 / resolution_m) {
    if (!std::isfinite(resolution_m) || resolution_m <= 0.0) {
      throw ValueError("resolution must be a finite number of metres > 0, got " + std::to_string(resolution_m));
    }
  }

  double resolution_m() const { return resolution_m_; }

  /// Half the number of voxels per axis: the key of coordinate 0.
  static constexpr double offset() { return std::ldexp(1.0, Depth - 1); }

  /// Key index of one coordinate in metres, or nullopt if outside the map (or not finite).
  std::optional<Index> indexOf(double coord_m) const {
    const double cell = std::floor(coord_m * inv_resolution_);
    if (!(cell >= -offset() && cell < offset())) return std::nullopt;  // also rejects NaN
    return indexFromCell(cell);
  }

  /// Key of a point in metres (world frame), or nullopt if any axis lies outside the map.
  std::optional<KeyType> keyOf(const Eigen::Vector3d& point_m) const {
    KeyType key;
    for (int axis = 0; axis < 3; ++axis) {
      const auto index = indexOf(point_m[axis]);
      if (!index) return std::nullopt;
      key[axis] = *index;
    }
    return key;
  }

  /// keyOf without the optional, for loops over many points: writes the key of `point_m` (metres,
  /// world frame) to `key` and returns true, or returns false, leaving `key` unspecified, when any
  /// axis lies outside the map or is not finite. The same keys as keyOf. Nothing is thrown.
  bool keyInto(const Eigen::Vector3d& point_m, KeyType& key) const {
    for (int axis = 0; axis < 3; ++axis) {
      const double scaled = point_m[axis] * inv_resolution_;
      // floor(scaled) lies in [-offset, offset) exactly when scaled does (offset is an integer).
      if (!(scaled >= -offset() && scaled < offset())) return false;  // also rejects NaN
      if constexpr (Depth <= 53) {
        // floor by truncation, one less below zero: exact, every cell here fits a long long.
        auto cell = static_cast<long long>(scaled);
        if (scaled < static_cast<double>(cell)) --cell;
        key[axis] = static_cast<Index>(cell + (1LL << (Depth - 1)));
      } else {
        key[axis] = indexFromCell(std::floor(scaled));
      }
    }
    return true;
  }

  /// Key of a point in metres.
  /// @throws OutOfMapError if the point is outside the map or not finite.
  KeyType keyOfChecked(const Eigen::Vector3d& point_m) const {
    if (auto key = keyOf(point_m)) return *key;
    throw OutOfMapError("point (" + std::to_string(point_m.x()) + ", " + std::to_string(point_m.y()) + ", " +
                        std::to_string(point_m.z()) + ") m is outside the map of depth " +
                        std::to_string(Depth) + " at resolution " + std::to_string(resolution_m_) + " m");
  }

  /// Centre in metres of the voxel with key index `index` (finest level).
  double centerOf(Index index) const { return (cellOf(index) + 0.5) * resolution_m_; }

  /// Centre in metres of the finest-level voxel `key`.
  Eigen::Vector3d centerOf(const KeyType& key) const {
    return {centerOf(key[0]), centerOf(key[1]), centerOf(key[2])};
  }

  /// Signed voxel count from the origin, `index − 2^(Depth−1)`, computed in integers first.
  static double cellOf(Index index) {
    const Index half = Index{1} << (Depth - 1);
    if (index >= half) return toDouble(static_cast<Index>(index - half));
    return -toDouble(static_cast<Index>(half - index));
  }

  static double toDouble(Index index) {
    if constexpr (Depth > 64) {
      return std::ldexp(static_cast<double>(static_cast<std::uint64_t>(index >> 64)), 64) +
             static_cast<double>(static_cast<std::uint64_t>(index));
    } else {
      return static_cast<double>(index);
    }
  }

 private:
  static Index indexFromCell(double cell) {
    if constexpr (Depth > 63) {
      // Wide keys: split the offset addition so no intermediate exceeds int64.
      const Index half = Index{1} << (Depth - 1);
      const auto magnitude = static_cast<Index>(std::fabs(cell));
      return cell >= 0 ? static_cast<Index>(half + magnitude) : static_cast<Index>(half - magnitude);
    } else {
      return static_cast<Index>(static_cast<long long>(cell) + (1LL << (Depth - 1)));
    }
  }

  double resolution_m_;
  double inv_resolution_;
};

}  // namespace sonarmap
