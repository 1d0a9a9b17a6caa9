/// @file scene.cpp
/// Scene primitives: validation, ray intersection, distance to the surface (see scene.hpp).

#include "sonarmap/sim/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kMinRange_m = 1e-9;  // hits nearer than this are the ray's own starting surface

template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;  // clang 14 has no aggregate CTAD (the fuzz build)

std::string describe(double value) { return std::to_string(value); }

void requireFinite(bool finite, const char* kind, const char* field) {
  if (!finite) throw ValueError(std::string(kind) + ": " + field + " must be finite");
}

void requirePositive(double value, const char* kind, const char* field) {
  if (!(value > 0.0)) throw ValueError(std::string(kind) + ": " + field + " must be > 0, got " + describe(value));
}

void requireReflectivity(double reflectivity, const char* kind) {
  if (!(reflectivity >= 0.0 && reflectivity <= 1.0)) {
    throw ValueError(std::string(kind) + ": reflectivity must be in [0, 1], got " + describe(reflectivity));
  }
}

/// Flips `normal` to face a ray travelling along `direction`.
Eigen::Vector3d facing(const Eigen::Vector3d& normal, const Eigen::Vector3d& direction) {
  return normal.dot(direction) > 0.0 ? Eigen::Vector3d(-normal) : normal;
}

/// Distance to the surface of an axis-aligned box (or a 2D one) from a point given by q = |p| − half
/// per axis in the box's frame: outside, the length of the positive part; inside, the nearest face.
template <class Vector>
double boxSurfaceDistance(const Vector& q) {
  const double outside = q.cwiseMax(0.0).norm();
  return outside > 0.0 ? outside : -q.maxCoeff();
}

Eigen::Matrix3d yawRotation(double yaw_rad) {
  return Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

std::optional<SurfaceHit> intersectPlane(const Plane& plane, const Eigen::Vector3d& unit_normal,
                                         const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction) {
  const double along = unit_normal.dot(direction);
  if (std::abs(along) < 1e-12) return std::nullopt;
  const double range_m = unit_normal.dot(plane.point_m - origin_m) / along;
  if (!(range_m > kMinRange_m)) return std::nullopt;
  return SurfaceHit{range_m, facing(unit_normal, direction)};
}

/// Slab method (Kay & Kajiya 1986) in the box's own frame (turned by `box_to_map` about z); the
/// nearest crossing of its surface.
std::optional<SurfaceHit> intersectBox(const Box& box, const Eigen::Matrix3d& box_to_map,
                                       const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d origin = box_to_map.transpose() * (origin_m - box.center_m);
  const Eigen::Vector3d dir = box_to_map.transpose() * direction;
  const Eigen::Vector3d half = 0.5 * box.size_m;
  double t_near = -std::numeric_limits<double>::infinity();
  double t_far = std::numeric_limits<double>::infinity();
  int axis_near = 0, axis_far = 0;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(dir[axis]) < 1e-15) {
      if (std::abs(origin[axis]) > half[axis]) return std::nullopt;
      continue;
    }
    const double t1 = (-half[axis] - origin[axis]) / dir[axis];
    const double t2 = (half[axis] - origin[axis]) / dir[axis];
    if (std::min(t1, t2) > t_near) {
      t_near = std::min(t1, t2);
      axis_near = axis;
    }
    if (std::max(t1, t2) < t_far) {
      t_far = std::max(t1, t2);
      axis_far = axis;
    }
  }
  if (t_near > t_far) return std::nullopt;
  const bool entering = t_near > kMinRange_m;
  if (!entering && !(t_far > kMinRange_m)) return std::nullopt;
  const int axis = entering ? axis_near : axis_far;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  normal[axis] = dir[axis] > 0.0 ? -1.0 : 1.0;  // the face's normal facing the ray
  return SurfaceHit{entering ? t_near : t_far, box_to_map * normal};
}

