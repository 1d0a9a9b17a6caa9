// insertPointCloud / insertRay behaviour: OctoMap's structural checks (17 nodes, pruning), range
// limit, skipped points, occupied over free, exact equality with a naive reference (dense and
// hash-set paths), parallel identity, lazy evaluation, scans at a pose, change detection vs OctoMap.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "octomap_reference.hpp"
#include "sonarmap/algorithms/point_cloud_insertion.hpp"
#include "sonarmap/raycast/dda.hpp"

namespace sonarmap {
namespace {

using namespace sonarmap::testing;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The naive OctoMap algorithm: ordered sets of keys, misses then hits, eager updates.
void referenceInsert(OcTree16& map, const PointCloud& points, const Eigen::Vector3d& origin, double max_range_m) {
  const auto less = [](const Key16& a, const Key16& b) { return a.k < b.k; };
  std::set<Key16, decltype(less)> free(less), occupied(less);
  std::vector<Key16> ray;
  for (const Eigen::Vector3d& p : points) {
    Eigen::Vector3d end = p;
    const bool clipped = max_range_m >= 0.0 && (p - origin).norm() > max_range_m;
    if (clipped) end = origin + (p - origin).normalized() * max_range_m;
    if (!rayKeysDDA(map.coder(), origin, end, ray)) continue;
    free.insert(ray.begin(), ray.end() - 1);  // the end voxel is not free
    if (!clipped) occupied.insert(ray.back());
  }
  for (const Key16& key : free)
    if (occupied.count(key) == 0) map.integrate(key, false);
  for (const Key16& key : occupied) map.integrate(key, true);
}

std::size_t occupiedVoxels(const OcTree16& map) {
  std::size_t count = 0;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (map.model().isOccupied(leaf.log_odds)) count += static_cast<std::size_t>(std::pow(leaf.edgeVoxels(), 3));
  });
  return count;
}

TEST(algorithmsInsertion, SinglePointInTheSensorVoxelMakes17Nodes) {
  OcTree16 ours(0.01);
  octomap::OcTree theirs(0.01);
  const PointCloud cloud{{0.0051, 0.0052, 0.0053}};
  const Eigen::Vector3d origin(0.001, 0.002, 0.003);
  const InsertStats stats = insertPointCloud(ours, cloud, origin);
  theirs.insertPointCloud(toOctomap(cloud), toOctomap(origin));
  EXPECT_EQ(stats.free_updates, 0U);
  EXPECT_EQ(stats.occupied_updates, 1U);
  EXPECT_EQ(ours.counts().nodes, 17U);
  EXPECT_EQ(theirs.size(), 17U);
}

TEST(algorithmsInsertion, ReportsTheBytesOfItsPerScanKeySets) {
  OcTree16 map(0.01);
  // Keys 32768 .. 32777 along x, one along y and z: 3 bricks of 4 × 4 × 4 voxels, a word each, in
  // the crossed set and in the hit set.
  const InsertStats near = insertPointCloud(map, PointCloud{{0.095, 0.005, 0.005}}, Eigen::Vector3d(0.005, 0.005, 0.005));
  EXPECT_EQ(near.key_set_bytes, 2 * 3 * sizeof(std::uint64_t));
  // A box of 20,000^3 voxels is far over the bitmap's limit: hash sets, sized by the keys alone.
  const InsertStats far = insertPointCloud(map, PointCloud{{200.0, 200.0, 200.0}}, Eigen::Vector3d(0.005, 0.005, 0.005));
  EXPECT_GT(far.key_set_bytes, 60000 * sizeof(Key16));  // the ray's ~60,000 crossed keys
  EXPECT_LT(far.key_set_bytes, std::size_t{16} << 20);
  InsertStats total = near;
  total += far;
  EXPECT_EQ(total.key_set_bytes, far.key_set_bytes);  // the largest scan's, not a sum
}

