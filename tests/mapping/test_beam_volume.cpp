// The beam-volume inverse sensor model: a single beam's free cone and shell against a
// brute-force classification of the voxels, evidence shares, one update per voxel and sweep, the
// protection of occupied cells from a cone's quiet outer part, and a tilted mounting.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <unordered_set>
#include <vector>

#include "sonarmap/mapping/sonar_mapper.hpp"
#include "polar_fixtures.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "sonarmap/raycast/dda.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kVoxel = 0.02;
const BeamShape kMicron{3.0 * kDegree, 35.0 * kDegree};

using KeySet = std::unordered_set<Key16, KeyHash<16>>;
using testing::tiltedPose;

/// The cells the planned free rays cross (as the mapper's traversal marks them).
KeySet crossedCells(const KeyCoder<16>& coder, const std::vector<FreeRay>& rays) {
  KeySet cells;
  for (const FreeRay& ray : rays) {
    traverseDDA(coder, ray.start_m, ray.end_m, [&](const Key16& key) { cells.insert(key); });
  }
  return cells;
}

/// Range, bearing and elevation of a map point in the sonar frame of `sonar_to_map`.
struct SonarPolar {
  double range_m, bearing_rad, elevation_rad;
};
SonarPolar toSonar(const Eigen::Isometry3d& sonar_to_map, const Eigen::Vector3d& point_m) {
  const Eigen::Vector3d v = sonar_to_map.inverse() * point_m;
  return {v.norm(), std::atan2(v.y(), v.x()), std::asin(v.z() / v.norm())};
}

// Every voxel whose centre lies well inside the cone (a voxel diagonal from its surface) is
// crossed; none whose centre lies a voxel diagonal outside it is. Checked on a tilted, turned pose.
TEST(mappingBeamVolume, SingleBeamFreeConeMatchesBruteForce) {
  const KeyCoder<16> coder(kVoxel);
  const Eigen::Isometry3d pose = tiltedPose({0.31, -0.17, 0.05}, 0.2, -0.4, 0.7);
  const PlannedBeam beam{pose, 40.0 * kDegree, 1.4, 1.5, true};
  // 12° wide, so that many voxels lie a voxel diagonal inside the cone's sides.
  const BeamShape shape{12.0 * kDegree, 35.0 * kDegree};
  std::vector<FreeRay> rays;
  planFreeRays({beam}, shape, kVoxel, rays);
  const KeySet crossed = crossedCells(coder, rays);
  const double diagonal_m = std::sqrt(3.0) * kVoxel;
  std::size_t inside = 0, inside_crossed = 0, outside_crossed = 0;
  const Key16 centre = *coder.keyOf(pose.translation());
  const int reach = static_cast<int>(std::ceil(1.6 / kVoxel));
  for (int dz = -reach; dz <= reach; ++dz) {
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const Key16 key{{static_cast<std::uint16_t>(centre[0] + dx), static_cast<std::uint16_t>(centre[1] + dy),
                         static_cast<std::uint16_t>(centre[2] + dz)}};
        const SonarPolar p = toSonar(pose, coder.centerOf(key));
        if (p.range_m < 1e-9) continue;
        const double bearing_off_m = std::abs(std::remainder(p.bearing_rad - beam.bearing_rad, 2.0 * std::numbers::pi)) -
                                     0.5 * shape.width_rad;
        const double elevation_off = std::abs(p.elevation_rad) - 0.5 * shape.vertical_aperture_rad;
        // Angular distances to the cone's sides, as lengths at the point's range.
        const double side_m = std::max(bearing_off_m * p.range_m * std::cos(p.elevation_rad), elevation_off * p.range_m);
        const bool well_inside = p.range_m < beam.free_range_m - diagonal_m && side_m < -diagonal_m;
        const bool well_outside = p.range_m > beam.free_range_m + diagonal_m || side_m > diagonal_m;
        const bool is_crossed = crossed.contains(key);
        if (well_inside) {
          ++inside;
          inside_crossed += is_crossed ? 1 : 0;
        }
        if (well_outside && is_crossed) ++outside_crossed;
      }
    }
  }
  ASSERT_GT(inside, 5000U);
  EXPECT_EQ(outside_crossed, 0U);
  // Rays at most a voxel apart can pass a voxel between them; measured: none is missed here.
  EXPECT_GE(static_cast<double>(inside_crossed) / static_cast<double>(inside), 0.999) << inside_crossed << " of " << inside;
}

