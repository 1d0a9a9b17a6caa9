// insertPointCloud against OctoMap 1.9's (liboctomap-dev, test-only): the same clouds into both
// trees at the same resolution, then every finest voxel known to either compared by class. The DDAs
// differ only in float rounding at voxel boundaries (OctoMap's stops a voxel early on some rays;
// ties between axes), so the maps must agree on ≥ 99.9 % of the known volume.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <tuple>

#include "octomap_reference.hpp"
#include "sonarmap/algorithms/point_cloud_insertion.hpp"

namespace sonarmap {
namespace {

using namespace sonarmap::testing;

constexpr double kMinAgreement = 0.999;

enum class CloudKind { kSphere, kPlane, kRandomBox };

const char* nameOf(CloudKind kind) {
  switch (kind) {
    case CloudKind::kSphere: return "sphere";
    case CloudKind::kPlane: return "plane";
    case CloudKind::kRandomBox: return "randombox";
  }
  return "?";
}

/// The cloud, and a range limit that cuts part of it.
std::pair<PointCloud, double> makeCloud(CloudKind kind) {
  switch (kind) {
    case CloudKind::kSphere: return {sphereCloud({0.0, 0.0, 0.0}, 2.0, 360, 180, 0.4), 2.2};
    case CloudKind::kPlane: return {planeCloud(-1.0, 3.0, 0.03), 2.5};
    case CloudKind::kRandomBox: return {randomBoxCloud({-3.0, -3.0, -1.5}, {3.0, 3.0, 1.5}, 40000, 11), 2.5};
  }
  return {};
}

using ParityParam = std::tuple<CloudKind, double, bool, bool>;  // cloud, resolution, max range, discretize

class algorithmsParity : public ::testing::TestWithParam<ParityParam> {};

TEST_P(algorithmsParity, SameVoxelsAsOctomapInsertPointCloud) {
  const auto [kind, resolution_m, use_max_range, discretize] = GetParam();
  const auto [cloud, range_m] = makeCloud(kind);
  const Eigen::Vector3d origin = asFloat(0.013, -0.021, 0.032);
  InsertOptions options;
  options.max_range_m = use_max_range ? range_m : -1.0;
  options.discretize = discretize;

  OcTree16 ours(resolution_m);
  const InsertStats stats = insertPointCloud(ours, cloud, origin, options);
  octomap::OcTree theirs(resolution_m);
  theirs.insertPointCloud(toOctomap(cloud), toOctomap(origin), options.max_range_m, false, discretize);

  const VoxelAgreement agreement = compareWithOctomap(ours, theirs);
  std::printf("[parity] %s res %.2f max_range %s discretize %d: rays %zu, free %zu, occupied %zu; %s\n",
              nameOf(kind), resolution_m, use_max_range ? std::to_string(range_m).c_str() : "none",
              discretize ? 1 : 0, stats.rays, stats.free_updates, stats.occupied_updates,
              agreement.summary().c_str());
  EXPECT_GE(agreement.agreement(), kMinAgreement) << agreement.summary();
  EXPECT_GT(agreement.agree, 10000U);
  if (use_max_range) {
    EXPECT_LT(stats.occupied_updates, cloud.size());  // the limit cut some points
  }
}

std::string parityName(const ::testing::TestParamInfo<ParityParam>& info) {
  const auto [kind, resolution_m, use_max_range, discretize] = info.param;
  return std::string(nameOf(kind)) + "_" + std::to_string(static_cast<int>(resolution_m * 100 + 0.5)) + "cm" +
         (use_max_range ? "_maxrange" : "") + (discretize ? "_discretize" : "");
}

INSTANTIATE_TEST_SUITE_P(algorithms, algorithmsParity,
                         ::testing::Combine(::testing::Values(CloudKind::kSphere, CloudKind::kPlane,
                                                              CloudKind::kRandomBox),
                                            ::testing::Values(0.05, 0.02), ::testing::Bool(), ::testing::Bool()),
                         parityName);

/// The walls, floor and ceiling of a room [lo, hi] with a pillar, seen from `origin`.
PointCloud roomScan(const Eigen::Vector3d& origin, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  PointCloud cloud;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < 360; ++i) {
    for (int j = 0; j < 120; ++j) {
      const double azimuth = 2.0 * pi * (i + 0.37) / 360.0;
      const double elevation = pi * ((j + 0.5) / 120.0 - 0.5);
      const Eigen::Vector3d d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                              std::sin(elevation));
      double t = 1e9;  // distance to the first surface along d
      for (int axis = 0; axis < 3; ++axis) {
        if (d[axis] > 1e-9) t = std::min(t, (hi[axis] - origin[axis]) / d[axis]);
        if (d[axis] < -1e-9) t = std::min(t, (lo[axis] - origin[axis]) / d[axis]);
      }
      // A vertical pillar of radius 0.3 m at (1, 1).
      const Eigen::Vector2d o(origin.x() - 1.0, origin.y() - 1.0), v(d.x(), d.y());
      const double a = v.squaredNorm(), b = 2.0 * o.dot(v), c = o.squaredNorm() - 0.09;
      if (a > 1e-12 && b * b - 4 * a * c >= 0.0) {
        const double s = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
        if (s > 0.0) t = std::min(t, s);
      }
      const Eigen::Vector3d p = origin + t * d;
      cloud.push_back(asFloat(p.x(), p.y(), p.z()));
    }
  }
  return cloud;
}

