// A vertical face seen at oblique incidence (planArcs, face_slope; MapperOptions::face_slope): each
// leading edge is the face's nearest point in its beam, so a face drawn at that distance across the
// whole beam stands in front of the wall; the neighbours' leading edges measure how fast it recedes.
// Checked against the wall's plane; a pile (its near point between its neighbours), a short echo and
// a head tilted to the side keep the face square to the beam.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "polar_fixtures.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kVoxel = 0.02;
constexpr double kTolerance = 0.03;
const BeamShape kMicron{3.0 * kDegree, 35.0 * kDegree};
constexpr double kStep = 0.9 * kDegree;  // the Micron's bearing step

/// A wall through (distance · n) with horizontal unit normal n at azimuth `normal_rad`, seen by a
/// level head at the origin: the beams at bearings k · step, k in [−count, count], each with the
/// echo of the wall's nearest point in its cone (the horizontal ray at the beam's edge nearer the
/// normal) lasting to its farthest (the aperture's edge row at the other side), plus `echo_extra_m`.
std::vector<PlannedBeam> beamsOnWall(const Eigen::Isometry3d& pose, double distance_m, double normal_rad, int count,
                                     double echo_extra_m) {
  std::vector<PlannedBeam> beams;
  const double half = 0.5 * kMicron.width_rad;
  for (int k = -count; k <= count; ++k) {
    const double bearing = k * kStep;
    const double nearest = std::min(std::abs(bearing - half - normal_rad), std::abs(bearing + half - normal_rad));
    const double farthest = std::max(std::abs(bearing - half - normal_rad), std::abs(bearing + half - normal_rad));
    const double range_m = distance_m / std::cos(nearest);
    PlannedBeam beam{pose, bearing, range_m - kTolerance, range_m, true};
    beam.hit_end_m = distance_m / (std::cos(farthest) * std::cos(0.5 * kMicron.vertical_aperture_rad)) + echo_extra_m;
    beams.push_back(beam);
  }
  return beams;
}

struct Offsets {
  std::size_t in_front = 0, behind = 0, total = 0;
};

/// The points more than 2 cm in front of (or behind) the wall, horizontally.
Offsets offsets(const std::vector<HitPoint>& hits, double distance_m, double normal_rad) {
  Offsets o;
  const Eigen::Vector3d normal(std::cos(normal_rad), std::sin(normal_rad), 0.0);
  for (const HitPoint& hit : hits) {
    const double signed_m = normal.dot(hit.point_m) - distance_m;
    o.in_front += signed_m < -0.02 ? 1 : 0;
    o.behind += signed_m > 0.02 ? 1 : 0;
    ++o.total;
  }
  return o;
}

std::vector<HitPoint> plan(const std::vector<PlannedBeam>& beams, bool face_slope) {
  std::vector<HitPoint> hits;
  planArcs(beams, kMicron, kVoxel, kTolerance, ArcEvidence::kBeamPattern, hits, ObstacleSurface::kVertical, face_slope);
  return hits;
}

// A wall 3 m away whose normal points 40° off the middle beam: across a 3° beam it recedes by
// 3 · tan 40° · 3° ≈ 0.13 m, more than the carving's tolerance and a beam step's recession.
TEST(mappingFaceSlope, AnObliqueWallIsDrawnOnTheWallNotInFrontOfIt) {
  const double wall_m = 3.0, normal_rad = 40.0 * kDegree;
  const std::vector<PlannedBeam> beams = beamsOnWall(Eigen::Isometry3d::Identity(), wall_m, normal_rad, 10, 0.05);
  const Offsets square = offsets(plan(beams, false), wall_m, normal_rad);
  const Offsets sloped = offsets(plan(beams, true), wall_m, normal_rad);
  ASSERT_GT(square.total, 1000U);
  ASSERT_GT(sloped.total, 1000U);
  // Square to each beam, most of the face stands in front of the wall, even after the carving;
  // along the measured slope, only the two end beams' (one neighbour each) and a few others'.
  EXPECT_GT(square.in_front, square.total / 2);
  EXPECT_LT(sloped.in_front, square.in_front / 3);
  EXPECT_LT(static_cast<double>(sloped.in_front) / static_cast<double>(sloped.total), 0.12);
  // The slope is the smaller of the two neighbours' secants of a convex 1 / cos: never behind.
  EXPECT_EQ(sloped.behind, 0U);
  EXPECT_EQ(square.behind, 0U);
}

