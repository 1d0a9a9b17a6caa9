// The built-in scenes: the CRAS tank's geometry, lookup by name, and how each scene is built for a
// head's reach and vertical aperture (the same fractions of the reach, thin piles, something at
// z = 0, nothing within reach in open water).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/scene.hpp"
#include "sonarmap/sim/scene_file.hpp"

#include <Eigen/Geometry>

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

TEST(simBuiltinScenes, Quay3dIsAThreeDimensionalSceneOutsideTheTwoDimensionalList) {
  EXPECT_EQ(builtinScene3dNames(), (std::vector<std::string>{"quay3d"}));
  const std::vector<std::string> names = builtinSceneNames();
  EXPECT_EQ(std::find(names.begin(), names.end(), "quay3d"), names.end());
  try {
    builtinScene("pool");
    FAIL() << "expected ValueError";
  } catch (const ValueError& error) {
    EXPECT_NE(std::string(error.what()).find("quay3d"), std::string::npos) << error.what();
  }
  EXPECT_THROW(builtinScene("quay3d", 0.0), ValueError);
  EXPECT_THROW(builtinScene("quay3d", 5.0, std::numbers::pi), ValueError);
  // The 2D scenes keep their sonar at z = 0; unknown names and bad reaches throw as builtinScene.
  for (const std::string& name : names) EXPECT_EQ(builtinSceneDepth_m(name, 7.5), 0.0) << name;
  EXPECT_THROW(builtinSceneDepth_m("pool"), ValueError);
  EXPECT_THROW(builtinSceneDepth_m("quay3d", -1.0), ValueError);
}

