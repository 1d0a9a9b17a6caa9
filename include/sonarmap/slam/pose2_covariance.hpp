#pragma once
/// @file pose2_covariance.hpp
/// First-order covariance algebra of planar poses (pose2.hpp): the covariance of a composition
/// and of an inverse, from the Jacobians of the group operations (Smith, Self & Cheeseman 1990,
/// "Estimating uncertain spatial relationships in robotics"). Covariances are of (x, y, yaw) in
/// metres and radians, each in the frame its pose is stated in.

#include <Eigen/Core>

#include "sonarmap/slam/pose2.hpp"

namespace sonarmap {

/// Composes the covariance of a chain of relative poses to first order: the covariance of
/// a ∘ b given cov(a) and cov(b), independent (x, y, yaw; the Jacobians of Pose2 composition).
Eigen::Matrix3d composeCovariance(const Pose2& a, const Eigen::Matrix3d& cov_a, const Pose2& b,
                                  const Eigen::Matrix3d& cov_b);

/// The Jacobian of pose⁻¹ with respect to pose (x, y, yaw).
Eigen::Matrix3d inverseJacobian(const Pose2& pose);

/// The covariance of pose⁻¹ given pose's (first order).
Eigen::Matrix3d inverseCovariance(const Pose2& pose, const Eigen::Matrix3d& covariance);

/// The information of a pose stated in the outer frame (NED) restated in `frame`'s coordinates:
/// the position's rows and columns turned into the frame, the yaw's unchanged.
Eigen::Matrix3d informationInFrame(const Eigen::Matrix3d& information, const Pose2& frame);

}  // namespace sonarmap
