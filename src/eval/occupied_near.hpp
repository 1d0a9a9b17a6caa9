#pragma once
// Whether an occupied voxel lies within a distance of a voxel, on one voxel grid: the match of
// recall (eval/ground_truth.cpp) and of heard recall (eval/heard_surface.cpp). Internal to the
// library.

#include <cmath>
#include <cstdint>
#include <unordered_set>

#include "sonarmap/core/key.hpp"

namespace sonarmap::detail {

/// A set of finest voxels' keys.
using KeySet = std::unordered_set<Key<16>, KeyHash<16>>;

/// True when a key of `occupied` has its centre within `tolerance_m` of the centre of `key`, both
/// on the grid of voxel edge `res_m` (metres): the keys k + d with |d| · res_m ≤ tolerance_m.
/// Cost: (2 ⌊tolerance_m / res_m⌋ + 1)³ look-ups at most.
inline bool occupiedNear(const KeySet& occupied, const Key<16>& key, double tolerance_m, double res_m) {
  const int reach = static_cast<int>(std::floor(tolerance_m / res_m));
  const double reach_sq = (tolerance_m / res_m) * (tolerance_m / res_m);
  for (int dz = -reach; dz <= reach; ++dz) {
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        if (dx * dx + dy * dy + dz * dz > reach_sq) continue;
        const Key<16> near{{static_cast<std::uint16_t>(key[0] + dx), static_cast<std::uint16_t>(key[1] + dy),
                            static_cast<std::uint16_t>(key[2] + dz)}};
        if (occupied.contains(near)) return true;
      }
    }
  }
  return false;
}

}  // namespace sonarmap::detail
