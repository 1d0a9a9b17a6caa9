// The joint inversion (mapping/volume_inversion.hpp): beams whose range cells hold the forward
// model's echo of a pile and a wall (with speckle) from a few viewpoints give back the pile and the
// wall; a voxel a beam heard as water is never occupied, though other beams' loud cells hold it;
// the map does not depend on the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "sonarmap/acoustics/forward_model.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/volume_inversion.hpp"

namespace sonarmap {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kRes = 0.05;
const TransducerPattern kPattern{{3.0 * kDeg, 2.0}, {35.0 * kDeg, 2.0}};

/// A head at `position` whose sonar frame (x ahead, y starboard, z down) is pitched `tilt_rad`
/// down in the map frame (x north, y west, z up).
Eigen::Isometry3d head(const Eigen::Vector3d& position, double tilt_rad) {
  Eigen::Isometry3d sonar_to_map = Eigen::Isometry3d::Identity();
  sonar_to_map.translation() = position;
  sonar_to_map.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal() *
                          Eigen::AngleAxisd(-tilt_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return sonar_to_map;
}

/// The scene's voxel centres (map frame): a pile of radius 0.15 m at the origin (its side facing
/// south, x < 0) and a wall facing south at x = 2 m, y within ±1.5 m; both from z = −1.5 to 0.5 m.
std::vector<Eigen::Vector3d> scene(const OcTree16& map, bool pile, bool wall) {
  std::set<std::uint64_t> codes;
  for (double z = -1.5; z <= 0.5; z += 0.5 * kRes) {
    if (pile) {
      for (double a = 90.0 * kDeg; a <= 270.0 * kDeg; a += 2.0 * kDeg) {
        codes.insert(mortonCode(*map.coder().keyOf(Eigen::Vector3d(0.15 * std::cos(a), 0.15 * std::sin(a), z))));
      }
    }
    if (wall) {
      for (double y = -1.5; y <= 1.5; y += 0.5 * kRes) codes.insert(mortonCode(*map.coder().keyOf(Eigen::Vector3d(2.0, y, z))));
    }
  }
  std::vector<Eigen::Vector3d> centres;
  for (const std::uint64_t code : codes) centres.push_back(map.coder().centerOf(keyOfMortonCode<16>(code)));
  return centres;
}

/// The beams of a few viewpoints south of the scene, scanning ±35° about north, each cell the
/// forward model's mean (water 1 plus each scene voxel's ScattererGain times `rho`) under speckle
/// (the mean of four exponential bins); added to `inversion`.
void viewScene(const std::vector<Eigen::Vector3d>& voxels, double rho, VolumeInversion& inversion, OcTree16& map) {
  const ScattererGain gain(kPattern, kRes * kRes);
  std::mt19937_64 random(11);
  std::exponential_distribution<double> speckle(1.0);
  const std::size_t cells = 100;  // 5 m
  for (const double y : {-1.5, 0.0, 1.5}) {
    for (const double z : {0.3, -0.8}) {
      for (const double tilt_deg : {0.0, 20.0}) {
        const Eigen::Isometry3d sonar_to_map = head(Eigen::Vector3d(-2.5, y, z), tilt_deg * kDeg);
        for (double bearing_deg = -35.0; bearing_deg <= 35.0; bearing_deg += 1.5) {
          const double bearing_rad = bearing_deg * kDeg;
          const Eigen::Matrix3d map_to_beam =
              (sonar_to_map.linear() * Eigen::AngleAxisd(bearing_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix()).transpose();
          std::vector<double> mean(cells, 1.0);
          for (const Eigen::Vector3d& voxel : voxels) {
            const Eigen::Vector3d v = map_to_beam * (voxel - sonar_to_map.translation());
            const double r = v.norm();
            const auto k = static_cast<std::size_t>(r / kRes);
            if (k >= cells) continue;
            mean[k] += rho * gain(std::atan2(v.y(), v.x()), std::asin(v.z() / r), r);
          }
          std::vector<float> power(cells);
          std::size_t first_echo = cells;
          for (std::size_t k = 0; k < cells; ++k) {
            double sum = 0.0;
            for (int i = 0; i < 4; ++i) sum += speckle(random);
            power[k] = static_cast<float>(mean[k] * sum / 4.0);
            if (mean[k] >= 2.0) first_echo = std::min(first_echo, k);
          }
          const double water_range_m = std::max(0.0, static_cast<double>(first_echo) * kRes - kRes);
          inversion.addBeam({sonar_to_map, bearing_rad, power, water_range_m, water_range_m, std::nullopt, std::nullopt}, map);
        }
      }
    }
  }
  inversion.flush(map);
}

std::vector<Eigen::Vector3d> occupiedVoxels(const OcTree16& map) {
  std::vector<Eigen::Vector3d> occupied;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (!map.model().isOccupied(leaf.log_odds)) return;
    leaf.forEachVoxel([&](const Key16& key) { occupied.push_back(map.coder().centerOf(key)); });
  });
  return occupied;
}

/// The share of `points` with one of `others` within `distance_m`.
double shareNear(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& others, double distance_m) {
  if (points.empty()) return 0.0;
  std::size_t near = 0;
  for (const Eigen::Vector3d& point : points) {
    near += std::any_of(others.begin(), others.end(), [&](const Eigen::Vector3d& o) { return (o - point).norm() <= distance_m; });
  }
  return static_cast<double>(near) / static_cast<double>(points.size());
}

TEST(mappingVolumeInversion, RecoversAPileAndAWallFromAFewViews) {
  OcTree16 map(kRes);
  VolumeInversion inversion(kPattern, kRes, VolumeInversionOptions{});
  const std::vector<Eigen::Vector3d> pile = scene(map, true, false), wall = scene(map, false, true);
  std::vector<Eigen::Vector3d> both = pile;
  both.insert(both.end(), wall.begin(), wall.end());
  viewScene(both, 300.0, inversion, map);
  map.updateInnerOccupancy();
  const std::vector<Eigen::Vector3d> occupied = occupiedVoxels(map);
  ASSERT_GT(occupied.size(), 100U);
  // Precision: most occupied voxels lie on the pile or the wall (within 1.5 voxels; 0.80 when written).
  EXPECT_GT(shareNear(occupied, both, 1.5 * kRes), 0.7);
  // Recall of each: most of its voxels have an occupied voxel within 1.5 voxels (0.99 and 0.83).
  EXPECT_GT(shareNear(pile, occupied, 1.5 * kRes), 0.9);
  EXPECT_GT(shareNear(wall, occupied, 1.5 * kRes), 0.7);
  EXPECT_GT(inversion.stats().free, 1000U);
}

/// Views of a point `v` (map frame) from eight heads 2 m around it, 20° above and below in turn,
/// each beam's axis on it and its cell holding the point (2.025 m, mid-cell) loud (+50 dB), water
/// before; with `water_beam`, also a head 4 m south of it (v's echo there a quarter of the others': 1/r²) whose beam's axis runs through it
/// and hears water up to 4.4 m, its cell at v a speckle peak. Returns the map.
OcTree16 viewPoint(const Eigen::Vector3d& v, bool water_beam) {
  OcTree16 map(kRes);
  VolumeInversionOptions options;
  VolumeInversion inversion(kPattern, kRes, options);
  const std::size_t cells = 100;
  const auto add = [&](const Eigen::Vector3d& position, const std::vector<float>& power, double water_range_m) {
    // The head pitched down towards v, then turned to it about its own z: its sonar frame is FRD
    // over the map's NWU, so bearing β looks along (cos β, −sin β) horizontally.
    const Eigen::Vector3d to = v - position;
    const double tilt_rad = std::atan2(-to.z(), to.head<2>().norm());
    Eigen::Isometry3d sonar_to_map = head(position, 0.0);
    sonar_to_map.linear() = sonar_to_map.linear() * Eigen::AngleAxisd(std::atan2(-to.y(), to.x()), Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(-tilt_rad, Eigen::Vector3d::UnitY());
    inversion.addBeam({sonar_to_map, 0.0, power, water_range_m, water_range_m, std::nullopt, std::nullopt}, map);
  };
  if (water_beam) {  // its cell at v a speckle peak (+2.8 dB), under the loud level: water, before its first echo
    std::vector<float> power(cells, 1.0f);
    power[80] = 1.9f;
    add(v - Eigen::Vector3d(4.025, 0.0, 0.0), power, 4.4);
  }
  for (int i = 0; i < 8; ++i) {
    const double a = (22.5 + 45.0 * i) * kDeg;
    const double e = (i % 2 == 0 ? 20.0 : -20.0) * kDeg;  // from above and from below, alternately
    const Eigen::Vector3d position = v + 2.025 * Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
    std::vector<float> power(cells, 1.0f);
    power[static_cast<std::size_t>((v - position).norm() / kRes)] = 1.0e5f;
    add(position, power, 1.9);
  }
  inversion.flush(map);
  map.updateInnerOccupancy();
  return map;
}

TEST(mappingVolumeInversion, AVoxelHeardAsWaterIsNeverOccupied) {
  // Eight beams' loud cells meet at v: alone they make it occupied; a ninth beam heard water there
  // in its loud core, before its first echo, and v is free.
  const Eigen::Vector3d v(0.0, 0.0, 0.0);
  OcTree16 probe(kRes);
  const Key16 key = *probe.coder().keyOf(v);
  const Eigen::Vector3d centre = probe.coder().centerOf(key);
  const OcTree16 without = viewPoint(centre, false);
  ASSERT_TRUE(without.search(key).has_value());
  EXPECT_TRUE(without.model().isOccupied(*without.search(key)));
  const OcTree16 with = viewPoint(centre, true);
  ASSERT_TRUE(with.search(key).has_value());
  EXPECT_EQ(with.model().classify(*with.search(key)), Occupancy::kFree);
}

TEST(mappingVolumeInversion, TheMapDoesNotDependOnTheThreadCount) {
  std::vector<std::vector<std::pair<std::uint64_t, float>>> leaves;
  for (const unsigned threads : {1U, 2U}) {
    OcTree16 map(kRes);
    VolumeInversionOptions options;
    options.window_pairs = 200000;  // several windows
    VolumeInversion inversion(kPattern, kRes, options, threads);
    const std::vector<Eigen::Vector3d> voxels = scene(map, true, true);
    viewScene(voxels, 300.0, inversion, map);
    EXPECT_GT(inversion.stats().windows, 1U);
    auto& mine = leaves.emplace_back();
    map.forEachLeaf([&](const LeafView<16>& leaf) { mine.emplace_back(mortonCode(leaf.key), leaf.log_odds); });
  }
  ASSERT_GT(leaves[0].size(), 1000U);
  EXPECT_EQ(leaves[0], leaves[1]);
}

TEST(mappingVolumeInversion, InvalidParametersAreRefused) {
  VolumeInversionOptions options;
  options.iterations = 0;
  EXPECT_THROW(VolumeInversion(kPattern, kRes, options), ValueError);
  EXPECT_THROW(VolumeInversion(kPattern, 0.0, VolumeInversionOptions{}), ValueError);
  EXPECT_THROW(VolumeInversion(kPattern, kRes, VolumeInversionOptions{}, 0), ValueError);
}

}  // namespace
}  // namespace sonarmap
