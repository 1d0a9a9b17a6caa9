// Scene primitives: ray intersections against hand-computed ranges and normals, distances to the
// surface and validation (the built-in scenes: test_builtin_scenes.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap {
namespace {

constexpr double kTolerance = 1e-12;
const Eigen::Vector3d kOrigin = Eigen::Vector3d::Zero();

void expectVectorNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected) {
  EXPECT_NEAR((actual - expected).norm(), 0.0, 1e-12) << actual.transpose() << " vs " << expected.transpose();
}

TEST(simScene, PlaneHitFromEitherSideWithNormalFacingTheRay) {
  const Plane floor{{0.0, 0.0, -1.5}, {0.0, 0.0, 2.0}, 0.5};  // normal of length 2 is allowed
  // 30° below the horizon: range 1.5 / sin 30° = 3.
  const Eigen::Vector3d down(std::cos(std::numbers::pi / 6), 0.0, -0.5);
  const auto hit = intersectRay(floor, kOrigin, down);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->range_m, 3.0, kTolerance);
  expectVectorNear(hit->normal, Eigen::Vector3d::UnitZ());
  // From below, the normal flips to face the ray.
  const auto from_below = intersectRay(floor, Eigen::Vector3d(0.0, 0.0, -4.0), Eigen::Vector3d::UnitZ());
  ASSERT_TRUE(from_below);
  EXPECT_NEAR(from_below->range_m, 2.5, kTolerance);
  expectVectorNear(from_below->normal, -Eigen::Vector3d::UnitZ());
  // Parallel and pointing away: no hit.
  EXPECT_FALSE(intersectRay(floor, kOrigin, Eigen::Vector3d::UnitX()));
  EXPECT_FALSE(intersectRay(floor, kOrigin, Eigen::Vector3d::UnitZ()));
}

TEST(simScene, BoxSeenFromOutsideAndFromInside) {
  const Box block{{3.0, 0.0, 0.0}, {2.0, 4.0, 2.0}, 0.0, 0.9};  // x ∈ [2, 4]
  const auto outside = intersectRay(block, kOrigin, Eigen::Vector3d::UnitX());
  ASSERT_TRUE(outside);
  EXPECT_NEAR(outside->range_m, 2.0, kTolerance);
  expectVectorNear(outside->normal, -Eigen::Vector3d::UnitX());
  // From inside (a tank around the sonar), the inner face: x = 4 seen from x = 3.
  const auto inside = intersectRay(block, Eigen::Vector3d(3.0, 0.0, 0.0), Eigen::Vector3d::UnitX());
  ASSERT_TRUE(inside);
  EXPECT_NEAR(inside->range_m, 1.0, kTolerance);
  expectVectorNear(inside->normal, -Eigen::Vector3d::UnitX());
  // Passing beside it: no hit.
  EXPECT_FALSE(intersectRay(block, Eigen::Vector3d(0.0, 2.5, 0.0), Eigen::Vector3d::UnitX()));
  // Diagonal into the inner corner of a tank x, y ∈ [−1, 1]: the ray along (1, 1)/√2 meets the
  // corner at range √2; a ray at 30° meets the x = 1 face at range 1 / cos 30°.
  const Box tank{{0.0, 0.0, 0.0}, {2.0, 2.0, 2.0}, 0.0, 0.9};
  const double a = std::numbers::pi / 6;
  const auto at_30 = intersectRay(tank, kOrigin, Eigen::Vector3d(std::cos(a), std::sin(a), 0.0));
  ASSERT_TRUE(at_30);
  EXPECT_NEAR(at_30->range_m, 1.0 / std::cos(a), kTolerance);
  expectVectorNear(at_30->normal, -Eigen::Vector3d::UnitX());
}

TEST(simScene, YawedBoxTurnsItsFaces) {
  // A 2 m cube centred 5 m north, turned 45°: its corner points at the origin, 5 − √2 away.
  const Box diamond{{5.0, 0.0, 0.0}, {2.0, 2.0, 2.0}, std::numbers::pi / 4, 0.9};
  const auto corner = intersectRay(diamond, kOrigin, Eigen::Vector3d::UnitX());
  ASSERT_TRUE(corner);
  EXPECT_NEAR(corner->range_m, 5.0 - std::sqrt(2.0), 1e-9);
  // Slightly to the left of the corner the ray meets the face whose outward normal is
  // (−cos 45°, +sin 45°)… facing the ray means pointing back towards −x.
  const auto face = intersectRay(diamond, Eigen::Vector3d(0.0, 0.2, 0.0), Eigen::Vector3d::UnitX());
  ASSERT_TRUE(face);
  EXPECT_NEAR(face->range_m, 5.0 - std::sqrt(2.0) + 0.2, 1e-9);  // the face is at 45°: +0.2 along x
  expectVectorNear(face->normal, Eigen::Vector3d(-1.0, 1.0, 0.0).normalized());
}