TEST(algorithmsInsertion, EightSiblingHitsPruneTo16Nodes) {
  OcTree16 ours(0.01);
  octomap::OcTree theirs(0.01);
  PointCloud cloud;
  for (int i = 0; i < 8; ++i) cloud.push_back(asFloat(0.005 + 0.01 * (i & 1), 0.005 + 0.01 * ((i >> 1) & 1), 0.005 + 0.01 * (i >> 2)));
  const Eigen::Vector3d origin = cloud.front();  // every ray stays inside the 8 siblings
  insertPointCloud(ours, cloud, origin);
  theirs.insertPointCloud(toOctomap(cloud), toOctomap(origin));
  EXPECT_EQ(ours.counts().nodes, 16U);
  EXPECT_EQ(ours.counts().leaves, 1U);
  EXPECT_EQ(theirs.size(), 16U);
}

TEST(algorithmsInsertion, CubeOf32VoxelsAt1cmPrunesToOneLeaf) {
  OcTree16 ours(0.01);
  octomap::OcTree theirs(0.01);
  PointCloud cloud;
  for (int x = 0; x < 32; ++x)
    for (int y = 0; y < 32; ++y)
      for (int z = 0; z < 32; ++z) cloud.push_back(asFloat(0.005 + 0.01 * x, 0.005 + 0.01 * y, 0.005 + 0.01 * z));
  const Eigen::Vector3d origin = asFloat(0.155, 0.165, 0.175);  // inside: all rays stay in the cube
  insertPointCloud(ours, cloud, origin);
  theirs.insertPointCloud(toOctomap(cloud), toOctomap(origin));
  EXPECT_EQ(ours.counts().leaves, 1U);
  EXPECT_EQ(ours.counts().nodes, 12U);  // a leaf at depth 11 under 11 inner nodes
  EXPECT_EQ(theirs.size(), 12U);
  EXPECT_EQ(occupiedVoxels(ours), 32U * 32U * 32U);
}

TEST(algorithmsInsertion, PointsBeyondMaxRangeClearUpToItAndMarkNothing) {
  OcTree16 ours(0.05);
  octomap::OcTree theirs(0.05);
  const Eigen::Vector3d origin = asFloat(0.012, 0.013, 0.011);
  const PointCloud cloud{asFloat(5.0, 0.31, 0.2), asFloat(-3.0, 4.0, 0.5)};
  InsertOptions options;
  options.max_range_m = 2.0;
  const InsertStats stats = insertPointCloud(ours, cloud, origin, options);
  theirs.insertPointCloud(toOctomap(cloud), toOctomap(origin), 2.0);
  EXPECT_EQ(stats.rays, 2U);
  EXPECT_EQ(stats.occupied_updates, 0U);
  EXPECT_EQ(occupiedVoxels(ours), 0U);
  for (const Eigen::Vector3d& p : cloud) {
    const Eigen::Vector3d dir = (p - origin).normalized();
    // Free up to the voxel holding the point at max range, which itself stays unknown.
    EXPECT_EQ(ours.occupancyAt(origin + dir * 1.9), Occupancy::kFree);
    EXPECT_EQ(ours.occupancyAt(origin + dir * 2.0), Occupancy::kUnknown);
    EXPECT_EQ(ours.occupancyAt(origin + dir * 2.2), Occupancy::kUnknown);
  }
  ours.forEachLeaf([&](const LeafView<16>& leaf) {
    EXPECT_LE((ours.coder().centerOf(leaf.key) - origin).norm(), 2.0 + 0.05);
  });
  const VoxelAgreement agreement = compareWithOctomap(ours, theirs);
  EXPECT_EQ(agreement.agree, agreement.unionKnown()) << agreement.summary();
}

