/// @file pose2_covariance.cpp
/// composeCovariance and inverseCovariance (pose2_covariance.hpp).

#include "sonarmap/slam/pose2_covariance.hpp"

#include <cmath>

namespace sonarmap {

Eigen::Matrix3d composeCovariance(const Pose2& a, const Eigen::Matrix3d& cov_a, const Pose2& b,
                                  const Eigen::Matrix3d& cov_b) {
  const double c = std::cos(a.yaw_rad), s = std::sin(a.yaw_rad);
  Eigen::Matrix3d j_a = Eigen::Matrix3d::Identity();
  j_a(0, 2) = -s * b.x_m - c * b.y_m;
  j_a(1, 2) = c * b.x_m - s * b.y_m;
  Eigen::Matrix3d j_b = Eigen::Matrix3d::Identity();
  j_b.topLeftCorner<2, 2>() = a.rotation();
  return j_a * cov_a * j_a.transpose() + j_b * cov_b * j_b.transpose();
}

Eigen::Matrix3d inverseJacobian(const Pose2& pose) {
  const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
  Eigen::Matrix3d j;
  j << -c, -s, s * pose.x_m - c * pose.y_m,  //
      s, -c, c * pose.x_m + s * pose.y_m,    //
      0.0, 0.0, -1.0;
  return j;
}

Eigen::Matrix3d inverseCovariance(const Pose2& pose, const Eigen::Matrix3d& covariance) {
  const Eigen::Matrix3d j = inverseJacobian(pose);
  return j * covariance * j.transpose();
}

Eigen::Matrix3d informationInFrame(const Eigen::Matrix3d& information, const Pose2& frame) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Identity();
  a.topLeftCorner<2, 2>() = frame.rotation();
  return a.transpose() * information * a;
}

}  // namespace sonarmap
