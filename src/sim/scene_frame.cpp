/// @file scene_frame.cpp
/// Primitives moved between NWU and a user's frame by a signed axis permutation (see
/// scene_frame.hpp).

#include "sonarmap/sim/scene_frame.hpp"

#include <utility>
#include <variant>

namespace sonarmap {
namespace {

/// `value` with a negative zero made positive (a file then never shows "-0").
double plainZero(double value) { return value + 0.0; }

Eigen::Vector3d turnedVector(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& v) {
  const Eigen::Vector3d out = rotation * v;  // one non-zero term per row: exact
  return {plainZero(out.x()), plainZero(out.y()), plainZero(out.z())};
}

/// `primitive` with its coordinates multiplied by `rotation`: a signed permutation of the axes,
/// determinant +1, that keeps z along z (rotation(2, 2) = ±1).
Primitive turned(const Primitive& primitive, const Eigen::Matrix3d& rotation) {
  const double z_sign = rotation(2, 2);
  // The 2 × 2 horizontal block either keeps each axis on itself (diagonal) or swaps x and y.
  const bool swaps_xy = rotation(0, 0) == 0.0;
  const double horizontal_det = rotation(0, 0) * rotation(1, 1) - rotation(0, 1) * rotation(1, 0);
  if (const auto* plane = std::get_if<Plane>(&primitive)) {
    return Plane{turnedVector(rotation, plane->point_m), turnedVector(rotation, plane->normal), plane->reflectivity};
  }
  if (const auto* box = std::get_if<Box>(&primitive)) {
    // Axis a1 = (cos ψ, sin ψ) goes to R a1. Diagonal block diag(s, s·d): R a1 = s · a1(d ψ).
    // Swapping block: R a2 (a2 = (−sin ψ, cos ψ)) = ± a1(d ψ), so the sizes along x and y swap.
    Eigen::Vector3d size_m = box->size_m;
    if (swaps_xy) std::swap(size_m.x(), size_m.y());
    return Box{turnedVector(rotation, box->center_m), size_m, plainZero(horizontal_det * box->yaw_rad), box->reflectivity};
  }
  const auto& cylinder = std::get<Cylinder>(primitive);
  const Eigen::Vector3d axis_m = turnedVector(rotation, {cylinder.center_x_m, cylinder.center_y_m, 0.0});
  const double z_min_m = z_sign > 0.0 ? cylinder.z_min_m : plainZero(-cylinder.z_max_m);
  const double z_max_m = z_sign > 0.0 ? cylinder.z_max_m : plainZero(-cylinder.z_min_m);
  return Cylinder{axis_m.x(), axis_m.y(), cylinder.radius_m, z_min_m, z_max_m, cylinder.reflectivity};
}

Scene turnedScene(const Scene& scene, const Eigen::Matrix3d& rotation) {
  Scene out;
  out.reverberation_db = scene.reverberation_db;
  out.primitives.reserve(scene.primitives.size());
  for (const Primitive& primitive : scene.primitives) out.primitives.push_back(turned(primitive, rotation));
  return out;
}

}  // namespace

Primitive primitiveInFrame(const Primitive& nwu, MapFrame frame) { return turned(nwu, nwuToMapFrame(frame)); }

Primitive primitiveFromFrame(const Primitive& framed, MapFrame frame) {
  return turned(framed, nwuToMapFrame(frame).transpose());
}

Scene sceneInFrame(const Scene& nwu, MapFrame frame) { return turnedScene(nwu, nwuToMapFrame(frame)); }

Scene sceneFromFrame(const Scene& framed, MapFrame frame) {
  return turnedScene(framed, nwuToMapFrame(frame).transpose());
}

}  // namespace sonarmap
