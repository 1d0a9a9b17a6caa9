#pragma once
/// @file scene.hpp
/// Ground-truth scenes for the MSIS simulator: a few geometric primitives with an acoustic
/// reflectivity, ray–surface intersection (range and surface normal, for the echo's incidence-angle
/// falloff) and the distance from a point to the nearest surface (for map evaluation).
///
/// Frame: everything is in the internal map frame (navigation.hpp): NWU, x north, y west, z up,
/// metres. Scene files are written in the map frame the user chose (ENU or NED, scene_file.hpp).
/// Every primitive is a surface; a ray meets it from either side. A box seen from outside is a
/// solid block (a floater, a quay block); seen from inside it is the walls of a water volume (a
/// tank around the sonar). The file format is in scene_file.hpp.

#include <cstddef>
#include <optional>
#include <variant>
#include <vector>

#include <Eigen/Core>

namespace sonarmap {

/// An infinite plane through `point_m` with normal `normal` (any non-zero length; either sense):
/// a floor, the water surface, a wall.
struct Plane {
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double reflectivity = 1.0;  ///< share of the incident energy scattered, [0, 1]
};

/// A box with vertical sides, turned by `yaw_rad` about the vertical through its centre
/// (counter-clockwise seen from above, from the map's +x to the box's first side).
struct Box {
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d size_m = Eigen::Vector3d::Ones();  ///< edge lengths along the box's own x, y, z, > 0
  double yaw_rad = 0.0;
  double reflectivity = 1.0;  ///< [0, 1]
};

/// A closed vertical cylinder (a pile): axis through (center_x_m, center_y_m), from z_min_m to
/// z_max_m, with its two end caps.
struct Cylinder {
  double center_x_m = 0.0;
  double center_y_m = 0.0;
  double radius_m = 0.1;  ///< > 0
  double z_min_m = -1.0;
  double z_max_m = 1.0;       ///< > z_min_m
  double reflectivity = 1.0;  ///< [0, 1]
};

using Primitive = std::variant<Plane, Box, Cylinder>;

/// The ground truth: primitives in the map frame.
struct Scene {
  std::vector<Primitive> primitives;
  /// The diffuse reverberation of an enclosed basin (a tank), none in open water: sound that has
  /// met the enclosure's walls keeps bouncing between them and fills every later bin. Its mean
  /// power after the head's TVG, dB in the echo model's units (msis_simulator.hpp: re the echo of
  /// a perfect reflector filling the beam at normal incidence), taken constant from the range of
  /// the first surface the beam's axis meets to the end of the beam (over a few metres the
  /// field's decay and the TVG's rise roughly cancel). Finite when set. Measured on the CRAS tank
  /// log for `tank` (builtin_scenes.hpp); a property of the place, not of the head.
  std::optional<double> reverberation_db = std::nullopt;
};

/// Where a ray meets a surface.
struct SurfaceHit {
  double range_m = 0.0;  ///< distance from the ray's origin along its unit direction, metres, > 0
  /// Unit normal of the surface at the hit, map frame, facing the ray (normal · direction ≤ 0), so
  /// −normal · direction is the cosine of the incidence angle.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

/// A hit on a scene: the nearest surface along the ray.
struct SceneHit {
  SurfaceHit surface;
  std::size_t primitive = 0;  ///< index into Scene::primitives
  double reflectivity = 0.0;  ///< that primitive's reflectivity
};

/// Checks one primitive: every number finite, normal non-zero, sizes and radius > 0,
/// z_max_m > z_min_m, reflectivity in [0, 1].
/// @throws ValueError naming the primitive's kind and the offending field.
void validatePrimitive(const Primitive& primitive);

/// Checks every primitive of `scene` (validatePrimitive).
/// @throws ValueError naming the primitive's index, kind and field.
void validateScene(const Scene& scene);

/// The kind's name as the scene file writes it: "plane", "box" or "cylinder".
const char* primitiveKind(const Primitive& primitive);

/// The first intersection of the ray origin_m + t · direction, t > 1e-9 m, with the primitive's
/// surface (boxes: slab method, Kay & Kajiya 1986; cylinders: side quadric and end discs). A ray
/// parallel to a plane misses it. The primitive is assumed valid (validatePrimitive).
/// @param origin_m   ray origin, map frame, metres.
/// @param direction  unit direction, map frame (not checked; a non-unit one scales range_m).
/// @return nullopt when the ray misses.
std::optional<SurfaceHit> intersectRay(const Primitive& primitive, const Eigen::Vector3d& origin_m,
                                       const Eigen::Vector3d& direction);

/// The nearest surface of the scene along the ray within max_range_m (intersectRay on every
/// primitive; ties go to the primitive listed first). nullopt when nothing is within reach.
std::optional<SceneHit> firstHit(const Scene& scene, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction,
                                 double max_range_m);

/// A scene prepared for many ray queries: each box's rotation and each plane's unit normal are
/// computed once. Keeps a reference to the scene, which must outlive it and not change.
class SceneRayCaster {
 public:
  explicit SceneRayCaster(const Scene& scene);

  /// As the free firstHit() above.
  std::optional<SceneHit> firstHit(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction,
                                   double max_range_m) const;

  /// As intersectRay() above, for primitive `index` of the scene (< its size).
  std::optional<SurfaceHit> intersect(std::size_t index, const Eigen::Vector3d& origin_m,
                                      const Eigen::Vector3d& direction) const;

 private:
  struct Cached {
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();  ///< box: its rotation; plane: unit normal in column 2
    double reflectivity = 0.0;
  };
  const Scene& scene_;
  std::vector<Cached> cached_;
};

/// Euclidean distance from `point_m` (map frame) to the nearest point of the primitive's surface,
/// metres, ≥ 0 (0 on the surface; also for points inside a box or cylinder it is the distance to
/// the nearest face, not 0).
double distanceToSurface(const Primitive& primitive, const Eigen::Vector3d& point_m);

/// Distance from `point_m` to the nearest surface of the scene, metres; +infinity for an empty
/// scene. Used to score maps: an occupied voxel within a tolerance of a surface is a true positive.
double distanceToSurface(const Scene& scene, const Eigen::Vector3d& point_m);

}  // namespace sonarmap
