#pragma once
/// @file pose_checks.hpp
/// Private to the simulator: the checks and wrapping its options and beams share.

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace sonarmap::sim {

/// Whether `pose` is finite with an orthonormal, right-handed rotation (to 1e-6).
inline bool isRigid(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d rotation = pose.linear();
  return pose.matrix().allFinite() && (rotation * rotation.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
         std::abs(rotation.determinant() - 1.0) < 1e-6;
}

/// `bearing_rad` wrapped to [0, 2π).
inline double wrapBearing(double bearing_rad) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const double wrapped = std::fmod(bearing_rad, kTwoPi);
  return wrapped < 0.0 ? wrapped + kTwoPi : (wrapped >= kTwoPi ? 0.0 : wrapped);
}

}  // namespace sonarmap::sim
