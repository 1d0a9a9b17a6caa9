// The surface voxels of a scene inside a box of keys (see surface_voxels.hpp).

#include "surface_voxels.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace sonarmap::detail {
namespace {

using Key16 = Key<16>;

/// Against rounding in the distance computations: a sub-box is dropped only when it is this much
/// farther from a primitive than the bound requires (metres).
constexpr double kMargin_m = 1e-6;

/// Where a voxel is tested (surface_voxels.hpp): its centre moved towards its lower corner by a
/// millionth of a voxel on every axis.
Eigen::Vector3d probeOf(const KeyCoder<16>& coder, const Key16& key) {
  return coder.centerOf(key).array() - 1e-6 * coder.resolution_m();
}

/// True when the probe point lies within res / 2 of one of `primitives` (indices into the scene).
bool nearSurface(const Scene& scene, const std::vector<std::size_t>& primitives, const Eigen::Vector3d& center_m,
                 double half_res_m) {
  double nearest_m = std::numeric_limits<double>::infinity();
  for (const std::size_t i : primitives) nearest_m = std::min(nearest_m, distanceToSurface(scene.primitives[i], center_m));
  return nearest_m <= half_res_m;
}

class Recursion {
 public:
  Recursion(const KeyCoder<16>& coder, const Scene& scene, std::vector<Key16>& out)
      : coder_(coder), scene_(scene), half_res_m_(0.5 * coder.resolution_m()), out_(out) {}

  /// The inclusive box [lo, hi] (per axis as ints), against the primitives `candidates`.
  void visit(const std::array<int, 3>& lo, const std::array<int, 3>& hi, const std::vector<std::size_t>& candidates) {
    Eigen::Vector3d low_m, high_m;
    for (int axis = 0; axis < 3; ++axis) {
      low_m[axis] = coder_.centerOf(static_cast<std::uint16_t>(lo[axis]));
      high_m[axis] = coder_.centerOf(static_cast<std::uint16_t>(hi[axis]));
    }
    const Eigen::Vector3d middle_m = 0.5 * (low_m + high_m);
    const double reach_m = 0.5 * (high_m - low_m).norm() + half_res_m_ + 2e-6 * coder_.resolution_m() + kMargin_m;
    std::vector<std::size_t> near;
    near.reserve(candidates.size());
    for (const std::size_t i : candidates) {
      if (distanceToSurface(scene_.primitives[i], middle_m) <= reach_m) near.push_back(i);
    }
    if (near.empty()) return;
    bool small = true;
    for (int axis = 0; axis < 3; ++axis) small = small && hi[axis] - lo[axis] < 2;
    if (small) {
      for (int z = lo[2]; z <= hi[2]; ++z) {
        for (int y = lo[1]; y <= hi[1]; ++y) {
          for (int x = lo[0]; x <= hi[0]; ++x) {
            const Key16 key{{static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint16_t>(z)}};
            if (nearSurface(scene_, near, probeOf(coder_, key), half_res_m_)) out_.push_back(key);
          }
        }
      }
      return;
    }
    // Halve every axis longer than one voxel: up to 8 sub-boxes.
    std::array<std::array<int, 2>, 3> lows{}, highs{};
    std::array<int, 3> parts{};
    for (int axis = 0; axis < 3; ++axis) {
      if (hi[axis] > lo[axis]) {
        const int split = lo[axis] + (hi[axis] - lo[axis]) / 2;
        lows[axis] = {lo[axis], split + 1};
        highs[axis] = {split, hi[axis]};
        parts[axis] = 2;
      } else {
        lows[axis] = {lo[axis], lo[axis]};
        highs[axis] = {hi[axis], hi[axis]};
        parts[axis] = 1;
      }
    }
    for (int cz = 0; cz < parts[2]; ++cz) {
      for (int cy = 0; cy < parts[1]; ++cy) {
        for (int cx = 0; cx < parts[0]; ++cx) {
          visit({lows[0][cx], lows[1][cy], lows[2][cz]}, {highs[0][cx], highs[1][cy], highs[2][cz]}, near);
        }
      }
    }
  }

 private:
  const KeyCoder<16>& coder_;
  const Scene& scene_;
  double half_res_m_;
  std::vector<Key16>& out_;
};

bool emptyBox(const Key16& lo, const Key16& hi) { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }

}  // namespace

std::vector<Key16> surfaceVoxelsBruteForce(const KeyCoder<16>& coder, const Scene& scene, const Key16& lo,
                                           const Key16& hi) {
  std::vector<Key16> keys;
  if (emptyBox(lo, hi)) return keys;
  const double half_res_m = 0.5 * coder.resolution_m();
  for (int z = lo[2]; z <= hi[2]; ++z) {
    for (int y = lo[1]; y <= hi[1]; ++y) {
      for (int x = lo[0]; x <= hi[0]; ++x) {
        const Key16 key{{static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint16_t>(z)}};
        if (distanceToSurface(scene, probeOf(coder, key)) <= half_res_m) keys.push_back(key);
      }
    }
  }
  return keys;
}

std::vector<Key16> surfaceVoxels(const KeyCoder<16>& coder, const Scene& scene, const Key16& lo, const Key16& hi) {
  std::vector<Key16> keys;
  if (emptyBox(lo, hi) || scene.primitives.empty()) return keys;
  std::vector<std::size_t> all(scene.primitives.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  Recursion(coder, scene, keys).visit({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, all);
  return keys;
}

}  // namespace sonarmap::detail