// The shell: every point at the hit range within the beam's width and aperture, at most a voxel
// apart, and the whole aperture spanned (nothing carves a lone beam).
TEST(mappingBeamVolume, SingleBeamShellSpansWidthAndAperture) {
  const Eigen::Isometry3d pose = tiltedPose({0.0, 0.0, 0.0}, 0.0, 0.3, 0.0);
  const PlannedBeam beam{pose, 10.0 * kDegree, 1.9, 2.0, true};
  std::vector<HitPoint> hits;
  planArcs({beam}, kMicron, kVoxel, 0.03, ArcEvidence::kWholeArc, hits);
  ASSERT_FALSE(hits.empty());
  double lowest = 1.0, highest = -1.0;
  for (const HitPoint& hit : hits) {
    const SonarPolar p = toSonar(pose, hit.point_m);
    EXPECT_NEAR(p.range_m, 2.0, 1e-9);
    EXPECT_LE(std::abs(p.bearing_rad - beam.bearing_rad), 0.5 * kMicron.width_rad + 1e-9);
    lowest = std::min(lowest, p.elevation_rad);
    highest = std::max(highest, p.elevation_rad);
    EXPECT_EQ(hit.weight, 1.0);
  }
  EXPECT_NEAR(lowest, -17.5 * kDegree, 1e-9);
  EXPECT_NEAR(highest, 17.5 * kDegree, 1e-9);
  // Points per elevation row and rows at most a voxel apart: 2 m × 35° = 1.22 m → ≥ 62 rows.
  EXPECT_GE(hits.size(), 62U * 2U);
}

// A vertical face: a quay wall at x = 2 m seen by a cone tilted 25° down from 1 m above the seabed.
// Its nearest point lies on the cone's most horizontal direction (7.5° down), 2 / cos 7.5° away,
// and that is the echo's range. As a shell its points stand up to 2 (1 − cos 35°) = 0.36 m in
// front of the wall; as a vertical face every point lies on the wall, across the whole aperture
// while the echo lasts, and no farther than its end.
TEST(mappingBeamVolume, VerticalFaceObstaclesLieOnTheWallUpToTheEchosEnd) {
  const Eigen::Isometry3d pose = tiltedPose({0.0, 0.0, 0.0}, 0.0, 25.0 * kDegree, 0.0);  // looking down 25°
  ASSERT_LT((pose.linear() * Eigen::Vector3d::UnitX()).z(), -0.4);
  const double wall_m = 2.0;
  const double range_m = wall_m / std::cos(7.5 * kDegree);
  PlannedBeam beam{pose, 0.0, range_m - 0.03, range_m, true};
  std::vector<HitPoint> shell, face;
  planArcs({beam}, kMicron, kVoxel, 0.03, ArcEvidence::kBeamPattern, shell, ObstacleSurface::kShell);
  planArcs({beam}, kMicron, kVoxel, 0.03, ArcEvidence::kBeamPattern, face, ObstacleSurface::kVertical);
  double shell_front_m = 0.0, face_low_m = 0.0, face_high_m = -1.0;
  for (const HitPoint& hit : shell) shell_front_m = std::max(shell_front_m, wall_m - hit.point_m.x());
  for (const HitPoint& hit : face) {
    EXPECT_NEAR(hit.point_m.x(), wall_m, 2e-3);  // a cylinder about the sonar: 1 − cos 1.5° off at the sides
    face_low_m = std::min(face_low_m, hit.point_m.z());
    face_high_m = std::max(face_high_m, hit.point_m.z());
  }
  EXPECT_GT(shell_front_m, 0.3);
  // Without the echo's end, the whole aperture: from 2 tan 7.5° to 2 tan 42.5° below the sonar.
  EXPECT_NEAR(face_high_m, -wall_m * std::tan(7.5 * kDegree), 0.01);
  EXPECT_NEAR(face_low_m, -wall_m * std::tan(42.5 * kDegree), 0.01);
  // Rows at most a voxel apart on the wall, and the columns across the width (≥ 2 per row).
  EXPECT_GE(face.size(), 2U * static_cast<std::size_t>((face_high_m - face_low_m) / kVoxel));
  // An echo that ends 0.2 m after its onset: the wall reaches no farther (plus the tolerance).
  beam.hit_end_m = range_m + 0.2;
  planArcs({beam}, kMicron, kVoxel, 0.03, ArcEvidence::kBeamPattern, face, ObstacleSurface::kVertical);
  ASSERT_FALSE(face.empty());
  for (const HitPoint& hit : face) {
    EXPECT_NEAR(hit.point_m.x(), wall_m, 2e-3);  // a cylinder about the sonar: 1 − cos 1.5° off at the sides
    EXPECT_LE(hit.point_m.norm(), range_m + 0.2 + 0.03 + 1e-9);
  }
  // A head looking straight down, without an echo's end: the face only along directions within
  // 75° of the horizontal, so its points stay within 1 / cos 75° of its distance (a bounded set).
  const Eigen::Isometry3d down = tiltedPose({0.0, 0.0, 0.0}, 0.0, 80.0 * kDegree, 0.0);
  const PlannedBeam below{down, 0.0, 1.97, 2.0, true};
  planArcs({below}, kMicron, kVoxel, 0.03, ArcEvidence::kBeamPattern, face, ObstacleSurface::kVertical);
  ASSERT_FALSE(face.empty());
  EXPECT_LT(face.size(), 20000U);
  for (const HitPoint& hit : face) {
    EXPECT_LE(std::abs(std::asin(hit.point_m.z() / hit.point_m.norm())), 75.0 * kDegree + 1e-9);
  }
}

