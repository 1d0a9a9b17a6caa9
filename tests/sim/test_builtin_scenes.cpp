// The built-in scenes: the CRAS tank's geometry, lookup by name, and how each scene is built for a
// head's reach and vertical aperture (the same fractions of the reach, thin piles, something at
// z = 0, nothing within reach in open water).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
const Eigen::Vector3d kOrigin = Eigen::Vector3d::Zero();

/// Unit direction at `bearing_rad` (from +x, counter-clockwise) and `elevation_rad` (up).
Eigen::Vector3d direction(double bearing_rad, double elevation_rad = 0.0) {
  return {std::cos(elevation_rad) * std::cos(bearing_rad), std::cos(elevation_rad) * std::sin(bearing_rad),
          std::sin(elevation_rad)};
}

/// The heads the presets model: (reach, vertical beam width).
struct Head {
  double reach_m;
  double vertical_rad;
};
const std::vector<Head> kHeads{{5.0, 35.0 * kDegree}, {20.0, 20.0 * kDegree}, {30.0, 40.0 * kDegree},
                               {50.0, 40.0 * kDegree}, {50.0, 25.0 * kDegree}, {2.0, 35.0 * kDegree}};

TEST(simBuiltinScenes, TankHasTheCrasGeometry) {
  const Scene tank = builtinScene("tank");
  EXPECT_NO_THROW(validateScene(tank));
  // Horizontal rays from the head: walls between 1.8 m (nearest face, −y) and 3.34 m (corners).
  double nearest_m = 1e9, farthest_m = 0.0;
  for (int degree = 0; degree < 360; ++degree) {
    const auto hit = firstHit(tank, kOrigin, direction(degree * kDegree), 10.0);
    ASSERT_TRUE(hit) << degree;
    nearest_m = std::min(nearest_m, hit->surface.range_m);
    farthest_m = std::max(farthest_m, hit->surface.range_m);
  }
  EXPECT_NEAR(nearest_m, 1.8, 1e-9);
  EXPECT_NEAR(farthest_m, std::hypot(2.1, 2.6), 0.01);
  // The top of the 35° aperture meets the surface at ≈ 1.56 m in every direction.
  const auto ring = firstHit(tank, kOrigin, direction(0.0, 17.5 * kDegree), 10.0);
  ASSERT_TRUE(ring);
  EXPECT_NEAR(ring->surface.range_m, 1.56, 0.01);
  // The floater at bearing 95°, 1.95 m away, within the aperture (12° up).
  const double up = 12.0 * kDegree;
  const auto floater = firstHit(tank, kOrigin, direction(95.0 * kDegree, up), 10.0);
  ASSERT_TRUE(floater);
  EXPECT_EQ(floater->primitive, 3U);
  EXPECT_NEAR(floater->surface.range_m * std::cos(up), 1.95, 1e-9);
}

TEST(simBuiltinScenes, LookupByNameAndUnknownNamesListed) {
  EXPECT_EQ(builtinSceneNames(), (std::vector<std::string>{"tank", "harbour", "hull", "soft", "open-water"}));
  const Scene harbour = builtinScene("harbour");
  EXPECT_NO_THROW(validateScene(harbour));
  // Straight ahead (north): a pile at 2 m − 0.2 m; to the west the open water has nothing within 5 m.
  const auto pile = firstHit(harbour, kOrigin, Eigen::Vector3d::UnitX(), 5.0);
  ASSERT_TRUE(pile);
  EXPECT_NEAR(pile->surface.range_m, 1.8, 1e-9);
  EXPECT_FALSE(firstHit(harbour, kOrigin, Eigen::Vector3d::UnitY(), 5.0));
  EXPECT_FALSE(firstHit(harbour, kOrigin, -Eigen::Vector3d::UnitX(), 5.0));  // no tank walls
  try {
    builtinScene("pool");
    FAIL() << "expected ValueError";
  } catch (const ValueError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("pool"), std::string::npos);
    for (const std::string& name : builtinSceneNames()) EXPECT_NE(message.find(name), std::string::npos) << name;
  }
}