TEST(simScene, CylinderSideAndCaps) {
  const Cylinder pile{2.0, 0.0, 0.5, -1.0, 1.0, 0.85};
  const auto side = intersectRay(pile, kOrigin, Eigen::Vector3d::UnitX());
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->range_m, 1.5, kTolerance);
  expectVectorNear(side->normal, -Eigen::Vector3d::UnitX());
  // Off-axis by 0.3 m: range 2 − √(0.25 − 0.09) = 1.6, normal (−0.4, 0.3)/0.5.
  const auto off_axis = intersectRay(pile, Eigen::Vector3d(0.0, 0.3, 0.0), Eigen::Vector3d::UnitX());
  ASSERT_TRUE(off_axis);
  EXPECT_NEAR(off_axis->range_m, 1.6, kTolerance);
  expectVectorNear(off_axis->normal, Eigen::Vector3d(-0.8, 0.6, 0.0));
  // Straight down onto the top cap from 3 m up.
  const auto cap = intersectRay(pile, Eigen::Vector3d(2.1, 0.0, 3.0), -Eigen::Vector3d::UnitZ());
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->range_m, 2.0, kTolerance);
  expectVectorNear(cap->normal, Eigen::Vector3d::UnitZ());
  // Above the pile: the side's z range excludes it.
  EXPECT_FALSE(intersectRay(pile, Eigen::Vector3d(0.0, 0.0, 1.5), Eigen::Vector3d::UnitX()));
}

TEST(simScene, FirstHitTakesTheNearestWithinReach) {
  Scene scene;
  scene.primitives.push_back(Plane{{10.0, 0.0, 0.0}, Eigen::Vector3d::UnitX(), 0.3});
  scene.primitives.push_back(Cylinder{4.0, 0.0, 0.5, -1.0, 1.0, 0.85});
  const auto hit = firstHit(scene, kOrigin, Eigen::Vector3d::UnitX(), 20.0);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->primitive, 1U);
  EXPECT_NEAR(hit->surface.range_m, 3.5, kTolerance);
  EXPECT_DOUBLE_EQ(hit->reflectivity, 0.85);
  EXPECT_FALSE(firstHit(scene, kOrigin, Eigen::Vector3d::UnitX(), 3.0));
  const auto behind = firstHit(scene, kOrigin, Eigen::Vector3d(0.0, 1.0, 0.0), 20.0);
  EXPECT_FALSE(behind);
}

TEST(simScene, DistanceToTheNearestSurface) {
  const Box box{{0.0, 0.0, 0.0}, {2.0, 4.0, 6.0}, 0.0, 0.9};
  EXPECT_NEAR(distanceToSurface(box, Eigen::Vector3d(3.0, 0.0, 0.0)), 2.0, kTolerance);  // outside, facing x
  EXPECT_NEAR(distanceToSurface(box, Eigen::Vector3d(4.0, 6.0, 0.0)), std::hypot(3.0, 4.0),
              kTolerance);                                                               // off a corner edge
  EXPECT_NEAR(distanceToSurface(box, Eigen::Vector3d(0.5, 0.0, 0.0)), 0.5, kTolerance);  // inside: the x face
  const Box yawed{{0.0, 0.0, 0.0}, {2.0, 2.0, 2.0}, std::numbers::pi / 4, 0.9};
  EXPECT_NEAR(distanceToSurface(yawed, Eigen::Vector3d(3.0, 0.0, 0.0)), 3.0 - std::sqrt(2.0), 1e-12);
  const Cylinder pile{0.0, 0.0, 1.0, 0.0, 2.0, 0.9};
  EXPECT_NEAR(distanceToSurface(pile, Eigen::Vector3d(3.0, 0.0, 1.0)), 2.0, kTolerance);
  EXPECT_NEAR(distanceToSurface(pile, Eigen::Vector3d(0.0, 0.0, 1.5)), 0.5, kTolerance);  // inside: the top cap
  EXPECT_NEAR(distanceToSurface(pile, Eigen::Vector3d(4.0, 0.0, 5.0)), std::hypot(3.0, 3.0), kTolerance);  // rim
  const Plane plane{{0.0, 0.0, -1.0}, {0.0, 0.0, -3.0}, 0.5};
  EXPECT_NEAR(distanceToSurface(plane, Eigen::Vector3d(7.0, 2.0, 1.0)), 2.0, kTolerance);
  Scene scene;
  EXPECT_TRUE(std::isinf(distanceToSurface(scene, kOrigin)));
  scene.primitives = {box, pile};
  EXPECT_NEAR(distanceToSurface(scene, Eigen::Vector3d(0.0, 0.0, 2.5)), 0.5, kTolerance);  // box top face at z = 3
}

TEST(simScene, ValidationNamesTheField) {
  EXPECT_NO_THROW(validatePrimitive(Plane{}));
  auto message = [](const Primitive& primitive) {
    try {
      validatePrimitive(primitive);
    } catch (const ValueError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(Plane{{0, 0, 0}, {0, 0, 0}, 0.5}).find("normal"), std::string::npos);
  EXPECT_NE(message(Box{{0, 0, 0}, {1, -1, 1}, 0.0, 0.5}).find("size_m.y"), std::string::npos);
  EXPECT_NE(message(Box{{0, 0, 0}, {1, 1, 1}, 0.0, 1.5}).find("reflectivity"), std::string::npos);
  EXPECT_NE(message(Cylinder{0, 0, 1, 2, 1, 0.5}).find("z_max_m"), std::string::npos);
  EXPECT_NE(message(Cylinder{0, 0, 0, 0, 1, 0.5}).find("radius_m"), std::string::npos);
  EXPECT_NE(message(Plane{{0, std::nan(""), 0}, {0, 0, 1}, 0.5}).find("point_m"), std::string::npos);
  Scene scene;
  scene.primitives = {Plane{}, Cylinder{0, 0, -1, 0, 1, 0.5}};
  EXPECT_THROW(validateScene(scene), ValueError);
}

}  // namespace
}  // namespace sonarmap
