/// @file builtin_scenes.cpp
/// The built-in scenes (see builtin_scenes.hpp for their geometry and its sources).

#include "sonarmap/sim/builtin_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
/// The CRAS tank's diffuse reverberation (Scene::reverberation_db), fitted on the real log (see tankScene).
constexpr double kTankReverberation_db = -27.0;

/// How a scene drawn for the Micron at 5 m is stretched for another head (builtin_scenes.hpp).
struct SceneScale {
  double across = 1.0;  ///< s: lengths in the horizontal plane
  double height = 1.0;  ///< h: heights of horizontal surfaces and of what stands near them

  /// A pile's radius: a real pile's, not scaled beyond 0.3 m nor below 0.2 m.
  double pileRadius_m() const { return std::clamp(0.2 * across, 0.2, 0.3); }
};

Plane horizontalPlane(double z_m, double reflectivity) {
  return Plane{{0.0, 0.0, z_m}, Eigen::Vector3d::UnitZ(), reflectivity};
}

Scene tankScene(const SceneScale& scale) {
  const double s = scale.across, h = scale.height;
  const double surface_m = 0.47 * h;  // water surface above the head: ring at 0.47 / sin(17.5°) = 1.56 m
  Scene scene;
  scene.primitives.push_back(horizontalPlane(surface_m, 1.0));
  scene.primitives.push_back(horizontalPlane(-1.5 * h, 0.5));  // floor
  // Inner faces x ∈ [−2.1, 2.1], y ∈ [−1.8, 2.6]; taller than the water so that only the planes
  // above close the volume at the surface and the floor.
  scene.primitives.push_back(Box{{0.0, 0.4 * s, -0.5 * h}, {4.2 * s, 4.4 * s, 3.0 * h}, 0.0, 0.9});
  // Floater: its near face ≈ 1.95 m from the head at bearing 95°, long side across the line of
  // sight, half above the surface (the real log's floater: a 1 m line at about that place).
  const double bearing_rad = 95.0 * kDegree;
  const double center_range_m = 2.15 * s;
  scene.primitives.push_back(Box{{center_range_m * std::cos(bearing_rad), center_range_m * std::sin(bearing_rad), surface_m},
                                 {1.0 * s, 0.4 * s, 0.3 * h},
                                 bearing_rad - 90.0 * kDegree,
                                 0.8});
  scene.reverberation_db = kTankReverberation_db;
  return scene;
}

/// Reflectivities of the waterfront layout shared by `harbour` and `soft`.
struct Waterfront {
  double quay = 0.9;
  double piles = 0.85;
  double seabed = 0.5;
};

/// A quay (or embankment) face at x = 3.5 m, five piles 2 m apart along y at x = 2 m, seabed
/// 1.3 m below the head, surface 3 m above (at 5 m reach; see builtin_scenes.hpp).
Scene waterfrontScene(const SceneScale& scale, const Waterfront& reflectivity) {
  const double s = scale.across, h = scale.height;
  const double seabed_m = -1.3 * h;  // enters the ±17.5° aperture at 1.3 / sin(17.5°) ≈ 4.3 m
  const double top_m = 3.5 * h;      // quay and piles stand out of the water
  Scene scene;
  scene.primitives.push_back(horizontalPlane(3.0 * h, 1.0));  // surface, beyond the aperture within reach
  scene.primitives.push_back(horizontalPlane(seabed_m, reflectivity.seabed));
  // Quay: a 40 m long block, face at x = 3.5 m.
  scene.primitives.push_back(
      Box{{6.0 * s, 0.0, 0.5 * (seabed_m + top_m)}, {5.0 * s, 40.0 * s, top_m - seabed_m}, 0.0, reflectivity.quay});
  for (const double y_m : {-4.0, -2.0, 0.0, 2.0, 4.0}) {
    scene.primitives.push_back(Cylinder{2.0 * s, y_m * s, scale.pileRadius_m(), seabed_m, top_m, reflectivity.piles});
  }
  return scene;
}

Scene hullScene(const SceneScale& scale) {
  const double s = scale.across, h = scale.height;
  const double surface_m = 3.0 * h, seabed_m = -1.3 * h;
  const double keel_m = -0.9 * h, deck_m = surface_m + 1.0 * h;
  Scene scene;
  scene.primitives.push_back(horizontalPlane(surface_m, 1.0));
  scene.primitives.push_back(horizontalPlane(seabed_m, 0.5));
  // Hull: x ∈ [−2, 2] m, near side at y = 2 m, 2.5 m wide, keel to 1 m above the surface.
  scene.primitives.push_back(Box{{0.0, 3.25 * s, 0.5 * (keel_m + deck_m)}, {4.0 * s, 2.5 * s, deck_m - keel_m}, 0.0, 0.95});
  for (const double x_m : {-3.25, 3.25}) {  // mooring dolphins off the bow and the stern
    scene.primitives.push_back(Cylinder{x_m * s, 2.25 * s, scale.pileRadius_m(), seabed_m, deck_m, 0.85});
  }
  return scene;
}