// Another beam that saw water farther carves the part of the shell inside its cone; the evidence
// of what is left is shared as ArcEvidence says.
TEST(mappingBeamVolume, ShellIsCarvedAndEvidenceShared) {
  const Eigen::Isometry3d level = Eigen::Isometry3d::Identity();
  // Same bearing, the second sonar 0.5 m higher and tilted up 10°: its cone (−7.5° … 27.5° from
  // 0.5 m up) covers the upper part of the first beam's shell at 2 m and saw water to 3 m.
  const PlannedBeam first{level, 0.0, 1.9, 2.0, true};
  const PlannedBeam second{tiltedPose({0.0, 0.0, 0.5}, 0.0, -10.0 * kDegree, 0.0), 0.0, 2.9, 3.0, true};
  std::vector<HitPoint> hits;
  planArcs({first, second}, kMicron, kVoxel, 0.03, ArcEvidence::kWholeArc, hits);
  // On the first shell's middle column (bearing 0; its edge columns lie on the second cone's
  // sides): the upper part carved away, the lower kept down to the aperture's edge.
  double highest_first = -1.0, lowest_first = 1.0;
  for (const HitPoint& hit : hits) {
    if (hit.point_m.norm() < 2.0 + 1e-6 && std::abs(hit.point_m.y()) < 1e-9) {
      highest_first = std::max(highest_first, std::asin(hit.point_m.z() / hit.point_m.norm()));
      lowest_first = std::min(lowest_first, std::asin(hit.point_m.z() / hit.point_m.norm()));
    }
  }
  EXPECT_LT(highest_first, 10.0 * kDegree);
  EXPECT_GT(highest_first, 0.0);
  EXPECT_NEAR(lowest_first, -17.5 * kDegree, 1e-9);
  // Uniform spread: every kept point of the first shell gets 1 / (kept rows).
  planArcs({first, second}, kMicron, kVoxel, 0.03, ArcEvidence::kSpreadUniform, hits);
  std::set<double> weights;
  for (const HitPoint& hit : hits) {
    if (hit.point_m.norm() < 2.0 + 1e-6) weights.insert(hit.weight);
  }
  ASSERT_EQ(weights.size(), 1U);
  EXPECT_LT(*weights.begin(), 1.0 / 20.0);  // dozens of rows kept
  // Beam pattern: 1 on the axis, 0.25 at the −3 dB edges.
  planArcs({first}, kMicron, kVoxel, 0.03, ArcEvidence::kBeamPattern, hits);
  double axis_weight = 0.0, edge_weight = 1.0;
  for (const HitPoint& hit : hits) {
    const double elevation = std::asin(hit.point_m.z() / hit.point_m.norm());
    if (std::abs(elevation) < 1e-9) axis_weight = hit.weight;
    if (std::abs(std::abs(elevation) - 17.5 * kDegree) < 1e-9) edge_weight = hit.weight;
  }
  EXPECT_NEAR(axis_weight, 1.0, 1e-12);
  EXPECT_NEAR(edge_weight, 0.25, 1e-12);
}