TEST(algorithmsInsertion, NonFiniteAndOutOfMapPointsAreCountedAndSkipped) {
  OcTree16 map(0.01);  // the map spans ±327.68 m
  const PointCloud cloud{{kNaN, 0, 0}, {0, kInf, 0}, {0, 0, -kInf}, {1e4, 0, 0}, {1.0, 0.5, 0.2}};
  const Eigen::Vector3d origin(0.0, 0.0, 0.0);
  const InsertStats stats = insertPointCloud(map, cloud, origin);
  EXPECT_EQ(stats.points, 5U);
  EXPECT_EQ(stats.skipped_nonfinite, 3U);
  EXPECT_EQ(stats.out_of_map, 1U);
  EXPECT_EQ(stats.rays, 1U);
  EXPECT_EQ(stats.occupied_updates, 1U);
  EXPECT_EQ(map.occupancyAt({1.0, 0.5, 0.2}), Occupancy::kOccupied);
  // With a range limit the far point's ray is clipped inside the map: it clears space.
  OcTree16 limited(0.01);
  InsertOptions options;
  options.max_range_m = 3.0;
  const InsertStats clipped = insertPointCloud(limited, cloud, origin, options);
  EXPECT_EQ(clipped.out_of_map, 0U);
  EXPECT_EQ(clipped.rays, 2U);
  EXPECT_EQ(limited.occupancyAt({2.5, 0.0, 0.0}), Occupancy::kFree);
  // Discretisation counts the same way.
  options.discretize = true;
  options.max_range_m = -1.0;
  const InsertStats discrete = insertPointCloud(limited, cloud, origin, options);
  EXPECT_EQ(discrete.skipped_nonfinite, 3U);
  EXPECT_EQ(discrete.out_of_map, 1U);
  EXPECT_EQ(discrete.rays, 1U);
}

TEST(algorithmsInsertion, BadOriginOrRangeThrows) {
  OcTree16 map(0.01);
  const PointCloud cloud{{1.0, 0.0, 0.0}};
  EXPECT_THROW(insertPointCloud(map, cloud, {400.0, 0.0, 0.0}), OutOfMapError);
  EXPECT_THROW(insertPointCloud(map, cloud, {kNaN, 0.0, 0.0}), OutOfMapError);
  EXPECT_THROW(insertPointCloud(map, {}, {400.0, 0.0, 0.0}), OutOfMapError);
  EXPECT_THROW(insertPointCloud(map, cloud, {0.0, 0.0, 0.0}, {kNaN}), ValueError);
  EXPECT_TRUE(map.empty());
}

TEST(algorithmsInsertion, AnOccupiedVoxelIsNeverAlsoClearedInTheSameScan) {
  OcTree16 map(0.05);
  const Eigen::Vector3d origin(0.01, 0.01, 0.01);
  const PointCloud cloud{{1.01, 0.01, 0.01}, {2.01, 0.01, 0.01}};  // the far ray crosses the near hit
  const InsertStats stats = insertPointCloud(map, cloud, origin);
  EXPECT_EQ(stats.occupied_updates, 2U);
  EXPECT_FLOAT_EQ(*map.search(*map.coder().keyOf(cloud[0])), map.model().hit);
  EXPECT_FLOAT_EQ(*map.search(*map.coder().keyOf({1.5, 0.01, 0.01})), map.model().miss);
}

/// Clouds for the exactness tests: one whose key box takes the bitmap, one that needs the hash set.
PointCloud denseBoxCloud() { return randomBoxCloud({-2.0, -2.0, -1.0}, {2.0, 2.0, 1.0}, 20000, 5); }
PointCloud sparseBoxCloud() { return randomBoxCloud({-60.0, -60.0, -2.0}, {60.0, 60.0, 2.0}, 100, 6); }

TEST(algorithmsInsertion, NearTheMapBorderEqualsTheNaiveAlgorithm) {
  OcTree16 ours(0.01), reference(0.01);  // the map spans [-327.68, 327.68) m
  const Eigen::Vector3d origin(-327.5, 327.5, -327.6);
  const PointCloud cloud = randomBoxCloud({-327.68, 327.2, -327.68}, {-327.2, 327.6799, -327.2}, 2000, 12);
  const InsertStats stats = insertPointCloud(ours, cloud, origin);
  referenceInsert(reference, cloud, origin, -1.0);
  EXPECT_EQ(stats.rays + stats.out_of_map, cloud.size());
  EXPECT_GT(stats.rays, 1900U);
  EXPECT_EQ(leavesOf(ours), leavesOf(reference));
}

