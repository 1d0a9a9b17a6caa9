#pragma once
/// @file pose2.hpp
/// A planar rigid pose (x, y, heading) and its group operations: the state of the pose graph and of
/// the scan matcher (3 degrees of freedom; depth, roll and pitch come from the sensors).
///
/// Frame: the horizontal plane of NED (navigation.hpp): x north, y east, metres; heading clockwise
/// from north seen from above, radians (NavSample::yaw_rad). A Pose2 `a_to_b` maps coordinates in
/// frame a to frame b: p_b = R(yaw) p_a + (x, y), R(yaw) = [cos −sin; sin cos] (x north, y east is
/// a right-handed plane seen from below, so this is NED's yaw rotation restricted to the plane).

#include <cmath>
#include <numbers>

#include <Eigen/Core>

namespace sonarmap {

/// Wraps an angle to [−π, π), radians.
inline double wrapAngle_rad(double angle_rad) {
  return angle_rad - 2.0 * std::numbers::pi * std::floor((angle_rad + std::numbers::pi) / (2.0 * std::numbers::pi));
}

/// A planar rigid transform: rotation by yaw_rad, then translation by (x_m, y_m).
struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;

  Eigen::Matrix2d rotation() const {
    const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
    return (Eigen::Matrix2d() << c, -s, s, c).finished();
  }
  Eigen::Vector2d translation() const { return {x_m, y_m}; }
  /// This pose applied to a point: R p + t.
  Eigen::Vector2d operator*(const Eigen::Vector2d& point) const { return rotation() * point + translation(); }
  /// Composition: (this ∘ other)(p) = this(other(p)); the yaw of the result is wrapped.
  Pose2 operator*(const Pose2& other) const {
    const Eigen::Vector2d t = *this * other.translation();
    return {t.x(), t.y(), wrapAngle_rad(yaw_rad + other.yaw_rad)};
  }
  Pose2 inverse() const {
    const Eigen::Vector2d t = -(rotation().transpose() * translation());
    return {t.x(), t.y(), wrapAngle_rad(-yaw_rad)};
  }
  /// `to` expressed in this pose's frame: inverse() ∘ to (the relative pose of a graph edge).
  Pose2 between(const Pose2& to) const { return inverse() * to; }
  Eigen::Vector3d vector() const { return {x_m, y_m, yaw_rad}; }
};

}  // namespace sonarmap
