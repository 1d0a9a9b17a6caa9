#pragma once
/// @file loop_gates.hpp
/// Internal to the slam layer: the χ² of a loop closure against the current estimate
/// (loop_consistency.cpp), used by the Localizer's gate.

#include <Eigen/Core>

#include "sonarmap/slam/pose2.hpp"

namespace sonarmap {

/// Squared Mahalanobis distance of `measured` from `estimated` (both the newer scan in the older
/// one's frame) under `covariance` (x, y, yaw), 3 degrees of freedom.
double loopChi2(const Pose2& measured, const Pose2& estimated, const Eigen::Matrix3d& covariance);

}  // namespace sonarmap
