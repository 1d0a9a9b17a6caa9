/// @file builtin_scenes.cpp
/// The built-in scenes (see builtin_scenes.hpp for their geometry and its sources).

#include "sonarmap/sim/builtin_scenes.hpp"

#include <cmath>
#include <numbers>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Plane horizontalPlane(double z_m, double reflectivity) {
  return Plane{{0.0, 0.0, z_m}, Eigen::Vector3d::UnitZ(), reflectivity};
}

Scene tankScene() {
  constexpr double kSurface_m = 0.47;  // water surface above the head: ring at 0.47 / sin(17.5°) = 1.56 m
  constexpr double kFloor_m = -1.5;
  Scene scene;
  scene.primitives.push_back(horizontalPlane(kSurface_m, 1.0));
  scene.primitives.push_back(horizontalPlane(kFloor_m, 0.5));
  // Inner faces x ∈ [−2.1, 2.1], y ∈ [−1.8, 2.6]; taller than the water so that only the planes
  // above close the volume at the surface and the floor.
  scene.primitives.push_back(Box{{0.0, 0.4, -0.5}, {4.2, 4.4, 3.0}, 0.0, 0.9});
  // Floater: its near face ≈ 1.95 m from the head at bearing 95°, long side across the line of
  // sight, half above the surface (the real log's floater: a 1 m line at about that place).
  const double bearing_rad = 95.0 * kDegree;
  const double center_range_m = 2.15;
  scene.primitives.push_back(
      Box{{center_range_m * std::cos(bearing_rad), center_range_m * std::sin(bearing_rad), kSurface_m},
          {1.0, 0.4, 0.3},
          bearing_rad - 90.0 * kDegree,
          0.8});
  return scene;
}

Scene harbourScene() {
  constexpr double kSeabed_m = -1.3;  // enters the ±17.5° aperture at 1.3 / sin(17.5°) ≈ 4.3 m
  constexpr double kTop_m = 3.5;      // quay and piles stand out of the water
  Scene scene;
  scene.primitives.push_back(horizontalPlane(3.0, 1.0));  // surface, beyond the 5 m range's aperture
  scene.primitives.push_back(horizontalPlane(kSeabed_m, 0.5));
  // Quay: a 40 m long block, face at x = 3.5 m.
  scene.primitives.push_back(Box{{6.0, 0.0, 0.5 * (kSeabed_m + kTop_m)}, {5.0, 40.0, kTop_m - kSeabed_m}, 0.0, 0.9});
  for (const double y_m : {-4.0, -2.0, 0.0, 2.0, 4.0}) {
    scene.primitives.push_back(Cylinder{2.0, y_m, 0.2, kSeabed_m, kTop_m, 0.85});
  }
  return scene;
}

}  // namespace

std::vector<std::string> builtinSceneNames() { return {"tank", "harbour"}; }

Scene builtinScene(std::string_view name) {
  if (name == "tank") return tankScene();
  if (name == "harbour") return harbourScene();
  std::string known;
  for (const std::string& candidate : builtinSceneNames()) known += (known.empty() ? "" : ", ") + candidate;
  throw ValueError("unknown scene '" + std::string(name) + "', expected one of: " + known);
}

}  // namespace sonarmap
