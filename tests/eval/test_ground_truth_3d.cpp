// evaluateAgainstScene in 3D: erosion and the surface error exactly on hand-made maps, the
// sensors' field of view (vertical aperture), the hierarchical search of surface voxels against
// the brute-force one, and a perfect and a fully eroded map of the 3D scene quay3d.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "eval/surface_voxels.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"

namespace sonarmap {
namespace {

constexpr double kRes = 0.1;  // T = √3 · 0.1 = 0.173 m
constexpr double kDegree = std::numbers::pi / 180.0;

/// Voxel centres of the hand-made maps: ((i + 0.5) · res, (j + 0.5) · res, (k + 0.5) · res).
Key16 keyAt(const OcTree16& map, int i, int j, int k = 0) {
  return map.coder().keyOfChecked({(i + 0.5) * kRes, (j + 0.5) * kRes, (k + 0.5) * kRes});
}
void setFree(OcTree16& map, int i, int j, int k = 0) { map.updateNode(keyAt(map, i, j, k), -2.0F); }
void setOccupied(OcTree16& map, int i, int j, int k = 0) { map.updateNode(keyAt(map, i, j, k), 4.0F); }

/// A wall x = 1.05 m (the centres of column i = 10) seen from the origin.
Scene wallScene() { return Scene{{Plane{{1.05, 0.0, 0.0}, Eigen::Vector3d::UnitX(), 0.9}}}; }

TEST(evalGroundTruth3d, ErosionIsTheShareOfVisibleSurfaceVoxelsMappedFree) {
  OcTree16 map(kRes);
  for (int j = -5; j < 5; ++j) {
    for (int i = 0; i < 10; ++i) setFree(map, i, j);  // water up to the wall
  }
  for (int j = -5; j < -2; ++j) setFree(map, 10, j);   // the wall's voxels of rows −5…−3 cleared
  for (int j = -2; j < 5; ++j) setOccupied(map, 10, j);  // the rest mapped
  setFree(map, 12, 0);  // behind the wall: free, but not a surface voxel
  const GroundTruthReport r = evaluateAgainstScene(map, wallScene());
  // Surface voxels: column 10, the known rows −5…4 grown by 2 (T / res rounded up): rows −7…6.
  EXPECT_EQ(r.surface_voxels, 14U);
  EXPECT_EQ(r.surface_voxels_free, 3U);
  EXPECT_DOUBLE_EQ(r.erosion, 3.0 / 14.0);
  // Found: rows −3…5 (the mapped rows −2…4 and one either side, within T = 1.73 voxels).
  EXPECT_EQ(r.surface_voxels_found, 9U);
  // Nothing cleared: no erosion.
  OcTree16 intact(kRes);
  for (int j = -5; j < 5; ++j) {
    for (int i = 0; i < 10; ++i) setFree(intact, i, j);
    setOccupied(intact, 10, j);
  }
  const GroundTruthReport clean = evaluateAgainstScene(intact, wallScene());
  EXPECT_EQ(clean.surface_voxels, 14U);
  EXPECT_EQ(clean.surface_voxels_free, 0U);
  EXPECT_EQ(clean.erosion, 0.0);
  // Out of reach, an eroded voxel is no visible surface voxel: a range that stops short of rows
  // −5 and −4 (1.144 and 1.108 m away; row −3 is 1.081 m away).
  GroundTruthOptions near;
  near.max_range_m = 1.10;
  const GroundTruthReport short_range = evaluateAgainstScene(map, wallScene(), near);
  EXPECT_EQ(short_range.surface_voxels_free, 1U);
  EXPECT_EQ(short_range.surface_voxels, 6U);  // rows −3…2
  EXPECT_DOUBLE_EQ(short_range.erosion, 1.0 / 6.0);
}

TEST(evalGroundTruth3d, RecallAndErosionSplitByNearestSurface) {
  // Two walls seen from the origin: x = 1.05 m (primitive 0, mapped, three voxels cleared) and
  // y = 1.05 m (primitive 1, cleared wherever known).
  const Scene scene{{Plane{{1.05, 0.0, 0.0}, Eigen::Vector3d::UnitX(), 0.9},
                     Plane{{0.0, 1.05, 0.0}, Eigen::Vector3d::UnitY(), 0.9}}};
  OcTree16 map(kRes);
  for (int j = -5; j < 10; ++j) {
    for (int i = -5; i < 10; ++i) setFree(map, i, j);
  }
  for (int j = -5; j < -2; ++j) setFree(map, 10, j);
  for (int j = -2; j < 10; ++j) setOccupied(map, 10, j);
  for (int i = -5; i < 10; ++i) setFree(map, i, 10);
  const GroundTruthReport r = evaluateAgainstScene(map, scene);
  ASSERT_EQ(r.recall_by_surface.size(), 2U);
  const SurfaceRecall& x_wall = r.recall_by_surface[0];
  const SurfaceRecall& y_wall = r.recall_by_surface[1];
  EXPECT_EQ(x_wall.primitive, 0U);
  EXPECT_EQ(y_wall.primitive, 1U);
  EXPECT_EQ(x_wall.visible_voxels + y_wall.visible_voxels, r.surface_voxels);
  EXPECT_EQ(x_wall.found_voxels + y_wall.found_voxels, r.surface_voxels_found);
  EXPECT_EQ(x_wall.free_voxels + y_wall.free_voxels, r.surface_voxels_free);
  EXPECT_EQ(x_wall.free_voxels, 3U);   // rows −5…−3 of column 10
  EXPECT_EQ(y_wall.free_voxels, 15U);  // row 10, columns −5…9
  EXPECT_GT(x_wall.found_voxels, 10U);
  EXPECT_LE(y_wall.found_voxels, 2U);  // only next to the corner's occupied voxels
}

// With surface_box_m the surface voxels are sought in the caller's box, not in the map's own known
// box: a map known in one layer is scored against the wall's visible height too.
TEST(evalGroundTruth3d, SurfaceBoxMakesTheTruthIndependentOfTheMap) {
  OcTree16 map(kRes);
  for (int j = -5; j < 5; ++j) {
    for (int i = 0; i < 10; ++i) setFree(map, i, j);
    setOccupied(map, 10, j);
  }
  GroundTruthOptions options;
  options.max_range_m = 1.5;
  const GroundTruthReport plain = evaluateAgainstScene(map, wallScene(), options);
  options.surface_box_m = Eigen::AlignedBox3d(Eigen::Vector3d(-2.0, -2.0, -0.5), Eigen::Vector3d(2.0, 2.0, 0.5));
  const GroundTruthReport boxed = evaluateAgainstScene(map, wallScene(), options);
  EXPECT_GT(boxed.surface_voxels, 5 * plain.surface_voxels);  // ten layers instead of one, more rows
  EXPECT_LT(boxed.recall, 0.5 * plain.recall);
  EXPECT_EQ(boxed.occupied_voxels, plain.occupied_voxels);  // precision: the map's own voxels
  options.surface_box_m = Eigen::AlignedBox3d(Eigen::Vector3d(1.0, 1.0, 1.0), Eigen::Vector3d(0.0, 0.0, 0.0));
  EXPECT_THROW(evaluateAgainstScene(map, wallScene(), options), ValueError);
}

TEST(evalGroundTruth3d, SurfaceErrorIsTheMedianAndNinetiethPercentileOverOccupiedVoxels) {
  OcTree16 map(kRes);
  for (int j = 0; j < 5; ++j) setOccupied(map, 10, j);  // 5 on the wall: 0 m
  setOccupied(map, 9, 0);                               // 0.1 m
  setOccupied(map, 9, 1);                               // 0.1 m
  setOccupied(map, 8, 0);                               // 0.2 m
  setOccupied(map, 6, 0);                               // 0.4 m
  setOccupied(map, 0, 0);                               // 1.0 m: clutter, beyond the match distance
  const GroundTruthReport r = evaluateAgainstScene(map, wallScene());
  ASSERT_EQ(r.occupied_voxels, 10U);
  // Sorted: 0 0 0 0 0 0.1 0.1 0.2 0.4 1.0; median at rank 4.5: (0 + 0.1) / 2; p90 at rank 8.1:
  // 0.4 + 0.1 · (1.0 − 0.4).
  EXPECT_NEAR(r.surface_error_median_m, 0.05, 1e-9);
  EXPECT_NEAR(r.surface_error_p90_m, 0.46, 1e-9);
  // The wall-position error leaves the clutter out; the surface error does not.
  EXPECT_EQ(r.matched_voxels, 9U);
  EXPECT_NEAR(r.mean_distance_m, 0.8 / 9.0, 1e-9);
  // An odd count: the middle value itself; a single voxel: its own distance for both.
  setOccupied(map, 5, 0);  // 0.5 m
  const GroundTruthReport odd = evaluateAgainstScene(map, wallScene());
  ASSERT_EQ(odd.occupied_voxels, 11U);
  EXPECT_NEAR(odd.surface_error_median_m, 0.1, 1e-9);
  EXPECT_NEAR(odd.surface_error_p90_m, 0.5, 1e-9);  // rank 9: the tenth value
  OcTree16 single(kRes);
  setOccupied(single, 7, 0);
  const GroundTruthReport one = evaluateAgainstScene(single, wallScene());
  EXPECT_NEAR(one.surface_error_median_m, 0.3, 1e-9);
  EXPECT_NEAR(one.surface_error_p90_m, 0.3, 1e-9);
  // No occupied voxel: 0.
  OcTree16 water(kRes);
  setFree(water, 0, 0);
  const GroundTruthReport none = evaluateAgainstScene(water, wallScene());
  EXPECT_EQ(none.surface_error_median_m, 0.0);
  EXPECT_EQ(none.surface_error_p90_m, 0.0);
}

// Occupied voxels off the surface are split by where they lie: in front of the wall (a shell in
// the water, reached from the sensor through no surface) or behind it.
TEST(evalGroundTruth3d, OffSurfaceVoxelsAreSplitIntoWaterAndBehind) {
  OcTree16 map(kRes);
  setOccupied(map, 10, 0);  // on the wall
  setOccupied(map, 9, 0);   // 0.1 m in front: within T, on the surface
  setOccupied(map, 8, 0);   // 0.2 m in front: in the water
  setOccupied(map, 6, 1);   // 0.4 m in front: in the water
  setOccupied(map, 13, 0);  // 0.3 m behind the wall
  setOccupied(map, 15, 2);  // 0.5 m behind the wall
  const GroundTruthReport r = evaluateAgainstScene(map, wallScene());
  ASSERT_EQ(r.occupied_voxels, 6U);
  EXPECT_EQ(r.occupied_on_surface, 2U);
  EXPECT_EQ(r.occupied_in_water, 2U);
}

/// A map of water in front of the wall over ten layers (z centres 0.05 … 0.95 m), rows −1…0.
OcTree16 waterColumnMap() {
  OcTree16 map(kRes);
  for (int k = 0; k < 10; ++k) {
    for (int j = -1; j < 1; ++j) {
      for (int i = 0; i < 10; ++i) setFree(map, i, j, k);
    }
  }
  return map;
}

/// How many of the wall's surface voxels of waterColumnMap (column 10, rows −3…2, layers 0…9) a
/// sonar at the origin whose frame maps to the map by `rotation` has within ±10° of elevation,
/// counted voxel by voxel.
std::size_t seenWithin10Degrees(const Eigen::Matrix3d& rotation) {
  std::size_t seen = 0;
  for (int k = 0; k < 10; ++k) {
    for (int j = -3; j < 3; ++j) {
      const Eigen::Vector3d center(1.05, (j + 0.5) * kRes, (k + 0.5) * kRes);
      const double elevation_rad = std::asin((rotation.transpose() * center.normalized()).z());
      seen += std::abs(elevation_rad) <= 10.0 * kDegree ? 1 : 0;
    }
  }
  return seen;
}

TEST(evalGroundTruth3d, SurfaceAboveTheApertureIsNotSeenUntilTheSonarTilts) {
  const OcTree16 map = waterColumnMap();
  GroundTruthOptions options;
  options.max_range_m = 5.0;
  // No field of view: the wall's column 10, rows −3…2 (known rows grown by 2), ten layers.
  const GroundTruthReport all = evaluateAgainstScene(map, wallScene(), options);
  EXPECT_EQ(all.surface_voxels, 60U);
  // An upright sonar with a 20° aperture (±10°) sees layers 0 (2.7° up at most) and 1 (≤ 8.1°),
  // not layer 2 (≥ 13.0°).
  options.sensor_orientations = {Eigen::Matrix3d::Identity()};
  options.vertical_aperture_rad = 20.0 * kDegree;
  EXPECT_EQ(seenWithin10Degrees(Eigen::Matrix3d::Identity()), 12U);
  const GroundTruthReport level = evaluateAgainstScene(map, wallScene(), options);
  EXPECT_EQ(level.surface_voxels, 12U);
  // Tilted 30° up (about the map's y axis: a negative angle raises +x): layers 4…8 or so, none
  // of the two the level sonar sees; the voxel 27.6° up (layer 5, row 0) now counts.
  const Eigen::Matrix3d up30 = Eigen::AngleAxisd(-30.0 * kDegree, Eigen::Vector3d::UnitY()).toRotationMatrix();
  ASSERT_NEAR((up30 * Eigen::Vector3d::UnitX()).z(), 0.5, 1e-12);
  const Eigen::Vector3d layer5(1.05, 0.05, 0.55);
  EXPECT_GT(std::asin(layer5.normalized().z()), 10.0 * kDegree);
  EXPECT_LT(std::abs(std::asin((up30.transpose() * layer5.normalized()).z())), 10.0 * kDegree);
  const std::size_t tilted_seen = seenWithin10Degrees(up30);
  ASSERT_GT(tilted_seen, 12U);
  options.sensor_orientations = {up30};
  EXPECT_EQ(evaluateAgainstScene(map, wallScene(), options).surface_voxels, tilted_seen);
  // Both sonars at the same place: the union (disjoint).
  options.sensor_positions_m = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  options.sensor_orientations = {Eigen::Matrix3d::Identity(), up30};
  EXPECT_EQ(evaluateAgainstScene(map, wallScene(), options).surface_voxels, tilted_seen + 12U);
  // A sonar upside down sees what an upright one sees (the aperture is symmetric) …
  options.sensor_positions_m = {Eigen::Vector3d::Zero()};
  options.sensor_orientations = {Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix()};
  EXPECT_EQ(evaluateAgainstScene(map, wallScene(), options).surface_voxels, 12U);
  // … and a sonar on its side (scan plane x–z) sees the rows within 10° of that plane, every
  // layer of rows y = ±0.05 and ±0.15 m, none of y = ±0.25 m.
  const Eigen::Matrix3d side = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_EQ(seenWithin10Degrees(side), 40U);
  options.sensor_orientations = {side};
  EXPECT_EQ(evaluateAgainstScene(map, wallScene(), options).surface_voxels, 40U);
}

TEST(evalGroundTruth3d, FieldOfViewOptionsAreChecked) {
  OcTree16 map(kRes);
  setFree(map, 0, 0);
  GroundTruthOptions options;
  options.vertical_aperture_rad = 0.5;  // without orientations
  EXPECT_THROW(evaluateAgainstScene(map, wallScene(), options), ValueError);
  options = {};
  options.sensor_orientations = {Eigen::Matrix3d::Identity()};  // without an aperture
  EXPECT_THROW(options.validate(), ValueError);
  options.vertical_aperture_rad = 0.5;
  EXPECT_NO_THROW(options.validate());
  options.sensor_orientations.push_back(Eigen::Matrix3d::Identity());  // two for one position
  EXPECT_THROW(options.validate(), ValueError);
  options.sensor_orientations = {2.0 * Eigen::Matrix3d::Identity()};  // not a rotation
  EXPECT_THROW(options.validate(), ValueError);
  options.sensor_orientations = {Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal()};  // a reflection
  EXPECT_THROW(options.validate(), ValueError);
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(0, 1) = std::nan("");
  options.sensor_orientations = {nan};
  EXPECT_THROW(options.validate(), ValueError);
  options.sensor_orientations = {Eigen::Matrix3d::Identity()};
  for (const double aperture_rad : {0.0, -0.1, std::numbers::pi, 4.0, std::nan("")}) {
    options.vertical_aperture_rad = aperture_rad;
    EXPECT_THROW(options.validate(), ValueError) << aperture_rad;
  }
}

/// Sloped planes, yawed boxes (one seen from inside), cylinders, at awkward positions.
Scene mixedScene() {
  Scene scene;
  scene.primitives.push_back(Plane{{0.0, 0.0, -0.8}, Eigen::Vector3d(0.3, -0.2, 1.0), 0.5});
  scene.primitives.push_back(Plane{{0.9, 0.1, 0.0}, Eigen::Vector3d(1.0, 0.7, 0.05), 0.9});
  scene.primitives.push_back(Box{{0.2, -0.3, 0.1}, {0.7, 0.45, 0.5}, 0.52, 0.8});
  scene.primitives.push_back(Box{{0.0, 0.0, 0.0}, {2.3, 1.9, 1.7}, -0.2, 0.9});
  scene.primitives.push_back(Cylinder{-0.5, 0.4, 0.17, -0.6, 0.45, 0.85});
  scene.primitives.push_back(Cylinder{0.55, 0.6, 0.33, -0.2, 0.1, 0.85});
  return scene;
}

std::vector<Key16> sorted(std::vector<Key16> keys) {
  std::sort(keys.begin(), keys.end(), [](const Key16& a, const Key16& b) { return a.k < b.k; });
  return keys;
}

TEST(evalGroundTruth3d, HierarchicalSurfaceVoxelsEqualTheBruteForce) {
  const Scene scene = mixedScene();
  for (const double res : {0.05, 0.1, 0.037}) {
    const KeyCoder<16> coder(res);
    SCOPED_TRACE("resolution " + std::to_string(res));
    // Boxes of every shape: odd sizes, one voxel thick, off the origin, a single voxel.
    const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes{
        {{-1.5, -1.3, -1.1}, {1.6, 1.2, 1.0}},
        {{-0.37, -1.0, 0.02}, {1.4, 0.9, 0.02}},
        {{0.3, 0.25, -0.9}, {0.3, 0.25, 0.9}},
        {{-0.1, 0.55, -0.2}, {1.2, 0.61, 0.33}},
        {{0.29, 0.6, -0.2}, {0.29, 0.6, -0.2}},
    };
    std::size_t total = 0;
    for (const auto& [low_m, high_m] : boxes) {
      const Key16 lo = coder.keyOfChecked(low_m), hi = coder.keyOfChecked(high_m);
      const std::vector<Key16> brute = detail::surfaceVoxelsBruteForce(coder, scene, lo, hi);
      const std::vector<Key16> fast = detail::surfaceVoxels(coder, scene, lo, hi);
      EXPECT_EQ(fast.size(), brute.size());
      EXPECT_TRUE(sorted(fast) == sorted(brute));
      total += brute.size();
    }
    EXPECT_GT(total, 1000U);
    // The brute force is one voxel tested directly, at its centre nudged towards its lower corner.
    const Key16 lo = coder.keyOfChecked({-1.5, -1.3, -1.1}), hi = coder.keyOfChecked({1.6, 1.2, 1.0});
    std::size_t direct = 0;
    for (int z = lo[2]; z <= hi[2]; ++z) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const Key16 key{{static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint16_t>(z)}};
          const Eigen::Vector3d probe_m = coder.centerOf(key).array() - 1e-6 * res;
          direct += distanceToSurface(scene, probe_m) <= 0.5 * res ? 1 : 0;
        }
      }
    }
    EXPECT_EQ(detail::surfaceVoxels(coder, scene, lo, hi).size(), direct);
  }
  // An empty box or scene has none.
  const KeyCoder<16> coder(0.1);
  // A level plane on the face between two layers of voxels counts in one layer, the one above
  // (its half-open interval holds the plane), wherever the face lies: at z = 0 the two centres
  // are exactly res / 2 away, at z = 2.5 m rounding puts one a hair nearer.
  for (const double level_m : {0.0, 2.5, -1.3}) {
    Scene level;
    level.primitives.push_back(Plane{{0.0, 0.0, level_m}, Eigen::Vector3d::UnitZ(), 1.0});
    const Key16 lo = coder.keyOfChecked({-0.45, -0.45, level_m - 0.45}), hi = coder.keyOfChecked({0.45, 0.45, level_m + 0.45});
    const std::vector<Key16> layer = detail::surfaceVoxels(coder, level, lo, hi);
    EXPECT_EQ(layer.size(), 100U) << level_m;
    for (const Key16& key : layer) EXPECT_NEAR(coder.centerOf(key).z(), level_m + 0.05, 1e-9) << level_m;
    EXPECT_TRUE(sorted(detail::surfaceVoxelsBruteForce(coder, level, lo, hi)) == sorted(layer)) << level_m;
  }
  const Key16 a = coder.keyOfChecked({0.0, 0.0, 0.0}), b = coder.keyOfChecked({1.0, 1.0, 1.0});
  EXPECT_TRUE(detail::surfaceVoxels(coder, scene, b, a).empty());
  EXPECT_TRUE(detail::surfaceVoxels(coder, Scene{}, a, b).empty());
}

