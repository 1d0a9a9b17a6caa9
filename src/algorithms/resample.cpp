/// @file resample.cpp
/// resampledMap (see resample.hpp).

#include "sonarmap/algorithms/resample.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <absl/container/flat_hash_map.h>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

using Key16 = OcTree16::KeyType;

/// A key as one 48-bit number (x, y, z of 16 bits each): hashable, and ordered as the keys' (x, y, z).
std::uint64_t packed(const Key16& key) {
  return (std::uint64_t{key[0]} << 32) | (std::uint64_t{key[1]} << 16) | std::uint64_t{key[2]};
}

Key16 unpacked(std::uint64_t code) {
  return Key16{{static_cast<std::uint16_t>(code >> 32), static_cast<std::uint16_t>(code >> 16),
                static_cast<std::uint16_t>(code)}};
}

}  // namespace

OcTree16 resampledMap(const OcTree16& map, double resolution_m) {
  if (!(std::isfinite(resolution_m) && resolution_m >= map.resolution_m())) {
    throw ValueError("resampling: the new resolution " + std::to_string(resolution_m) +
                     " m must be finite and at least the map's " + std::to_string(map.resolution_m()) + " m");
  }
  OcTree16 coarse(resolution_m, map.options());
  const KeyCoder<16>& fine_coder = map.coder();
  const KeyCoder<16>& coarse_coder = coarse.coder();
  absl::flat_hash_map<std::uint64_t, float> largest;
  const auto keep = [&](const Key16& key, float log_odds) {
    const auto [it, inserted] = largest.try_emplace(packed(key), log_odds);
    if (!inserted) it->second = std::max(it->second, log_odds);
  };
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    const double edge_m = leaf.edgeVoxels() * map.resolution_m();
    const Eigen::Vector3d low_m = fine_coder.centerOf(leaf.key) - Eigen::Vector3d::Constant(0.5 * map.resolution_m());
    // The new voxels whose centres lie in [low, low + edge) on every axis.
    std::array<long, 3> first{}, last{};
    bool any = true;
    for (int axis = 0; axis < 3; ++axis) {
      first[axis] = static_cast<long>(std::ceil(low_m[axis] / resolution_m - 0.5));
      last[axis] = static_cast<long>(std::ceil((low_m[axis] + edge_m) / resolution_m - 0.5)) - 1;
      any = any && first[axis] <= last[axis];
    }
    if (!any) {
      keep(coarse_coder.keyOfChecked(low_m + Eigen::Vector3d::Constant(0.5 * edge_m)), leaf.log_odds);
      return;
    }
    for (long x = first[0]; x <= last[0]; ++x) {
      for (long y = first[1]; y <= last[1]; ++y) {
        for (long z = first[2]; z <= last[2]; ++z) {
          const Eigen::Vector3d centre_m(static_cast<double>(x) * resolution_m, static_cast<double>(y) * resolution_m,
                                         static_cast<double>(z) * resolution_m);
          keep(coarse_coder.keyOfChecked(centre_m + Eigen::Vector3d::Constant(0.5 * resolution_m)), leaf.log_odds);
        }
      }
    }
  });
  std::vector<std::pair<std::uint64_t, float>> voxels(largest.begin(), largest.end());
  std::sort(voxels.begin(), voxels.end());
  for (const auto& [code, log_odds] : voxels) coarse.updateNode(unpacked(code), log_odds, /*lazy_eval=*/true);
  coarse.updateInnerOccupancy();
  return coarse;
}

}  // namespace sonarmap