TEST(algorithmsInsertion, EqualsTheNaiveAlgorithmExactly) {
  for (const auto& [cloud, resolution_m] : {std::pair{denseBoxCloud(), 0.05}, std::pair{sparseBoxCloud(), 0.01}}) {
    for (const double max_range_m : {-1.0, 1.5}) {
      OcTree16 ours(resolution_m), reference(resolution_m);
      const Eigen::Vector3d origins[] = {{0.011, -0.02, 0.03}, {0.7, 0.4, -0.2}};
      for (const Eigen::Vector3d& origin : origins) {  // two scans: the second updates known voxels
        insertPointCloud(ours, cloud, origin, {max_range_m});
        referenceInsert(reference, cloud, origin, max_range_m);
      }
      EXPECT_EQ(leavesOf(ours), leavesOf(reference)) << "resolution " << resolution_m << " range " << max_range_m;
      EXPECT_EQ(ours.counts().nodes, reference.counts().nodes);
    }
  }
}

TEST(algorithmsInsertion, ParallelInsertionGivesTheIdenticalMap) {
  for (const auto& [cloud, resolution_m] : {std::pair{denseBoxCloud(), 0.02}, std::pair{sparseBoxCloud(), 0.01}}) {
    OcTree16 serial(resolution_m);
    const InsertStats expected = insertPointCloud(serial, cloud, {0.01, 0.02, 0.03});
    for (const unsigned threads : {2U, 3U, 4U, 0U}) {
      OcTree16 parallel(resolution_m);
      const InsertStats stats = insertPointCloudParallel(parallel, cloud, {0.01, 0.02, 0.03}, {}, threads);
      EXPECT_EQ(leavesOf(parallel), leavesOf(serial)) << threads << " threads";
      EXPECT_EQ(stats.free_updates, expected.free_updates);
      EXPECT_EQ(stats.occupied_updates, expected.occupied_updates);
    }
  }
}

TEST(algorithmsInsertion, HandedOverPointsGiveTheSameMapAndAreFreed) {
  // With a range limit (copied, clipped rays), without (the points as the rays), discretized.
  for (const InsertOptions options : {InsertOptions{-1.0}, InsertOptions{1.5}, InsertOptions{-1.0, true}}) {
    for (const unsigned threads : {1U, 2U}) {
      OcTree16 borrowed(0.02), handed(0.02);
      const PointCloud cloud = denseBoxCloud();
      const InsertStats expected = insertPointCloudParallel(borrowed, cloud, {0.01, 0.02, 0.03}, options, threads);
      PointCloud given = cloud;
      const InsertStats stats = insertPointCloudParallel(handed, std::move(given), {0.01, 0.02, 0.03}, options, threads);
      EXPECT_TRUE(given.empty());
      EXPECT_EQ(given.capacity(), 0U);
      EXPECT_EQ(leavesOf(handed), leavesOf(borrowed)) << options.max_range_m << " " << threads;
      EXPECT_EQ(stats.rays, expected.rays);
      EXPECT_EQ(stats.free_updates, expected.free_updates);
      EXPECT_EQ(stats.occupied_updates, expected.occupied_updates);
    }
  }
}

TEST(algorithmsInsertion, LazyEvaluationEndsInTheSameMap) {
  const PointCloud cloud = denseBoxCloud();
  OcTree16 eager(0.05), lazy_call(0.05);
  OctreeOptions lazy_options;
  lazy_options.lazy = true;
  OcTree16 lazy_tree(0.05, lazy_options);
  InsertOptions lazy;
  lazy.lazy_eval = true;
  for (const Eigen::Vector3d& origin : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.5, -0.3, 0.1)}) {
    insertPointCloud(eager, cloud, origin);
    insertPointCloud(lazy_call, cloud, origin, lazy);
    insertPointCloud(lazy_tree, cloud, origin);  // lazy anyway
  }
  EXPECT_GT(lazy_call.counts().nodes, eager.counts().nodes);  // not pruned yet
  lazy_call.updateInnerOccupancy();
  lazy_tree.updateInnerOccupancy();
  EXPECT_EQ(leavesOf(lazy_call), leavesOf(eager));
  EXPECT_EQ(leavesOf(lazy_tree), leavesOf(eager));
  EXPECT_FLOAT_EQ(*lazy_call.search(Key16{{32768, 32768, 32768}}, 0), *eager.search(Key16{{32768, 32768, 32768}}, 0));
}

