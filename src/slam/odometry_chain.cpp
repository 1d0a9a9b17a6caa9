/// @file odometry_chain.cpp
/// OdometryChain (odometry_chain.hpp): prefix sums of the first-order composed covariance.

#include "sonarmap/slam/odometry_chain.hpp"

#include "sonarmap/slam/pose2_covariance.hpp"

namespace sonarmap {
namespace {

/// The quarter turn J: J v is v turned by +90°.
Eigen::Matrix2d quarterTurn() { return (Eigen::Matrix2d() << 0.0, -1.0, 1.0, 0.0).finished(); }

}  // namespace

OdometryChain::OdometryChain(double origin_heading_rad)
    : poses_{Pose2{}},
      motions_{Pose2{}},
      translation_{Eigen::Matrix2d::Zero()},
      yaw_{0.0},
      yaw_p_{Eigen::Vector2d::Zero()},
      yaw_pp_{Eigen::Matrix2d::Zero()},
      cross_{Eigen::Vector2d::Zero()},
      cross_p_{Eigen::Matrix2d::Zero()},
      deviation_{Eigen::Matrix2d::Zero()},
      origin_heading_rad_(origin_heading_rad) {}

void OdometryChain::accumulate(std::size_t i, const Eigen::Matrix3d& covariance) {
  const Eigen::Matrix2d rotation = poses_[i - 1].rotation();
  const Eigen::Vector2d p = poses_[i].translation();
  const double y = covariance(2, 2);
  const Eigen::Vector2d c = rotation * covariance.topRightCorner<2, 1>();
  translation_[i] = translation_[i - 1] + rotation * covariance.topLeftCorner<2, 2>() * rotation.transpose();
  yaw_[i] = yaw_[i - 1] + y;
  yaw_p_[i] = yaw_p_[i - 1] + y * p;
  yaw_pp_[i] = yaw_pp_[i - 1] + y * p * p.transpose();
  cross_[i] = cross_[i - 1] + c;
  cross_p_[i] = cross_p_[i - 1] + c * p.transpose();
}

void OdometryChain::append(const Pose2& motion, const Eigen::Matrix3d& covariance) {
  poses_.push_back(poses_.back() * motion);
  motions_.push_back(motion);
  translation_.emplace_back();
  yaw_.emplace_back();
  yaw_p_.emplace_back();
  yaw_pp_.emplace_back();
  cross_.emplace_back();
  cross_p_.emplace_back();
  const std::size_t i = poses_.size() - 1;
  const double start_heading_rad = origin_heading_rad_ + poses_[i - 1].yaw_rad;
  deviation_.push_back(deviation_[i - 1] + (poses_[i].translation() - poses_[i - 1].translation()) *
                                               Eigen::RowVector2d(std::cos(start_heading_rad), std::sin(start_heading_rad)));
  accumulate(i, covariance);
}

void OdometryChain::restate(const std::vector<Eigen::Matrix3d>& covariances) {
  for (std::size_t i = 1; i < poses_.size(); ++i) accumulate(i, covariances[i]);
}

Pose2 OdometryChain::between(std::size_t a, std::size_t b) const { return poses_[a].between(poses_[b]); }

Eigen::Matrix3d OdometryChain::forwardCovariance(std::size_t a, std::size_t b) const {
  const Eigen::Matrix2d j = quarterTurn();
  const Eigen::Vector2d pb = poses_[b].translation();
  const double s0 = yaw_[b] - yaw_[a];
  const Eigen::Vector2d s1 = yaw_p_[b] - yaw_p_[a];
  const Eigen::Matrix2d s2 = yaw_pp_[b] - yaw_pp_[a];
  const Eigen::Vector2d sc = cross_[b] - cross_[a];
  const Eigen::Matrix2d scp = cross_p_[b] - cross_p_[a];
  // Σ y (p_b − p)(p_b − p)ᵀ and Σ c (p_b − p)ᵀ from the prefix sums.
  const Eigen::Matrix2d lever = s0 * pb * pb.transpose() - pb * s1.transpose() - s1 * pb.transpose() + s2;
  const Eigen::Matrix2d cross_lever = sc * pb.transpose() - scp;
  Eigen::Matrix3d covariance;
  covariance.topLeftCorner<2, 2>() = (translation_[b] - translation_[a]) + j * lever * j.transpose() +
                                     cross_lever * j.transpose() + j * cross_lever.transpose();
  const Eigen::Vector2d position_yaw = sc + j * (s0 * pb - s1);
  covariance.topRightCorner<2, 1>() = position_yaw;
  covariance.bottomLeftCorner<1, 2>() = position_yaw.transpose();
  covariance(2, 2) = s0;
  return covariance;
}

Eigen::Matrix<double, 3, 2> OdometryChain::deviationSensitivity(std::size_t a, std::size_t b) const {
  Eigen::Matrix<double, 3, 2> sensitivity = Eigen::Matrix<double, 3, 2>::Zero();
  if (a == b) return sensitivity;
  if (b < a) return inverseJacobian(between(b, a)) * deviationSensitivity(b, a);
  const auto coefficients = [this](std::size_t node) {
    const double heading_rad = origin_heading_rad_ + poses_[node].yaw_rad;
    return Eigen::RowVector2d(std::cos(heading_rad), std::sin(heading_rad));
  };
  // Each step turned by δ at its start less δ at node a, in the chain's frame, then into a's.
  const Eigen::Matrix2d position = quarterTurn() * (deviation_[b] - deviation_[a] -
                                                    (poses_[b].translation() - poses_[a].translation()) * coefficients(a));
  sensitivity.topRows<2>() = poses_[a].rotation().transpose() * position;
  sensitivity.row(2) = coefficients(b) - coefficients(a);
  return sensitivity;
}

Eigen::Matrix3d OdometryChain::covariance(std::size_t a, std::size_t b) const {
  if (a == b) return Eigen::Matrix3d::Zero();
  if (b < a) return inverseCovariance(between(b, a), covariance(b, a));
  // From the chain's frame into node a's: the position part turned by R_aᵀ.
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
  turn.topLeftCorner<2, 2>() = poses_[a].rotation().transpose();
  const Eigen::Matrix3d covariance = turn * forwardCovariance(a, b) * turn.transpose();
  return 0.5 * (covariance + covariance.transpose());
}

}  // namespace sonarmap