TEST(simBuiltinScenes, Quay3dHasHeightStructureScaledWithTheReach) {
  for (const double r : {5.0, 2.0, 20.0, 50.0}) {
    const double s = r / 5.0;
    SCOPED_TRACE("reach " + std::to_string(r) + " m");
    const Scene scene = builtinScene("quay3d", r);
    ASSERT_EQ(scene.primitives.size(), 8U);
    for (const Primitive& primitive : scene.primitives) EXPECT_NO_THROW(validatePrimitive(primitive));
    // The vertical beam width changes nothing.
    const Scene narrow = builtinScene("quay3d", r, 10.0 * kDegree);
    for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
      EXPECT_EQ(distanceToSurface(scene.primitives[i], Eigen::Vector3d(0.3, 0.2, 0.1) * s),
                distanceToSurface(narrow.primitives[i], Eigen::Vector3d(0.3, 0.2, 0.1) * s));
    }
    // The vehicle's nominal place: 3 m deep under the origin. The surface, at z = 0 (a depth
    // sensor's 0), is 3 m straight above it.
    EXPECT_DOUBLE_EQ(builtinSceneDepth_m("quay3d", r), 3.0 * s);
    const Eigen::Vector3d vehicle(0.0, 0.0, -3.0 * s);
    const auto up = firstHit(scene, vehicle, Eigen::Vector3d::UnitZ(), 10.0 * s);
    ASSERT_TRUE(up);
    EXPECT_EQ(up->primitive, 0U);
    EXPECT_EQ(up->reflectivity, 1.0);
    EXPECT_NEAR(up->surface.range_m, 3.0 * s, 1e-9 * s);
    // The seabed slopes: −4.5 m under x = −4, −5.5 m under x = +4 (7.1°), seen from above.
    const auto& seabed = std::get<Plane>(scene.primitives[1]);
    EXPECT_NEAR(std::acos(std::abs(seabed.normal.normalized().z())), std::atan(1.0 / 8.0), 1e-12);
    for (const auto& [x, depth] : {std::pair{-4.0, -4.5}, std::pair{4.0, -5.5}, std::pair{0.0, -5.0}}) {
      const auto down = intersectRay(seabed, Eigen::Vector3d(x * s, 1.0 * s, 0.0), -Eigen::Vector3d::UnitZ());
      ASSERT_TRUE(down) << x;
      EXPECT_NEAR(-down->range_m, depth * s, 1e-9 * s) << x;
    }
    EXPECT_EQ(seabed.reflectivity, 0.5);
    // A horizontal ray from the vehicle towards +x meets the quay face at 3.5 m.
    const auto quay = firstHit(scene, vehicle, Eigen::Vector3d::UnitX(), 10.0 * s);
    ASSERT_TRUE(quay);
    EXPECT_EQ(quay->primitive, 2U);
    EXPECT_EQ(quay->reflectivity, 0.9);
    EXPECT_NEAR(quay->surface.range_m, 3.5 * s, 1e-9 * s);
    // The quay reaches below the seabed and above the surface: a vertical line at its face's
    // foot meets the seabed before the quay's bottom.
    const auto& quay_box = std::get<Box>(scene.primitives[2]);
    EXPECT_LT(quay_box.center_m.z() - 0.5 * quay_box.size_m.z(), -5.0 * s - 8.5 * s / 8.0);
    EXPECT_GT(quay_box.center_m.z() + 0.5 * quay_box.size_m.z(), 0.0);
    // Piles stand from below the seabed to above the surface: a horizontal ray at any height
    // between them meets the pile at (2, −2.5).
    for (const double z : {-4.9, -3.5, -2.5, -0.1}) {
      const Eigen::Vector3d from(0.0, -2.5 * s, z * s);
      const auto pile = firstHit(scene, from, Eigen::Vector3d::UnitX(), 10.0 * s);
      ASSERT_TRUE(pile) << z;
      EXPECT_EQ(pile->primitive, 3U) << z;
      EXPECT_NEAR(pile->surface.range_m, 1.8 * s, 1e-9 * s) << z;
      EXPECT_EQ(pile->reflectivity, 0.85);
    }
    for (std::size_t i = 3; i <= 5; ++i) {
      const auto& pile = std::get<Cylinder>(scene.primitives[i]);
      EXPECT_NEAR(pile.radius_m, 0.2 * s, 1e-12);
      EXPECT_LT(pile.z_min_m, -5.0 * s - pile.center_x_m / 8.0);  // buried
      EXPECT_GT(pile.z_max_m, 0.0);
    }
    // The boulder rests on the seabed: straight down from above it meets the boulder's top at
    // −4.4125 m, and its bottom lies below the seabed everywhere under it.
    const auto boulder =
        firstHit(scene, Eigen::Vector3d(-1.5 * s, -1.0 * s, -2.5 * s), -Eigen::Vector3d::UnitZ(), 10.0 * s);
    ASSERT_TRUE(boulder);
    EXPECT_EQ(boulder->primitive, 6U);
    EXPECT_EQ(boulder->reflectivity, 0.7);
    EXPECT_NEAR(-2.5 * s - boulder->surface.range_m, -4.4125 * s, 1e-9 * s);
    const auto& rock = std::get<Box>(scene.primitives[6]);
    EXPECT_NEAR(rock.yaw_rad, 30.0 * kDegree, 1e-12);
    const double rock_bottom_m = rock.center_m.z() - 0.5 * rock.size_m.z();
    for (const double dx : {-0.5, 0.5}) EXPECT_LT(rock_bottom_m, -5.0 * s - (rock.center_m.x() + dx * s) / 8.0);
    // The pontoon overhangs: a ray going up from below it meets its underside at z = −3.1 m, the
    // face looking down, with water below.
    const Eigen::Vector3d below(0.0, 3.0 * s, -4.0 * s);
    const auto underside = firstHit(scene, below, Eigen::Vector3d::UnitZ(), 10.0 * s);
    ASSERT_TRUE(underside);
    EXPECT_EQ(underside->primitive, 7U);
    EXPECT_EQ(underside->reflectivity, 0.9);
    EXPECT_NEAR(underside->surface.range_m, 0.9 * s, 1e-9 * s);
    EXPECT_NEAR(underside->surface.normal.z(), -1.0, 1e-12);
    const auto to_seabed = firstHit(scene, below, -Eigen::Vector3d::UnitZ(), 10.0 * s);
    ASSERT_TRUE(to_seabed);
    EXPECT_EQ(to_seabed->primitive, 1U);
    EXPECT_NEAR(to_seabed->surface.range_m, 1.0 * s, 1e-9 * s);
    // Its top stands out of the water.
    const auto& pontoon = std::get<Box>(scene.primitives[7]);
    EXPECT_GT(pontoon.center_m.z() + 0.5 * pontoon.size_m.z(), 0.0);
    // Everything but the planes and the quay's long block lies within 4.2 m of the origin in plan.
    for (std::size_t i = 3; i < scene.primitives.size(); ++i) {
      if (const auto* pile = std::get_if<Cylinder>(&scene.primitives[i])) {
        EXPECT_LE(std::hypot(pile->center_x_m, pile->center_y_m) + pile->radius_m, 4.2 * s) << i;
        continue;
      }
      const auto& box = std::get<Box>(scene.primitives[i]);
      for (const double sx : {-0.5, 0.5}) {
        for (const double sy : {-0.5, 0.5}) {
          const Eigen::Vector2d corner = box.center_m.head<2>() + Eigen::Rotation2Dd(box.yaw_rad) *
                                                                      Eigen::Vector2d(sx * box.size_m.x(), sy * box.size_m.y());
          EXPECT_LE(corner.norm(), 4.2 * s) << i;
        }
      }
    }
  }
  // The scene file format holds it (sloped plane, yawed boxes): written and read back, every
  // distance is the same.
  const Scene scene = builtinScene("quay3d");
  std::stringstream file;
  writeScene(file, scene, MapFrame::kNed);  // NED: every yaw negated, every z flipped
  const Scene read = readScene(file, "quay3d.scene");
  ASSERT_EQ(read.primitives.size(), scene.primitives.size());
  for (const Eigen::Vector3d& point : {Eigen::Vector3d(0.3, 2.9, -3.5), Eigen::Vector3d(-1.2, -0.8, -4.5),
                                       Eigen::Vector3d(3.0, 0.0, -5.0), Eigen::Vector3d(1.9, -2.4, -2.2)}) {
    for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
      EXPECT_NEAR(distanceToSurface(read.primitives[i], point), distanceToSurface(scene.primitives[i], point), 1e-12);
    }
  }
  // As designed at the Micron's 5 m, exactly.
  const Scene micron = builtinScene("quay3d");
  const auto& pontoon = std::get<Box>(micron.primitives[7]);
  EXPECT_EQ(pontoon.center_m, Eigen::Vector3d(0.0, 3.0, -1.4));
  EXPECT_EQ(pontoon.size_m, Eigen::Vector3d(2.5, 1.2, 3.4));
}

}  // namespace
}  // namespace sonarmap