TEST(algorithmsInsertion, ScanAtAPoseEqualsItsWorldCloud) {
  Scan scan;
  scan.points_m = sphereCloud({0.0, 0.0, 0.0}, 1.5, 90, 45);
  scan.sensor_to_world = Eigen::Translation3d(0.4, -0.2, 0.1) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ());
  PointCloud world;
  for (const Eigen::Vector3d& p : scan.points_m) world.push_back(scan.sensor_to_world * p);
  OcTree16 a(0.05), b(0.05);
  InsertStats total = insertScan(a, scan);
  const InsertStats single = insertPointCloud(b, world, scan.sensor_to_world.translation());
  EXPECT_EQ(leavesOf(a), leavesOf(b));
  total += single;
  EXPECT_EQ(total.points, 2 * scan.points_m.size());
  EXPECT_EQ(total.free_updates, 2 * single.free_updates);
}

TEST(algorithmsInsertion, InsertRayMatchesOctomap) {
  OcTree16 ours(0.05);
  octomap::OcTree theirs(0.05);
  const Eigen::Vector3d origin = asFloat(0.013, 0.021, -0.007);
  const PointCloud ends = randomBoxCloud({-3, -3, -1}, {3, 3, 1}, 200, 9);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    const double max_range_m = i % 2 == 0 ? -1.0 : 2.0;
    EXPECT_TRUE(insertRay(ours, origin, ends[i], max_range_m));
    theirs.insertRay(toOctomap(origin), toOctomap(ends[i]), max_range_m);
  }
  const VoxelAgreement agreement = compareWithOctomap(ours, theirs);
  EXPECT_EQ(agreement.agree, agreement.unionKnown()) << agreement.summary();
  EXPECT_FALSE(insertRay(ours, origin, {5000.0, 0.0, 0.0}));      // end outside the map (±1638 m)
  EXPECT_TRUE(insertRay(ours, origin, {5000.0, 0.0, 0.0}, 3.0));  // clipped inside it
  EXPECT_FALSE(insertRay(ours, {kNaN, 0.0, 0.0}, {1.0, 0.0, 0.0}));
  EXPECT_THROW(insertRay(ours, origin, {1.0, 0.0, 0.0}, kNaN), ValueError);
}

/// Changed keys of an OctoMap tree: key → created.
std::map<std::tuple<int, int, int>, bool> octomapChanges(const octomap::OcTree& tree) {
  std::map<std::tuple<int, int, int>, bool> changes;
  for (auto it = tree.changedKeysBegin(); it != tree.changedKeysEnd(); ++it) {
    changes[{it->first[0], it->first[1], it->first[2]}] = it->second;
  }
  return changes;
}

std::map<std::tuple<int, int, int>, bool> ourChanges(const OcTree16& tree) {
  std::map<std::tuple<int, int, int>, bool> changes;
  for (const auto& [key, change] : tree.changedKeys()) changes[{key[0], key[1], key[2]}] = change.created;
  return changes;
}

TEST(algorithmsInsertion, ChangeDetectionReportsTheSameKeysAsOctomap) {
  OcTree16 ours(0.05);
  octomap::OcTree theirs(0.05);
  ours.enableChangeDetection(true);
  theirs.enableChangeDetection(true);
  const PointCloud first = sphereCloud({0, 0, 0}, 1.5, 180, 90);
  const PointCloud second = sphereCloud({0.3, 0.2, 0.0}, 1.0, 180, 90);
  const Eigen::Vector3d origin = asFloat(0.013, -0.021, 0.032);
  insertPointCloud(ours, first, origin);
  theirs.insertPointCloud(toOctomap(first), toOctomap(origin));
  EXPECT_EQ(ourChanges(ours), octomapChanges(theirs));
  EXPECT_GT(ours.numChangesDetected(), 10000U);
  ours.resetChangeDetection();
  theirs.resetChangeDetection();
  insertPointCloud(ours, second, origin);  // hits inside known free space: free → occupied
  theirs.insertPointCloud(toOctomap(second), toOctomap(origin));
  EXPECT_EQ(ourChanges(ours), octomapChanges(theirs));
  std::size_t now_occupied = 0;
  for (const auto& [key, change] : ours.changedKeys()) now_occupied += change.occupied() ? 1 : 0;
  EXPECT_GT(now_occupied, 1000U);
}

}  // namespace
}  // namespace sonarmap
