// The seabed's slope from the onsets of weak seabed returns (seabed_slope.hpp): a robust plane that
// outliers do not pull, kept only where the F test asks for a slope and the onsets were seen from
// many directions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "sonarmap/mapping/seabed_slope.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// A look direction drawn uniformly around the compass.
Eigen::Vector2d anyLook(std::mt19937& random) {
  const double azimuth = std::uniform_real_distribution<double>(0.0, 2.0 * std::numbers::pi)(random);
  return {std::cos(azimuth), std::sin(azimuth)};
}

/// `count` onsets over a 10 × 10 m square centred on the origin, on the plane through (0, 0, −2)
/// with unit normal `normal`, each raised by Gaussian noise of `noise_m` and seen from any direction.
void addPlane(SeabedSlope& slope, const Eigen::Vector3d& normal, int count, double noise_m, std::mt19937& random) {
  std::uniform_real_distribution<double> across(-5.0, 5.0);
  std::normal_distribution<double> noise(0.0, noise_m);
  for (int i = 0; i < count; ++i) {
    const double x = across(random), y = across(random);
    const double z = -2.0 - (normal.x() * x + normal.y() * y) / normal.z();
    slope.add({x, y, z + noise(random)}, anyLook(random));
  }
}

double angleBetween_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) / kDegree;
}

// A 7° seabed (quay3d's) with 3 cm of scatter, and 40 % as many onsets again 0.8 m above it (the
// weak echo of a wall traced as seabed): the normal comes within half a degree of the truth.
TEST(mappingSeabedSlope, OnsetsOnASlopeGiveItsNormalDespiteOutliers) {
  std::mt19937 random(3);
  SeabedSlope slope;
  const Eigen::Vector3d truth = Eigen::Vector3d(1.0, 0.0, 8.0).normalized();
  addPlane(slope, truth, 200, 0.03, random);
  std::uniform_real_distribution<double> across(0.0, 3.0);
  for (int i = 0; i < 80; ++i) {
    const double x = across(random), y = across(random);
    slope.add({x, y, -2.0 - x / 8.0 + 0.8}, anyLook(random));
  }
  const Eigen::Vector3d normal = slope.normalAt(Eigen::Vector3d::Zero(), 10.0);
  EXPECT_LT(angleBetween_deg(normal, truth), 0.5) << normal.transpose();
  EXPECT_GT(normal.z(), 0.0);
}

// Scatter alone on a level seabed asks for no slope: the normal is exactly up. So does a slope
// with too few onsets, or only far ones, or one steeper than 30° (no seabed met at grazing
// incidence).
TEST(mappingSeabedSlope, WithoutEvidenceForASlopeTheSeabedIsLevel) {
  std::mt19937 random(5);
  SeabedSlope level;
  addPlane(level, Eigen::Vector3d::UnitZ(), 300, 0.1, random);
  EXPECT_EQ(level.normalAt(Eigen::Vector3d::Zero(), 10.0), Eigen::Vector3d::UnitZ());

  const Eigen::Vector3d sloped = Eigen::Vector3d(std::sin(10.0 * kDegree), 0.0, std::cos(10.0 * kDegree));
  SeabedSlope few;
  addPlane(few, sloped, static_cast<int>(SeabedSlope::kMinOnsets) - 1, 0.0, random);
  few.add({std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}, {1.0, 0.0});  // ignored
  few.add({0.0, 0.0, -2.0}, {0.0, 0.0});                                        // no look: ignored
  EXPECT_EQ(few.size(), SeabedSlope::kMinOnsets - 1);
  EXPECT_EQ(few.normalAt(Eigen::Vector3d::Zero(), 10.0), Eigen::Vector3d::UnitZ());
  addPlane(few, sloped, 100, 0.0, random);
  EXPECT_LT(angleBetween_deg(few.normalAt(Eigen::Vector3d::Zero(), 10.0), sloped), 0.01);
  EXPECT_EQ(few.normalAt(Eigen::Vector3d(100.0, 0.0, 0.0), 10.0), Eigen::Vector3d::UnitZ());  // none within 10 m
  EXPECT_EQ(few.normalAt(Eigen::Vector3d::Zero(), 0.0), Eigen::Vector3d::UnitZ());

  SeabedSlope steep;
  addPlane(steep, Eigen::Vector3d(std::sin(40.0 * kDegree), 0.0, std::cos(40.0 * kDegree)), 100, 0.0, random);
  EXPECT_EQ(steep.normalAt(Eigen::Vector3d::Zero(), 10.0), Eigen::Vector3d::UnitZ());
}

// Onsets seen from one way only (a static head's forward fan, looks within ±60° of +x) give no
// slope, however well they fit one: their errors depend on the look and would not cancel.
TEST(mappingSeabedSlope, OnsetsSeenFromOneWayGiveNoSlope) {
  std::mt19937 random(11);
  const Eigen::Vector3d sloped = Eigen::Vector3d(std::sin(10.0 * kDegree), 0.0, std::cos(10.0 * kDegree));
  SeabedSlope one_way;
  std::uniform_real_distribution<double> across(-5.0, 5.0), fan(-60.0 * kDegree, 60.0 * kDegree);
  for (int i = 0; i < 200; ++i) {
    const double x = across(random), y = across(random), azimuth = fan(random);
    one_way.add({x, y, -2.0 - x * sloped.x() / sloped.z()}, {std::cos(azimuth), std::sin(azimuth)});
  }
  EXPECT_EQ(one_way.normalAt(Eigen::Vector3d::Zero(), 10.0), Eigen::Vector3d::UnitZ());
  // The same points seen from opposite ways too: the slope.
  for (int i = 0; i < 200; ++i) {
    const double x = across(random), y = across(random), azimuth = std::numbers::pi + fan(random);
    one_way.add({x, y, -2.0 - x * sloped.x() / sloped.z()}, {std::cos(azimuth), std::sin(azimuth)});
  }
  EXPECT_LT(angleBetween_deg(one_way.normalAt(Eigen::Vector3d::Zero(), 10.0), sloped), 0.01);
}

// A long mission keeps the newest onsets only: the seabed where the vehicle is now.
TEST(mappingSeabedSlope, KeepsTheNewestOnsets) {
  std::mt19937 random(7);
  SeabedSlope slope;
  const Eigen::Vector3d before = Eigen::Vector3d(-std::sin(10.0 * kDegree), 0.0, std::cos(10.0 * kDegree));
  const Eigen::Vector3d now = Eigen::Vector3d(0.0, std::sin(10.0 * kDegree), std::cos(10.0 * kDegree));
  addPlane(slope, before, static_cast<int>(SeabedSlope::kCapacity), 0.02, random);
  addPlane(slope, now, static_cast<int>(SeabedSlope::kCapacity), 0.02, random);
  EXPECT_EQ(slope.size(), SeabedSlope::kCapacity);
  EXPECT_LT(angleBetween_deg(slope.normalAt(Eigen::Vector3d::Zero(), 10.0), now), 0.5);
}

}  // namespace
}  // namespace sonarmap