// Carving against brute force: a shell point is kept exactly when no other beam of the sweep saw
// water beyond it in its cone, whatever the beams' poses. Beams from sonars moved and turned by up
// to 0.3 m and 40° (the mapper skips pairs of beams that cannot share a direction; that must never
// skip one that carves), some with an obstacle, some with water only.
TEST(mappingBeamVolume, CarvingMatchesBruteForceForMovedAndTurnedSonars) {
  std::vector<PlannedBeam> beams;
  for (int i = 0; i < 40; ++i) {
    const double turn = (i % 4) * 10.0 * kDegree;  // 0°, 10°, 20°, 30° of roll, pitch and yaw
    const Eigen::Vector3d origin_m(0.3 * std::sin(i), 0.2 * std::cos(1.7 * i), 0.1 * std::sin(0.3 * i));
    const Eigen::Isometry3d pose = tiltedPose(origin_m, 0.7 * turn, -turn, 1.3 * turn);
    const double bearing_rad = 2.0 * kDegree * i;
    const double range_m = 1.5 + 0.05 * (i % 7) + 0.5 * (i % 3);
    const bool hit = i % 5 != 0;
    beams.push_back(PlannedBeam{pose, bearing_rad, range_m - 0.05, range_m, hit});
  }
  const double tolerance_m = 0.03;
  auto inCone = [&](const PlannedBeam& beam, const Eigen::Vector3d& point_m) {
    const Eigen::Vector3d v = beam.sonar_to_map.inverse() * point_m;
    const double reach_m = (beam.hit ? beam.hit_range_m : beam.free_range_m) - tolerance_m;
    if (!(v.norm() < reach_m)) return false;
    const double elevation_rad = std::asin(v.z() / v.norm());
    const double bearing_gap_rad = std::abs(std::remainder(std::atan2(v.y(), v.x()) - beam.bearing_rad, 2.0 * std::numbers::pi));
    return std::abs(elevation_rad) <= 0.5 * kMicron.vertical_aperture_rad + 1e-12 &&
           bearing_gap_rad <= 0.5 * kMicron.width_rad + 1e-12;
  };
  std::vector<HitPoint> expected, shell;
  std::size_t carved = 0;
  for (std::size_t b = 0; b < beams.size(); ++b) {
    planArcs({beams[b]}, kMicron, kVoxel, tolerance_m, ArcEvidence::kWholeArc, shell);
    for (const HitPoint& point : shell) {
      bool water = false;
      for (std::size_t n = 0; n < beams.size() && !water; ++n) water = n != b && inCone(beams[n], point.point_m);
      if (water) {
        ++carved;
      } else {
        expected.push_back(point);
      }
    }
  }
  std::vector<HitPoint> hits;
  planArcs(beams, kMicron, kVoxel, tolerance_m, ArcEvidence::kWholeArc, hits);
  EXPECT_GT(carved, 1000U);  // the test carves
  ASSERT_EQ(hits.size(), expected.size());
  for (std::size_t i = 0; i < hits.size(); ++i) EXPECT_EQ(hits[i].point_m, expected[i].point_m) << i;
}

/// A sweep of `beams` beams over a full turn, all with `bins` bins of 2 cm.
PolarImage makeSweep(int beams, int bins) { return testing::makeFullTurnSweep(beams, bins, kVoxel); }

MapperOptions volumeOptions() {
  MapperOptions options;
  options.resolution_m = kVoxel;
  options.beam_model = BeamModel::kVolume;
  options.range_tolerance_m = 0.04;
  return options;
}

// One sweep of 200 overlapping cones on an empty map: every known cell holds exactly one update
// (a miss, or one hit weighted by the beam pattern, at most the whole hit), and the counts add up
// to the cells.
TEST(mappingBeamVolume, EachVoxelIsUpdatedOncePerSweep) {
  SonarMapper mapper(volumeOptions());
  PolarImage polar = makeSweep(200, 100);
  std::vector<BeamDetection> detections;
  for (int i = 0; i < 200; ++i) {
    const int bin = 50 + (i % 7) * 5;
    detections.push_back({bin, 200, (bin + 0.5) * kVoxel});
  }
  mapper.integrateSweep(polar, detections);
  const OcTree16& map = mapper.map();
  std::size_t known = 0, other = 0;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    const auto edge = static_cast<std::size_t>(leaf.edgeVoxels());  // pruned leaves: their voxels
    known += edge * edge * edge;
    const bool one_hit = leaf.log_odds > 0.0F && leaf.log_odds <= map.model().hit;
    if (leaf.log_odds != map.model().miss && !one_hit) ++other;
  });
  EXPECT_EQ(other, 0U);
  EXPECT_EQ(known, mapper.stats().free_updates + mapper.stats().occupied_updates);
  EXPECT_GT(mapper.stats().free_updates, 100000U);  // a 3D volume, not a plane
}