std::optional<SurfaceHit> intersectCylinder(const Cylinder& cylinder, const Eigen::Vector3d& origin_m,
                                            const Eigen::Vector3d& direction) {
  const Eigen::Vector3d origin = origin_m - Eigen::Vector3d(cylinder.center_x_m, cylinder.center_y_m, 0.0);
  std::optional<SurfaceHit> best;
  auto consider = [&](double range_m, const Eigen::Vector3d& normal) {
    if (range_m > kMinRange_m && (!best || range_m < best->range_m))
      best = SurfaceHit{range_m, facing(normal, direction)};
  };
  const double r2 = cylinder.radius_m * cylinder.radius_m;
  // Side: |(origin + t·direction)_xy|² = r², within the z range.
  const double a = direction.head<2>().squaredNorm();
  if (a > 1e-24) {
    const double b = origin.head<2>().dot(direction.head<2>());
    const double c = origin.head<2>().squaredNorm() - r2;
    const double discriminant = b * b - a * c;
    if (discriminant >= 0.0) {
      for (const double sign : {-1.0, 1.0}) {
        const double t = (-b + sign * std::sqrt(discriminant)) / a;
        const Eigen::Vector3d p = origin + t * direction;
        if (p.z() >= cylinder.z_min_m && p.z() <= cylinder.z_max_m)
          consider(t, Eigen::Vector3d(p.x(), p.y(), 0.0).normalized());
      }
    }
  }
  // Caps: the discs at z_min and z_max.
  if (std::abs(direction.z()) > 1e-15) {
    for (const double z_m : {cylinder.z_min_m, cylinder.z_max_m}) {
      const double t = (z_m - origin.z()) / direction.z();
      if ((origin + t * direction).head<2>().squaredNorm() <= r2) consider(t, Eigen::Vector3d::UnitZ());
    }
  }
  return best;
}

}  // namespace

const char* primitiveKind(const Primitive& primitive) {
  return std::visit(Overloaded{[](const Plane&) { return "plane"; }, [](const Box&) { return "box"; },
                               [](const Cylinder&) { return "cylinder"; }},
                    primitive);
}

void validatePrimitive(const Primitive& primitive) {
  std::visit(Overloaded{
                 [](const Plane& plane) {
                   requireFinite(plane.point_m.allFinite(), "plane", "point_m");
                   requireFinite(plane.normal.allFinite(), "plane", "normal");
                   if (!(plane.normal.norm() > 0.0)) throw ValueError("plane: normal must be non-zero");
                   requireReflectivity(plane.reflectivity, "plane");
                 },
                 [](const Box& box) {
                   requireFinite(box.center_m.allFinite(), "box", "center_m");
                   requireFinite(box.size_m.allFinite(), "box", "size_m");
                   requireFinite(std::isfinite(box.yaw_rad), "box", "yaw_rad");
                   requirePositive(box.size_m.x(), "box", "size_m.x");
                   requirePositive(box.size_m.y(), "box", "size_m.y");
                   requirePositive(box.size_m.z(), "box", "size_m.z");
                   requireReflectivity(box.reflectivity, "box");
                 },
                 [](const Cylinder& cylinder) {
                   requireFinite(std::isfinite(cylinder.center_x_m) && std::isfinite(cylinder.center_y_m), "cylinder",
                                 "center");
                   requireFinite(std::isfinite(cylinder.z_min_m) && std::isfinite(cylinder.z_max_m), "cylinder",
                                 "z range");
                   requireFinite(std::isfinite(cylinder.radius_m), "cylinder", "radius_m");
                   requirePositive(cylinder.radius_m, "cylinder", "radius_m");
                   if (!(cylinder.z_max_m > cylinder.z_min_m)) {
                     throw ValueError("cylinder: z_max_m (" + describe(cylinder.z_max_m) + ") must be > z_min_m (" +
                                      describe(cylinder.z_min_m) + ")");
                   }
                   requireReflectivity(cylinder.reflectivity, "cylinder");
                 },
             },
             primitive);
}