class algorithmsParitySequence : public ::testing::TestWithParam<double> {};

TEST_P(algorithmsParitySequence, ScansFromSeveralOriginsMatchOctomap) {
  const double resolution_m = GetParam();
  OcTree16 ours(resolution_m);
  octomap::OcTree theirs(resolution_m);
  const Eigen::Vector3d origins[] = {asFloat(0.01, 0.02, 0.0), asFloat(-1.7, 1.1, 0.3), asFloat(2.1, -1.4, -0.2),
                                     asFloat(-0.6, -1.9, 0.8)};
  int scan = 0;
  for (const Eigen::Vector3d& origin : origins) {
    // Walls off the voxel faces (see PointsOnVoxelFaces below for walls on them).
    const PointCloud cloud = roomScan(origin, {-3.0137, -2.5071, -1.0093}, {2.9871, 2.4917, 1.5113});
    const double max_range_m = scan % 2 == 0 ? -1.0 : 4.0;  // alternate: no limit, 4 m
    insertPointCloud(ours, cloud, origin, {max_range_m});
    theirs.insertPointCloud(toOctomap(cloud), toOctomap(origin), max_range_m);
    ++scan;
    if (resolution_m < 0.03 && scan < 4) continue;  // at 2 cm compare the final map only (7 M voxels)
    const VoxelAgreement agreement = compareWithOctomap(ours, theirs);
    std::printf("[parity] room after %d scans, res %.2f: %s\n", scan, resolution_m, agreement.summary().c_str());
    EXPECT_GE(agreement.agreement(), kMinAgreement) << "after scan " << scan << ": " << agreement.summary();
  }
  std::printf("[parity] room res %.2f: nodes ours %zu, OctoMap %zu\n", resolution_m, ours.counts().nodes,
              theirs.size());
}

INSTANTIATE_TEST_SUITE_P(algorithms, algorithmsParitySequence, ::testing::Values(0.05, 0.02),
                         [](const auto& info) { return info.param > 0.03 ? std::string("5cm") : std::string("2cm"); });

/// True when a face neighbour of `key` is occupied in both maps.
bool nextToAnObstacle(const OcTree16& ours, const octomap::OcTree& theirs, const Key16& key) {
  for (int axis = 0; axis < 3; ++axis) {
    for (const int step : {-1, 1}) {
      Key16 next = key;
      next[axis] = static_cast<std::uint16_t>(next[axis] + step);
      const octomap::OcTreeNode* node = theirs.search(toOctomap(next));
      if (ours.occupancyOf(next) == Occupancy::kOccupied && node != nullptr && theirs.isNodeOccupied(node)) return true;
    }
  }
  return false;
}

// Points exactly on voxel faces (axis-aligned walls at multiples of the resolution): OctoMap's float
// DDA stops one voxel early on many of these rays, so the free voxel just before the wall is
// missing from its map; our DDA always reaches the end voxel (raycast/dda.hpp). The maps never
// disagree on a class; every voxel only we know lies against the wall.
TEST(algorithmsParityFaces, PointsOnVoxelFacesKeepTheLastFreeVoxel) {
  OcTree16 ours(0.05);
  octomap::OcTree theirs(0.05);
  const Eigen::Vector3d origin = asFloat(0.01, 0.02, 0.0);
  const PointCloud cloud = roomScan(origin, {-3.0, -2.5, -1.0}, {3.0, 2.5, 1.5});
  insertPointCloud(ours, cloud, origin);
  theirs.insertPointCloud(toOctomap(cloud), toOctomap(origin));
  const VoxelAgreement agreement = compareWithOctomap(ours, theirs);
  std::printf("[parity] room walls on voxel faces, res 0.05: %s\n", agreement.summary().c_str());
  EXPECT_EQ(agreement.differ, 0U);
  EXPECT_EQ(agreement.only_theirs, 0U);
  EXPECT_GE(agreement.agreement(), 0.99);
  std::size_t against_wall = 0;
  ours.forEachLeaf([&](const LeafView<16>& leaf) {
    forEachVoxel(leaf.key, static_cast<unsigned>(leaf.edgeVoxels()), [&](const Key16& key) {
      if (theirs.search(toOctomap(key)) == nullptr && nextToAnObstacle(ours, theirs, key)) ++against_wall;
    });
  });
  EXPECT_EQ(against_wall, agreement.only_ours);
}

}  // namespace
}  // namespace sonarmap