// A cone whose quieter outer part (half the free core's extent off the axis and beyond) crosses a
// cell the map holds occupied leaves it occupied; its loud inner part clears it.
TEST(mappingBeamVolume, OuterConeDoesNotErodeOccupiedCells) {
  SonarMapper mapper(volumeOptions());
  const Key16 target = *mapper.map().coder().keyOf(Eigen::Vector3d(2.0, 0.0, 0.0));
  const Eigen::Vector3d target_m = mapper.map().coder().centerOf(target);
  auto occupied = [&] {
    const std::optional<float> log_odds = mapper.map().search(target);
    return log_odds && mapper.map().model().isOccupied(*log_odds);
  };
  PolarImage polar = makeSweep(1, 250);
  // First: a level sonar 2 m behind the target maps a face through it (the cone's axis is its
  // most horizontal ray: the face at 2 m).
  const Eigen::Isometry3d behind = tiltedPose(target_m + Eigen::Vector3d(-2.0, 0.0, 0.0), 0.0, 0.0, 0.0);
  const int bin = static_cast<int>(2.0 / kVoxel);
  for (int i = 0; i < 4; ++i) mapper.integrateSweep(polar, {BeamDetection{bin, 200, 2.0}}, behind);
  ASSERT_TRUE(occupied());
  // Then a level sonar higher up sees an obstacle at 4.5 m: the target lies 6.5° below its axis,
  // in the outer part of the cleared core (35° / 8 < |e| ≤ 35° / 4): it stays occupied.
  const BeamDetection far{static_cast<int>(4.5 / kVoxel), 200, 4.5};
  const Eigen::Vector3d above_m = target_m + Eigen::Vector3d(-2.0, 0.0, 2.0 * std::tan(6.5 * kDegree));
  for (int i = 0; i < 10; ++i) mapper.integrateSweep(polar, {far}, tiltedPose(above_m, 0.0, 0.0, 0.0));
  EXPECT_TRUE(occupied());
  // Tilted down onto it, the inner part clears it.
  const Eigen::Isometry3d looking = tiltedPose(above_m, 0.0, 6.5 * kDegree, 0.0);
  for (int i = 0; i < 10; ++i) mapper.integrateSweep(polar, {far}, looking);
  EXPECT_FALSE(occupied());
}

// A sonar mounted tilted down: the cone follows the mounting (the free cells lie below the
// sonar's level ahead of it). By default only the central half of the aperture is cleared.
TEST(mappingBeamVolume, TiltedMountingTiltsTheCone) {
  const Eigen::Isometry3d tilted = tiltedPose({0.0, 0.0, 0.0}, 0.0, 25.0 * kDegree, 0.0);  // nose down
  PolarImage polar = makeSweep(1, 150);
  const BeamDetection obstacle{static_cast<int>(3.0 / kVoxel), 200, 3.0};
  auto zExtent = [&](const MapperOptions& options) {
    SonarMapper mapper(options);
    mapper.integrateSweep(polar, {obstacle}, tilted);
    double lowest_z = 0.0, highest_z = -1.0;
    mapper.map().forEachLeaf([&](const LeafView<16>& leaf) {
      if (leaf.log_odds >= 0.0F) return;  // the free cells only
      const double z = mapper.map().coder().centerOf(leaf.key).z();
      lowest_z = std::min(lowest_z, z);
      highest_z = std::max(highest_z, z);
    });
    return std::pair{lowest_z, highest_z};
  };
  // Axis 25° down, free to 3 m less the 4 cm tolerance; the free core spans 16.25°…33.75° down:
  // z down to −1.64 m.
  const auto [core_low, core_high] = zExtent(volumeOptions());
  EXPECT_NEAR(core_low, -2.96 * std::sin(33.75 * kDegree), 0.05);
  EXPECT_LT(core_high, 0.05);  // nothing above the sonar's level
}