// The same wall with the normal on the other side of the beams: the face recedes the other way.
TEST(mappingFaceSlope, TheFaceRecedesEitherWay) {
  const double wall_m = 2.0, normal_rad = -35.0 * kDegree;
  const std::vector<PlannedBeam> beams = beamsOnWall(Eigen::Isometry3d::Identity(), wall_m, normal_rad, 10, 0.05);
  const Offsets square = offsets(plan(beams, false), wall_m, normal_rad);
  const Offsets sloped = offsets(plan(beams, true), wall_m, normal_rad);
  EXPECT_LT(sloped.in_front, square.in_front / 3);
  EXPECT_EQ(sloped.behind, 0U);
}

// What keeps the face square to the beam: a pile's near point (both neighbours farther), an echo
// too short for the recession, a beam without both neighbours, a head rolled so that its bearings
// are no longer azimuths across the aperture.
TEST(mappingFaceSlope, PilesShortEchoesAndRolledHeadsKeepTheFaceSquare) {
  const Eigen::Isometry3d level = Eigen::Isometry3d::Identity();
  // A pile of radius 0.2 m at 2.5 m: each beam's range is its nearest point; the middle beam's
  // neighbours are both farther, so its face is square (the same points either way).
  std::vector<PlannedBeam> pile;
  for (int k = -1; k <= 1; ++k) {
    const double bearing = k * kStep;
    const double off = std::max(0.0, std::abs(bearing) - 0.5 * kMicron.width_rad);
    const double range_m = 2.7 * std::cos(off) - std::sqrt(0.04 - std::pow(2.7 * std::sin(off), 2.0));
    PlannedBeam beam{level, bearing, range_m - kTolerance, range_m, true};
    beam.hit_end_m = range_m + 0.2;
    pile.push_back(beam);
  }
  EXPECT_EQ(plan(pile, true).size(), plan(pile, false).size());
  // The oblique wall, but each echo ends 1 cm after its leading edge: no room for the recession.
  const double wall_m = 3.0, normal_rad = 40.0 * kDegree;
  std::vector<PlannedBeam> short_echo = beamsOnWall(level, wall_m, normal_rad, 3, 0.0);
  for (PlannedBeam& beam : short_echo) beam.hit_end_m = beam.hit_range_m + 0.01;
  const std::vector<HitPoint> a = plan(short_echo, true), b = plan(short_echo, false);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(a[i].point_m.isApprox(b[i].point_m));
  // Without an echo's end (NaN), no bound to check the slope against: square.
  for (PlannedBeam& beam : short_echo) beam.hit_end_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(plan(short_echo, true).size(), plan(short_echo, false).size());
  // A single beam has no neighbours.
  const std::vector<PlannedBeam> one(1, beamsOnWall(level, wall_m, normal_rad, 0, 0.05).front());
  EXPECT_EQ(plan(one, true).size(), plan(one, false).size());
  // Rolled 25° about its axis (a tilted head looking to the side): the aperture's edge rows are
  // 17.5° sin 25° = 7.4° of azimuth off its bearings, more than half the width: square.
  const Eigen::Isometry3d rolled = testing::tiltedPose({0.0, 0.0, 0.0}, 25.0 * kDegree, 0.0, 0.0);
  const std::vector<PlannedBeam> side = beamsOnWall(rolled, wall_m, normal_rad, 3, 0.05);
  const std::vector<HitPoint> c = plan(side, true), d = plan(side, false);
  ASSERT_EQ(c.size(), d.size());
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_TRUE(c[i].point_m.isApprox(d[i].point_m));
}

}  // namespace
}  // namespace sonarmap