void validateScene(const Scene& scene) {
  for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
    try {
      validatePrimitive(scene.primitives[i]);
    } catch (const ValueError& error) {
      throw ValueError("scene primitive " + std::to_string(i) + " (" + error.what() + ")");
    }
  }
  if (scene.reverberation_db && !std::isfinite(*scene.reverberation_db)) {
    throw ValueError("scene: reverberation_db must be finite when set");
  }
}

SceneRayCaster::SceneRayCaster(const Scene& scene) : scene_(scene) {
  cached_.reserve(scene.primitives.size());
  for (const Primitive& primitive : scene.primitives) {
    Cached cached;
    std::visit(Overloaded{[&](const Plane& plane) { cached.frame.col(2) = plane.normal.normalized(); },
                          [&](const Box& box) { cached.frame = yawRotation(box.yaw_rad); }, [](const Cylinder&) {}},
               primitive);
    cached.reflectivity = std::visit([](const auto& p) { return p.reflectivity; }, primitive);
    cached_.push_back(cached);
  }
}

std::optional<SurfaceHit> SceneRayCaster::intersect(std::size_t index, const Eigen::Vector3d& origin_m,
                                                    const Eigen::Vector3d& direction) const {
  const Eigen::Matrix3d& frame = cached_[index].frame;
  return std::visit(
      Overloaded{[&](const Plane& plane) { return intersectPlane(plane, frame.col(2), origin_m, direction); },
                 [&](const Box& box) { return intersectBox(box, frame, origin_m, direction); },
                 [&](const Cylinder& cylinder) { return intersectCylinder(cylinder, origin_m, direction); }},
      scene_.primitives[index]);
}

std::optional<SceneHit> SceneRayCaster::firstHit(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction,
                                                 double max_range_m) const {
  std::optional<SceneHit> best;
  for (std::size_t i = 0; i < cached_.size(); ++i) {
    const std::optional<SurfaceHit> hit = intersect(i, origin_m, direction);
    if (!hit || hit->range_m > max_range_m || (best && hit->range_m >= best->surface.range_m)) continue;
    best = SceneHit{*hit, i, cached_[i].reflectivity};
  }
  return best;
}

std::optional<SurfaceHit> intersectRay(const Primitive& primitive, const Eigen::Vector3d& origin_m,
                                       const Eigen::Vector3d& direction) {
  Scene scene;
  scene.primitives.push_back(primitive);
  return SceneRayCaster(scene).intersect(0, origin_m, direction);
}

std::optional<SceneHit> firstHit(const Scene& scene, const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction,
                                 double max_range_m) {
  return SceneRayCaster(scene).firstHit(origin_m, direction, max_range_m);
}

double distanceToSurface(const Primitive& primitive, const Eigen::Vector3d& point_m) {
  return std::visit(
      Overloaded{
          [&](const Plane& plane) { return std::abs(plane.normal.normalized().dot(point_m - plane.point_m)); },
          [&](const Box& box) {
            const Eigen::Vector3d local = yawRotation(box.yaw_rad).transpose() * (point_m - box.center_m);
            return boxSurfaceDistance(Eigen::Vector3d(local.cwiseAbs() - 0.5 * box.size_m));
          },
          [&](const Cylinder& cylinder) {
            // In the (radial, axial) half-plane the closed cylinder is a rectangle.
            const double radial_m = std::hypot(point_m.x() - cylinder.center_x_m, point_m.y() - cylinder.center_y_m);
            const double z_center_m = 0.5 * (cylinder.z_min_m + cylinder.z_max_m);
            const double half_height_m = 0.5 * (cylinder.z_max_m - cylinder.z_min_m);
            return boxSurfaceDistance(
                Eigen::Vector2d(radial_m - cylinder.radius_m, std::abs(point_m.z() - z_center_m) - half_height_m));
          },
      },
      primitive);
}

double distanceToSurface(const Scene& scene, const Eigen::Vector3d& point_m) {
  double nearest_m = std::numeric_limits<double>::infinity();
  for (const Primitive& primitive : scene.primitives)
    nearest_m = std::min(nearest_m, distanceToSurface(primitive, point_m));
  return nearest_m;
}

}  // namespace sonarmap