TEST(simBuiltinScenes, BadReachOrApertureIsRejected) {
  for (const double reach_m : {0.0, -5.0, std::nan(""), HUGE_VAL}) {
    EXPECT_THROW(builtinScene("tank", reach_m), ValueError) << reach_m;
  }
  for (const double width_rad : {0.0, std::numbers::pi, std::nan("")}) {
    EXPECT_THROW(builtinScene("harbour", 30.0, width_rad), ValueError) << width_rad;
  }
}

TEST(simBuiltinScenes, TheMicronsScenesAreTheScenesAsFirstBuilt) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene defaults = builtinScene(name);
    const Scene micron = builtinScene(name, 5.0, 35.0 * kDegree);
    ASSERT_EQ(defaults.primitives.size(), micron.primitives.size()) << name;
  }
  // The original numbers, exactly (s = h = 1).
  const Scene harbour = builtinScene("harbour", 5.0, 35.0 * kDegree);
  EXPECT_EQ(std::get<Plane>(harbour.primitives[1]).point_m.z(), -1.3);
  const auto& quay = std::get<Box>(harbour.primitives[2]);
  EXPECT_EQ(quay.center_m, Eigen::Vector3d(6.0, 0.0, 0.5 * (-1.3 + 3.5)));
  EXPECT_EQ(quay.size_m, Eigen::Vector3d(5.0, 40.0, 3.5 - -1.3));
  EXPECT_EQ(std::get<Cylinder>(harbour.primitives[3]).radius_m, 0.2);
  const Scene tank = builtinScene("tank", 5.0, 35.0 * kDegree);
  EXPECT_EQ(std::get<Plane>(tank.primitives[0]).point_m.z(), 0.47);
  EXPECT_EQ(std::get<Box>(tank.primitives[2]).size_m, Eigen::Vector3d(4.2, 4.4, 3.0));
}

TEST(simBuiltinScenes, ScenesKeepTheirFractionsOfTheReach) {
  for (const Head& head : kHeads) {
    const double r = head.reach_m, half_rad = 0.5 * head.vertical_rad;
    SCOPED_TRACE("reach " + std::to_string(r) + " m, vertical " + std::to_string(head.vertical_rad / kDegree) + "°");
    // Tank: nearest wall at 0.36 R; the aperture's upper edge meets the surface at 0.313 R (the
    // ring), its lower edge the floor at ≈ R.
    const Scene tank = builtinScene("tank", r, head.vertical_rad);
    EXPECT_NEAR(firstHit(tank, kOrigin, direction(-90.0 * kDegree), 2.0 * r)->surface.range_m, 0.36 * r, 1e-9 * r);
    const auto ring = firstHit(tank, kOrigin, direction(0.0, half_rad), 2.0 * r);
    ASSERT_TRUE(ring);
    EXPECT_EQ(ring->primitive, 0U);
    EXPECT_NEAR(ring->surface.range_m, 0.47 / std::sin(17.5 * kDegree) / 5.0 * r, 1e-9 * r);
    const auto floor = intersectRay(tank.primitives[1], kOrigin, direction(0.0, -half_rad));
    ASSERT_TRUE(floor);
    EXPECT_NEAR(floor->range_m, 1.5 / std::sin(17.5 * kDegree) / 5.0 * r, 1e-9 * r);  // behind the walls
    // Harbour: pile ahead at 0.4 R less its radius; the quay at 0.7 R (15° off the piles); the
    // aperture's lower edge meets the seabed at 0.86 R, its upper edge no surface within reach.
    for (const std::string name : {"harbour", "soft"}) {
      const Scene scene = builtinScene(name, r, head.vertical_rad);
      const auto& pile = std::get<Cylinder>(scene.primitives[5]);
      EXPECT_GE(pile.radius_m, 0.2);
      EXPECT_LE(pile.radius_m, 0.3);
      EXPECT_NEAR(firstHit(scene, kOrigin, direction(0.0), r)->surface.range_m, 0.4 * r - pile.radius_m, 1e-9 * r);
      const auto quay = firstHit(scene, kOrigin, direction(15.0 * kDegree), r);
      ASSERT_TRUE(quay);
      EXPECT_EQ(quay->primitive, 2U);
      EXPECT_NEAR(quay->surface.range_m * std::cos(15.0 * kDegree), 0.7 * r, 1e-9 * r);
      const auto seabed = firstHit(scene, kOrigin, direction(180.0 * kDegree, -half_rad), 2.0 * r);
      ASSERT_TRUE(seabed);
      EXPECT_NEAR(seabed->surface.range_m, 1.3 / std::sin(17.5 * kDegree) / 5.0 * r, 1e-9 * r);
      EXPECT_FALSE(firstHit(scene, kOrigin, direction(180.0 * kDegree, half_rad), r));
    }
    // Hull: its near side 0.4 R to port, the dolphins at 0.79 R.
    const Scene hull = builtinScene("hull", r, head.vertical_rad);
    const auto side = firstHit(hull, kOrigin, direction(90.0 * kDegree), r);
    ASSERT_TRUE(side);
    EXPECT_NEAR(side->surface.range_m, 0.4 * r, 1e-9 * r);
    EXPECT_EQ(side->reflectivity, 0.95);
    const double dolphin_rad = std::atan2(2.25, 3.25);
    const auto dolphin = firstHit(hull, kOrigin, direction(dolphin_rad), r);
    ASSERT_TRUE(dolphin);
    EXPECT_EQ(dolphin->reflectivity, 0.85);
    EXPECT_NEAR(dolphin->surface.range_m, std::hypot(3.25, 2.25) / 5.0 * r - std::clamp(0.2 * r / 5.0, 0.2, 0.3),
                1e-9 * r);
  }
  // Piles stay piles: 0.2 m at 5 m, 0.3 m from 7.5 m on, not 3 m at 50 m.
  EXPECT_EQ(std::get<Cylinder>(builtinScene("harbour", 50.0).primitives[3]).radius_m, 0.3);
  EXPECT_EQ(std::get<Cylinder>(builtinScene("hull", 30.0).primitives[3]).radius_m, 0.3);
}