TEST(evalGroundTruth3d, HierarchicalSurfaceVoxelsOfTheQuayEqualTheBruteForce) {
  const Scene scene = builtinScene("quay3d");
  const KeyCoder<16> coder(0.05);
  const Key16 lo = coder.keyOfChecked({-4.0, -4.0, -5.9}), hi = coder.keyOfChecked({4.0, 4.0, 0.1});
  const std::vector<Key16> brute = detail::surfaceVoxelsBruteForce(coder, scene, lo, hi);
  EXPECT_GT(brute.size(), 50000U);
  EXPECT_TRUE(sorted(detail::surfaceVoxels(coder, scene, lo, hi)) == sorted(brute));
}

/// The quay3d scene's surface voxels in x, y ∈ [−3.5, 3.5] m, z ∈ [−5.8, −0.5] m (below the
/// water surface) at 0.1 m.
std::vector<Key16> quaySurface(const OcTree16& map, const Scene& scene) {
  const Key16 lo = map.coder().keyOfChecked({-3.5, -3.5, -5.8}), hi = map.coder().keyOfChecked({3.5, 3.5, -0.5});
  return detail::surfaceVoxelsBruteForce(map.coder(), scene, lo, hi);
}

TEST(evalGroundTruth3d, PerfectAndErodedMapsOfTheQuay) {
  const Scene scene = builtinScene("quay3d");
  OcTree16 perfect(kRes), eroded(kRes);
  const std::vector<Key16> surface = quaySurface(perfect, scene);
  ASSERT_GT(surface.size(), 4000U);
  for (const Key16& key : surface) {
    perfect.updateNode(key, 4.0F);
    eroded.updateNode(key, -2.0F);
  }
  // Within 3 m of a sensor 2.5 m deep above the origin every surface voxel lies inside the mapped box.
  GroundTruthOptions options;
  options.sensor_positions_m = {Eigen::Vector3d(0.0, 0.0, -2.5)};
  options.max_range_m = 3.0;
  const GroundTruthReport good = evaluateAgainstScene(perfect, scene, options);
  EXPECT_EQ(good.precision, 1.0);
  EXPECT_EQ(good.recall, 1.0);
  EXPECT_EQ(good.erosion, 0.0);
  EXPECT_LE(good.surface_error_median_m, 0.05);
  EXPECT_LE(good.surface_error_p90_m, 0.05 + 1e-12);
  EXPECT_GT(good.surface_voxels, 1000U);
  // Seabed, quay, piles, boulder and pontoon all have matched voxels.
  std::vector<std::size_t> primitives;
  for (const SurfaceOffset& s : good.surfaces) primitives.push_back(s.primitive);
  EXPECT_EQ(primitives, (std::vector<std::size_t>{1, 2, 3, 4, 5, 6, 7}));
  const GroundTruthReport bad = evaluateAgainstScene(eroded, scene, options);
  EXPECT_EQ(bad.surface_voxels, good.surface_voxels);
  EXPECT_EQ(bad.surface_voxels_free, bad.surface_voxels);
  EXPECT_EQ(bad.erosion, 1.0);
  EXPECT_EQ(bad.recall, 0.0);
  // With the Micron's 35° aperture an upright sonar there cannot see the seabed within 3 m
  // (2.2–2.9 m below it: 47° down and more) but sees the pontoon's side and underside.
  options.sensor_orientations = {Eigen::Matrix3d::Identity()};
  options.vertical_aperture_rad = 35.0 * kDegree;
  const GroundTruthReport view = evaluateAgainstScene(eroded, scene, options);
  EXPECT_GT(view.surface_voxels, 100U);
  EXPECT_LT(view.surface_voxels, bad.surface_voxels / 2);
  EXPECT_EQ(view.erosion, 1.0);
}

}  // namespace
}  // namespace sonarmap
