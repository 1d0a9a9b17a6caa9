#pragma once
// Test helpers shared by the algorithms tests: clouds in OctoMap's float precision, conversion to
// OctoMap's types, voxel-by-voxel comparison of our tree with an octomap::OcTree, and exact
// comparison of two of our trees.

#include <octomap/OcTree.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "sonarmap/core/point_cloud.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap::testing {

/// A point rounded to float, so OctoMap (float points) and we (doubles) see the same coordinates.
inline Eigen::Vector3d asFloat(double x, double y, double z) {
  return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
}

inline octomap::point3d toOctomap(const Eigen::Vector3d& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

inline octomap::Pointcloud toOctomap(const PointCloud& cloud) {
  octomap::Pointcloud out;
  out.reserve(cloud.size());
  for (const Eigen::Vector3d& p : cloud) out.push_back(toOctomap(p));
  return out;
}

inline octomap::OcTreeKey toOctomap(const Key16& key) { return octomap::OcTreeKey(key[0], key[1], key[2]); }

/// Points on a sphere of radius `radius_m` around `centre_m`, `azimuths` × `elevations` directions
/// (poles excluded); `ripple_m` > 0 modulates the radius so part of the cloud lies beyond a range limit.
inline PointCloud sphereCloud(const Eigen::Vector3d& centre_m, double radius_m, int azimuths, int elevations,
                              double ripple_m = 0.0) {
  PointCloud cloud;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < azimuths; ++i) {
    for (int j = 0; j < elevations; ++j) {
      const double azimuth = 2.0 * pi * (i + 0.5) / azimuths;
      const double elevation = pi * ((j + 0.5) / elevations - 0.5);
      const double r = radius_m + ripple_m * std::sin(3.0 * azimuth) * std::cos(2.0 * elevation);
      const Eigen::Vector3d d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                              std::sin(elevation));
      const Eigen::Vector3d p = centre_m + r * d;
      cloud.push_back(asFloat(p.x(), p.y(), p.z()));
    }
  }
  return cloud;
}

/// A horizontal plane z = `z_m`, a square of side 2 × `half_m` sampled every `step_m`.
inline PointCloud planeCloud(double z_m, double half_m, double step_m) {
  PointCloud cloud;
  const int n = static_cast<int>(std::lround(2.0 * half_m / step_m));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) cloud.push_back(asFloat(-half_m + i * step_m, -half_m + j * step_m + 0.003, z_m));
  return cloud;
}

/// Uniform random points in the box [lo, hi].
inline PointCloud randomBoxCloud(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int count, unsigned seed) {
  std::mt19937 rng(seed);
  PointCloud cloud;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d p;
    for (int axis = 0; axis < 3; ++axis) p[axis] = std::uniform_real_distribution<double>(lo[axis], hi[axis])(rng);
    cloud.push_back(asFloat(p.x(), p.y(), p.z()));
  }
  return cloud;
}

/// Voxel counts of a comparison of two maps over every finest voxel known to either.
struct VoxelAgreement {
  std::size_t ours_known = 0;    ///< voxels known in our map
  std::size_t theirs_known = 0;  ///< voxels known in OctoMap's
  std::size_t agree = 0;         ///< known in both, same class (free / occupied)
  std::size_t differ = 0;        ///< known in both, different class
  std::size_t only_ours = 0;     ///< known in ours only
  std::size_t only_theirs = 0;   ///< known in OctoMap's only
  std::size_t unionKnown() const { return agree + differ + only_ours + only_theirs; }
  double agreement() const { return unionKnown() == 0 ? 1.0 : static_cast<double>(agree) / unionKnown(); }
  std::string summary() const {
    return "known ours " + std::to_string(ours_known) + ", OctoMap " + std::to_string(theirs_known) + "; agree " +
           std::to_string(agree) + ", differ " + std::to_string(differ) + ", only ours " +
           std::to_string(only_ours) + ", only OctoMap " + std::to_string(only_theirs) + " (" +
           std::to_string(100.0 * agreement()) + " %)";
  }
};

/// Calls visit(key) for every finest voxel inside a leaf whose lowest corner is `corner` and whose
/// edge is `edge` voxels.
template <class Visit>
void forEachVoxel(const Key16& corner, unsigned edge, Visit&& visit) {
  for (unsigned z = 0; z < edge; ++z)
    for (unsigned y = 0; y < edge; ++y)
      for (unsigned x = 0; x < edge; ++x) {
        visit(Key16{{static_cast<std::uint16_t>(corner[0] + x), static_cast<std::uint16_t>(corner[1] + y),
                     static_cast<std::uint16_t>(corner[2] + z)}});
      }
}

/// Compares the class (free / occupied) of every finest voxel known to either map.
inline VoxelAgreement compareWithOctomap(const OcTree16& ours, const octomap::OcTree& theirs) {
  VoxelAgreement result;
  ours.forEachLeaf([&](const LeafView<16>& leaf) {
    const bool occupied = ours.model().isOccupied(leaf.log_odds);
    forEachVoxel(leaf.key, static_cast<unsigned>(leaf.edgeVoxels()), [&](const Key16& key) {
      ++result.ours_known;
      const octomap::OcTreeNode* node = theirs.search(toOctomap(key));
      if (node == nullptr) {
        ++result.only_ours;
      } else if (theirs.isNodeOccupied(node) == occupied) {
        ++result.agree;
      } else {
        ++result.differ;
      }
    });
  });
  for (auto it = theirs.begin_leafs(), end = theirs.end_leafs(); it != end; ++it) {
    const unsigned edge = 1U << (16 - it.getDepth());
    const octomap::OcTreeKey& k = it.getKey();
    const auto mask = static_cast<std::uint16_t>(~(edge - 1));
    const Key16 corner{{static_cast<std::uint16_t>(k[0] & mask), static_cast<std::uint16_t>(k[1] & mask),
                        static_cast<std::uint16_t>(k[2] & mask)}};
    forEachVoxel(corner, edge, [&](const Key16& key) {
      ++result.theirs_known;
      if (!ours.search(key)) ++result.only_theirs;
    });
  }
  return result;
}

/// Every leaf of a tree as (key, depth, log-odds), in depth-first order.
inline std::vector<std::tuple<std::uint16_t, std::uint16_t, std::uint16_t, int, float>> leavesOf(const OcTree16& tree) {
  std::vector<std::tuple<std::uint16_t, std::uint16_t, std::uint16_t, int, float>> leaves;
  tree.forEachLeaf([&](const LeafView<16>& l) { leaves.emplace_back(l.key[0], l.key[1], l.key[2], l.depth, l.log_odds); });
  return leaves;
}

}  // namespace sonarmap::testing