TEST(simBuiltinScenes, SoftSceneReflectsTenToTwentyDecibelsLessThanTheHarbour) {
  const Scene harbour = builtinScene("harbour", 30.0, 40.0 * kDegree);
  const Scene soft = builtinScene("soft", 30.0, 40.0 * kDegree);
  for (const double bearing_rad : {0.0, 15.0 * kDegree}) {  // a pile, the quay face
    const auto hard = firstHit(harbour, kOrigin, direction(bearing_rad), 30.0);
    const auto weak = firstHit(soft, kOrigin, direction(bearing_rad), 30.0);
    ASSERT_TRUE(hard && weak);
    EXPECT_EQ(hard->surface.range_m, weak->surface.range_m);
    const double weaker_db = 10.0 * std::log10(hard->reflectivity / weak->reflectivity);
    EXPECT_GE(weaker_db, 9.5);
    EXPECT_LE(weaker_db, 20.0);
  }
}

TEST(simBuiltinScenes, EveryScenesSonarPlaneHoldsATargetExceptOpenWater) {
  for (const Head& head : kHeads) {
    for (const std::string& name : builtinSceneNames()) {
      SCOPED_TRACE(name + " at " + std::to_string(head.reach_m) + " m");
      const Scene scene = builtinScene(name, head.reach_m, head.vertical_rad);
      EXPECT_NO_THROW(validateScene(scene));
      std::size_t hits_at_z0 = 0;
      for (int degree = 0; degree < 360; ++degree) {
        hits_at_z0 += firstHit(scene, kOrigin, direction(degree * kDegree), head.reach_m) ? 1 : 0;
      }
      if (name == "open-water") {
        EXPECT_EQ(hits_at_z0, 0U);
        // Nothing within reach in any direction, straight up and down included.
        for (int elevation = -90; elevation <= 90; elevation += 5) {
          for (int degree = 0; degree < 360; degree += 15) {
            EXPECT_FALSE(firstHit(scene, kOrigin, direction(degree * kDegree, elevation * kDegree), head.reach_m));
          }
        }
      } else {
        EXPECT_GT(hits_at_z0, 30U);
      }
    }
  }
}

}  // namespace
}  // namespace sonarmap
