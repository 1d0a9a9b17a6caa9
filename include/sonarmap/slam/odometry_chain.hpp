#pragma once
/// @file odometry_chain.hpp
/// Dead reckoning as a chain of relative poses between consecutive scans, each with its
/// covariance, and the relative pose of any two scans with the covariance the chain between them
/// accumulates: to first order (composeCovariance, pose2_covariance.hpp, composed along the path;
/// Smith, Self & Cheeseman 1990), computed in O(1) per pair from prefix sums.
///
/// An edge i (node i − 1 → i) contributes its translation error, turned into the chain's frame,
/// and its heading error, which swings every later node about node i: for a path a → b,
///   δp_b = Σ_{i=a+1..b} R_{i−1} δt_i + J (p_b − p_i) δθ_i,   δθ_b = Σ δθ_i,
/// J the quarter turn, p_i and R_i node i's position and rotation in the chain's frame. The sums
/// over i expand into prefix sums of the edges' covariances weighted by 1, p_i and p_i p_iᵀ, so any
/// path's covariance is a few differences of them. Positions are relative to the first node, so the
/// sums stay small for any survey (a navigation in UTM included).

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/slam/pose2.hpp"

namespace sonarmap {

class OdometryChain {
 public:
  /// A chain of one node (the first scan), whose heading in the outer frame (NED yaw, radians) is
  /// `origin_heading_rad`: the heading sensor's deviation depends on the absolute heading.
  explicit OdometryChain(double origin_heading_rad = 0.0);
  /// Appends a node: `motion` from the last node (in its frame) with `covariance` (x, y, yaw in
  /// that frame; m², rad²).
  void append(const Pose2& motion, const Eigen::Matrix3d& covariance);
  /// Replaces the covariance of every edge (edge i: node i − 1 → i, i ≥ 1; index 0 unused), the
  /// motions kept. @pre covariances.size() == size().
  void restate(const std::vector<Eigen::Matrix3d>& covariances);

  std::size_t size() const { return poses_.size(); }
  /// Node b's pose in node a's frame by the chain (any a, b < size()).
  Pose2 between(std::size_t a, std::size_t b) const;
  /// Its covariance in node a's frame (x, y, yaw; zero for a == b); for b < a the inverse path's.
  Eigen::Matrix3d covariance(std::size_t a, std::size_t b) const;
  /// How node b's pose in node a's frame moves with the heading sensor's deviation coefficients
  /// (a, b of δ(ψ) = a cos ψ + b sin ψ, odometry_noise.hpp): the rows x, y, yaw, the columns a, b.
  /// The heading error on each step is δ at its start, taken relative to δ at node a (node a's own
  /// frame turns with it). A covariance of the coefficients C adds G C Gᵀ to covariance(a, b).
  Eigen::Matrix<double, 3, 2> deviationSensitivity(std::size_t a, std::size_t b) const;

 private:
  /// covariance(a, b) for a < b, in the chain's frame.
  Eigen::Matrix3d forwardCovariance(std::size_t a, std::size_t b) const;
  void accumulate(std::size_t i, const Eigen::Matrix3d& covariance);

  std::vector<Pose2> poses_;  ///< node i in the chain's frame (node 0 at the origin)
  std::vector<Pose2> motions_;  ///< edge i's motion (index 0 unused)
  // Prefix sums over edges 1..i (index i), in the chain's frame.
  std::vector<Eigen::Matrix2d> translation_;  ///< Σ R C_tt Rᵀ
  std::vector<double> yaw_;                   ///< Σ C_θθ
  std::vector<Eigen::Vector2d> yaw_p_;        ///< Σ C_θθ p_i
  std::vector<Eigen::Matrix2d> yaw_pp_;       ///< Σ C_θθ p_i p_iᵀ
  std::vector<Eigen::Vector2d> cross_;        ///< Σ R C_tθ
  std::vector<Eigen::Matrix2d> cross_p_;      ///< Σ R C_tθ p_iᵀ
  std::vector<Eigen::Matrix2d> deviation_;    ///< Σ Δp_i c_{i−1}ᵀ, c = (cos ψ, sin ψ) of the absolute heading
  double origin_heading_rad_ = 0.0;
};

}  // namespace sonarmap