Scene openWaterScene(const SceneScale& scale) {
  // 1.1 R above and below: beyond the reach in every direction.
  Scene scene;
  scene.primitives.push_back(horizontalPlane(5.5 * scale.across, 1.0));
  scene.primitives.push_back(horizontalPlane(-5.5 * scale.across, 0.5));
  return scene;
}

/// The 3D harbour corner `quay3d` (builtin_scenes.hpp), every length scaled by `s`.
Scene quay3dScene(double s) {
  // The water surface at z = 0 (a depth sensor's depth 0, nedToMap). Seabed z = −5 − x / 8 (at
  // s = 1): −4.5 m at x = −4, −5.5 m at x = +4.
  auto seabed_z_m = [s](double x_m) { return -5.0 * s - x_m / 8.0; };
  Scene scene;
  scene.primitives.push_back(horizontalPlane(0.0, 1.0));
  scene.primitives.push_back(Plane{{0.0, 0.0, -5.0 * s}, Eigen::Vector3d(1.0, 0.0, 8.0).normalized(), 0.5});
  // Quay: x ∈ [3.5, 8.5], y ∈ [−20, 20], z ∈ [−6.5, 1.0]: below the seabed (−6.06 m at x = 8.5) to
  // 1 m above the surface.
  scene.primitives.push_back(Box{{6.0 * s, 0.0, -2.75 * s}, {5.0 * s, 40.0 * s, 7.5 * s}, 0.0, 0.9});
  for (const auto& [x, y] : {std::pair{2.0, -2.5}, std::pair{2.0, 2.5}, std::pair{-3.0, -2.5}}) {
    scene.primitives.push_back(Cylinder{x * s, y * s, 0.2 * s, seabed_z_m(x * s) - 0.3 * s, 1.0 * s, 0.85});
  }
  // Boulder: 0.8 × 0.6 × 0.5 m, yawed 30°, its bottom 0.1 m below the seabed under its centre (the
  // slope changes the seabed's height by less than 0.07 m over its footprint).
  const double boulder_x_m = -1.5 * s, boulder_bottom_m = seabed_z_m(boulder_x_m) - 0.1 * s;
  scene.primitives.push_back(Box{{boulder_x_m, -1.0 * s, boulder_bottom_m + 0.25 * s},
                                 {0.8 * s, 0.6 * s, 0.5 * s},
                                 30.0 * kDegree,
                                 0.7});
  // Pontoon: x ∈ [−1.25, 1.25], y ∈ [2.4, 3.6], z ∈ [−3.1, 0.3]: its underside overhangs water.
  scene.primitives.push_back(Box{{0.0, 3.0 * s, -1.4 * s}, {2.5 * s, 1.2 * s, 3.4 * s}, 0.0, 0.9});
  return scene;
}

}  // namespace

std::vector<std::string> builtinSceneNames() { return {"tank", "harbour", "hull", "soft", "open-water"}; }

std::vector<std::string> builtinScene3dNames() { return {"quay3d"}; }

Scene builtinScene(std::string_view name, double reach_m, double vertical_beam_width_rad) {
  if (!(std::isfinite(reach_m) && reach_m > 0.0)) {
    throw ValueError("builtin scene: reach_m must be > 0, got " + std::to_string(reach_m));
  }
  if (!(std::isfinite(vertical_beam_width_rad) && vertical_beam_width_rad > 0.0 &&
        vertical_beam_width_rad < std::numbers::pi)) {
    throw ValueError("builtin scene: vertical_beam_width_rad must be in (0, π), got " +
                     std::to_string(vertical_beam_width_rad));
  }
  SceneScale scale;
  scale.across = reach_m / kBuiltinSceneReach_m;
  scale.height = scale.across * (std::sin(0.5 * vertical_beam_width_rad) /
                                 std::sin(0.5 * kBuiltinSceneVerticalBeamWidth_rad));
  if (name == "tank") return tankScene(scale);
  if (name == "harbour") return waterfrontScene(scale, Waterfront{});
  if (name == "hull") return hullScene(scale);
  if (name == "soft") return waterfrontScene(scale, Waterfront{0.06, 0.09, 0.3});
  if (name == "open-water") return openWaterScene(scale);
  if (name == "quay3d") return quay3dScene(scale.across);
  std::string known;
  for (const auto& names : {builtinSceneNames(), builtinScene3dNames()}) {
    for (const std::string& candidate : names) known += (known.empty() ? "" : ", ") + candidate;
  }
  throw ValueError("unknown scene '" + std::string(name) + "', expected one of: " + known);
}

double builtinSceneDepth_m(std::string_view name, double reach_m) {
  builtinScene(name, reach_m);  // validates the name and the reach
  return name == "quay3d" ? 3.0 * reach_m / kBuiltinSceneReach_m : 0.0;
}

}  // namespace sonarmap