// Without an obstacle a cone clears nothing (clearsWithoutObstacle): its silence may hide a grazing
// seabed. The planar model's wedge clears.
TEST(mappingBeamVolume, BeamWithoutObstacleClearsNothingInTheCone) {
  PolarImage polar = makeSweep(1, 150);
  BeamDetection water;
  water.water_range_m = 3.0;
  auto freeCells = [&](const MapperOptions& options) {
    SonarMapper mapper(options);
    mapper.integrateSweep(polar, {water}, Eigen::Isometry3d::Identity());
    EXPECT_EQ(mapper.stats().beams_without_evidence + mapper.stats().beams_used, 1U);
    return mapper.stats().free_updates;
  };
  EXPECT_EQ(freeCells(volumeOptions()), 0U);
  MapperOptions planar = volumeOptions();
  planar.beam_model = BeamModel::kPlanar;
  EXPECT_GT(freeCells(planar), 50U);  // the wedge to 3 m
  // A beam with an obstacle clears up to it either way.
  SonarMapper mapper(volumeOptions());
  mapper.integrateSweep(polar, {BeamDetection{120, 200, 120 * kVoxel}}, Eigen::Isometry3d::Identity());
  EXPECT_GT(mapper.stats().free_updates, 1000U);
  EXPECT_EQ(mapper.stats().beams_without_evidence, 0U);
}

// A weak extended return (8.8 dB over the background: a grazing seabed) ahead of a strong wall is no
// obstacle, but it sets the echo onset, and the volume model clears its cones only up to there.
TEST(mappingBeamVolume, WeakReturnStopsTheFreeCone) {
  PolarImage polar = makeSweep(60, 200);  // 4 m of 2 cm bins, 60 beams: a background to estimate
  for (int r = 0; r < 60; ++r) {
    for (int c = 10; c < 200; ++c) polar.intensities.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(c % 3);  // quiet
  }
  for (int c = 100; c < 200; ++c) polar.intensities.at<std::uint8_t>(0, c) = 50;  // 8.8 dB at 45 dB per 255
  for (int c = 150; c < 160; ++c) polar.intensities.at<std::uint8_t>(0, c) = 230;  // the wall
  MapperOptions options = volumeOptions();
  SonarMapper mapper(options);
  PolarImage detected = polar;
  const std::vector<BeamDetection> detections = mapper.detect(detected);
  ASSERT_TRUE(detections[0].hasObstacle());
  EXPECT_NEAR(detections[0].range_m, 3.0, 0.05);
  EXPECT_NEAR(detections[0].echo_onset_m, 2.0, 0.03);
  EXPECT_FALSE(detections[1].hasObstacle());
  EXPECT_NEAR(detections[1].echo_onset_m, detections[1].water_range_m, 1e-12);  // nothing rises
  mapper.integrateSweep(detected, detections);
  // Along beam 0's axis: free before the onset, unknown between the onset and the wall.
  const auto classify = [&](double x_m) {
    const std::optional<float> log_odds = mapper.map().search(*mapper.map().coder().keyOf(Eigen::Vector3d(x_m, 0.001, 0.001)));
    return log_odds ? mapper.map().model().classify(*log_odds) : Occupancy::kUnknown;
  };
  EXPECT_EQ(classify(1.5), Occupancy::kFree);
  EXPECT_EQ(classify(2.5), Occupancy::kUnknown);
}

/// 60 beams of water (0–2 counts) with beam 0 stepping to 50 counts from 2 m on: a weak return
/// below the obstacle threshold that lasts to the end of the beam (a step into reverberation).
PolarImage sweepWithAStepInBeamZero() {
  PolarImage polar = makeSweep(60, 200);  // 4 m of 2 cm bins
  for (int r = 0; r < 60; ++r) {
    for (int c = 10; c < 200; ++c) polar.intensities.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(c % 3);
  }
  for (int c = 100; c < 200; ++c) polar.intensities.at<std::uint8_t>(0, c) = 50;  // from 2 m on
  return polar;
}

