/// @file loop_consistency.cpp
/// The gates of a loop closure (localizer.hpp): dead reckoning's covariance along a path of the
/// graph, and the pairwise consistency of two loop closures (Mangelson et al. 2018).

#include <cmath>

#include "sonarmap/slam/localizer.hpp"
#include "loop_gates.hpp"

namespace sonarmap {
namespace {

/// Covariance of pose⁻¹ given pose's (first order).
Eigen::Matrix3d inverseCovariance(const Pose2& pose, const Eigen::Matrix3d& covariance) {
  const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
  Eigen::Matrix3d j;
  j << -c, -s, s * pose.x_m - c * pose.y_m,  //
      s, -c, c * pose.x_m + s * pose.y_m,    //
      0.0, 0.0, -1.0;
  return j * covariance * j.transpose();
}

/// Squared Mahalanobis distance of a relative pose from the identity.
double chi2(const Pose2& error, const Eigen::Matrix3d& covariance) {
  const Eigen::Vector3d e(error.x_m, error.y_m, wrapAngle_rad(error.yaw_rad));
  return e.dot(covariance.ldlt().solve(e));
}

}  // namespace

Eigen::Matrix3d Localizer::pathCovariance(std::size_t a, std::size_t b) const {
  Pose2 chain;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t k = a + 1; k <= b; ++k) {
    covariance = composeCovariance(chain, covariance, odometry_[k], odometry_cov_[k]);
    chain = chain * odometry_[k];
  }
  return covariance;
}

std::vector<Eigen::Matrix3d> Localizer::pathCovariancesTo(std::size_t b) const {
  // Backwards: the path from a is odometry a → a+1 followed by the path from a+1.
  std::vector<Eigen::Matrix3d> covariances(b + 1, Eigen::Matrix3d::Zero());
  Pose2 chain;  // the path from a+1 to b
  for (std::size_t a = b; a-- > 0;) {
    covariances[a] = composeCovariance(odometry_[a + 1], odometry_cov_[a + 1], chain, covariances[a + 1]);
    chain = odometry_[a + 1] * chain;
  }
  return covariances;
}

/// The cycle of loops (j1 → k1, z1) and (j2 → k2, z2): z1 ∘ est(k1 → k2) ∘ z2⁻¹ ∘ est(j2 → j1)
/// should be the identity; its covariance adds both matches' and dead reckoning's along the two
/// paths between their ends.
bool Localizer::consistentWithAccepted(const LoopClosure& loop, const Eigen::Matrix3d& covariance) const {
  const auto pathBetween = [this](std::size_t from, std::size_t to) {
    const Pose2 estimate = graph_.pose(from).between(graph_.pose(to));
    if (from <= to) return std::make_pair(estimate, pathCovariance(from, to));
    return std::make_pair(estimate, inverseCovariance(estimate.inverse(), pathCovariance(to, from)));
  };
  for (std::size_t i = 0; i < accepted_loops_.size(); ++i) {
    const LoopClosure& other = report_.loop_closures[accepted_loops_[i]];
    const auto [k1_to_k2, k_cov] = pathBetween(loop.to, other.to);
    const auto [j2_to_j1, j_cov] = pathBetween(other.from, loop.from);
    Pose2 cycle = loop.measurement;
    Eigen::Matrix3d cycle_cov = covariance;
    cycle_cov = composeCovariance(cycle, cycle_cov, k1_to_k2, k_cov);
    cycle = cycle * k1_to_k2;
    const Pose2 back = other.measurement.inverse();
    cycle_cov = composeCovariance(cycle, cycle_cov, back, inverseCovariance(other.measurement, loop_cov_[i]));
    cycle = cycle * back;
    cycle_cov = composeCovariance(cycle, cycle_cov, j2_to_j1, j_cov);
    cycle = cycle * j2_to_j1;
    if (chi2(cycle, cycle_cov) > options_.consistency_chi2) return false;
  }
  return true;
}

double loopChi2(const Pose2& measured, const Pose2& estimated, const Eigen::Matrix3d& covariance) {
  return chi2(estimated.between(measured), covariance);
}

}  // namespace sonarmap