// The planar model with the loud echoes only (the background detector): a beam whose only return is
// weak (8.8 dB over the background: a soft or grazing surface, no obstacle) clears its wedge up to
// where that return starts, not through it; a quiet beam still clears to its full range.
TEST(mappingBeamVolume, PlanarBeamWithAWeakReturnClearsOnlyUpToIt) {
  const PolarImage polar = sweepWithAStepInBeamZero();
  MapperOptions options;
  options.resolution_m = kVoxel;
  selectDetector(options.detector, "background");
  SonarMapper mapper(options);
  PolarImage detected = polar;
  const std::vector<BeamDetection> detections = mapper.detect(detected);
  ASSERT_FALSE(detections[0].hasObstacle());
  EXPECT_NEAR(detections[0].echo_onset_m, 2.0, 0.03);
  EXPECT_GT(detections[0].water_range_m, 3.9);  // below the obstacle threshold all along
  mapper.integrateSweep(detected, detections);
  const auto classify = [&](double x_m, double y_m) {
    const std::optional<float> log_odds = mapper.map().search(*mapper.map().coder().keyOf(Eigen::Vector3d(x_m, y_m, 0.001)));
    return log_odds ? mapper.map().model().classify(*log_odds) : Occupancy::kUnknown;
  };
  EXPECT_EQ(classify(1.5, 0.001), Occupancy::kFree);
  EXPECT_EQ(classify(3.0, 0.001), Occupancy::kUnknown);  // behind the weak return's start
  EXPECT_EQ(classify(0.0, -3.0), Occupancy::kFree);       // the quiet beam at 270°
}

// The same sweep with the default (evidence) detector: the step is the beam's first return, a weak
// return certain by its bins' evidence, mapped in the plane at its start: free before, occupied at
// 2 m, unknown behind. The volume model detects with the loud echoes alone (a weak return in a cone
// is traced as a level surface by the extended returns): its detections are the background's.
TEST(mappingBeamVolume, StepIntoReverberationIsTheBeamsFirstReturn) {
  const PolarImage polar = sweepWithAStepInBeamZero();
  MapperOptions options;
  options.resolution_m = kVoxel;
  SonarMapper mapper(options);
  PolarImage detected = polar;
  const std::vector<BeamDetection> detections = mapper.detect(detected);
  ASSERT_TRUE(detections[0].hasObstacle());
  EXPECT_TRUE(detections[0].weak);
  EXPECT_NEAR(detections[0].range_m, 2.0, 0.03);
  for (std::size_t r = 1; r < detections.size(); ++r) EXPECT_FALSE(detections[r].hasObstacle()) << r;
  mapper.integrateSweep(detected, detections);
  const auto classify = [&](double x_m) {
    const std::optional<float> log_odds = mapper.map().search(*mapper.map().coder().keyOf(Eigen::Vector3d(x_m, 0.001, 0.001)));
    return log_odds ? mapper.map().model().classify(*log_odds) : Occupancy::kUnknown;
  };
  EXPECT_EQ(classify(1.5), Occupancy::kFree);
  EXPECT_EQ(classify(2.01), Occupancy::kOccupied);
  EXPECT_EQ(classify(3.0), Occupancy::kUnknown);

  MapperOptions volume = volumeOptions();
  selectDetector(volume.detector, "background");
  PolarImage loud = polar;
  const std::vector<BeamDetection> background = SonarMapper(volume).detect(loud);
  volume.detector = MapperOptions{}.detector;
  PolarImage weak = polar;
  const std::vector<BeamDetection> in_the_cone = SonarMapper(volume).detect(weak);
  ASSERT_EQ(in_the_cone.size(), background.size());
  for (std::size_t r = 0; r < background.size(); ++r) {
    EXPECT_EQ(in_the_cone[r].obstacle_bin, background[r].obstacle_bin) << r;
    EXPECT_EQ(in_the_cone[r].water_range_m, background[r].water_range_m) << r;
    EXPECT_EQ(in_the_cone[r].echo_onset_m, background[r].echo_onset_m) << r;
    EXPECT_FALSE(in_the_cone[r].weak) << r;
  }
}

// Options: the volume model's aperture in (0, π); the cone it clears is half of it.
TEST(mappingBeamVolume, ApertureOptionsAreChecked) {
  MapperOptions options = volumeOptions();
  EXPECT_DOUBLE_EQ(freeVerticalAperture_rad(options), 0.5 * options.vertical_aperture_rad);
  options.vertical_aperture_rad = std::numbers::pi;
  EXPECT_THROW(options.validate(), ValueError);
  options.beam_model = BeamModel::kPlanar;  // unused by the planar model
  EXPECT_NO_THROW(options.validate());
  EXPECT_EQ(parseBeamModel("volume"), BeamModel::kVolume);
}

}  // namespace
}  // namespace sonarmap
