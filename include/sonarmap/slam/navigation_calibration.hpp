#pragma once
/// @file navigation_calibration.hpp
/// How far a log's own dead reckoning and scan matches can be trusted, measured on the log: the
/// odometry's noise (odometry_noise.hpp) and the scan matches' noise beyond their pairs'
/// information, both fitted by maximum likelihood to the disagreements the log shows.
///
/// - The matches' noise: three scans matched pairwise (a → b, b → c, a → c) must agree. Their
///   disagreement measures what the pairs' information leaves out: the errors every pair of a
///   match shares (the scans' distortion by dead reckoning during the sweep, a bearing's bias,
///   wrong pairs), which do not average out over the pairs as the ICP's Hessian assumes (Censi
///   2007, "An accurate closed-form estimate of ICP's covariance", ICRA). Modelled as one isotropic
///   translation σ and one yaw σ added to every match's covariance.
/// - The odometry's noise: the accepted loop closures against the dead reckoning along the paths
///   they close, the noise model's parameters (scale, heading, velocity noise, heading random walk)
///   fitted with the stated class as the lower bound and the centre of a log-normal prior (a factor
///   e at 1σ), so a log that shows little keeps what the user stated. A compass pulled by steel quays, or whose
///   deviation turns the heading by degrees between passes in opposite directions, shows here as a
///   larger noise.
///
/// The fit uses a Student-t likelihood (ν = 5) so that the odd wrong match weighs little (Lange,
/// Little & Taylor 1989, "Robust statistical modeling using the t distribution"), and are solved
/// with Ceres' gradient solver (L-BFGS) in the logarithms of the σ's.

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/slam/odometry_noise.hpp"
#include "sonarmap/slam/pose2.hpp"

namespace sonarmap {

/// The noise of a scan match beyond its pairs' information: σ's added to its covariance.
struct MatchNoise {
  double translation_sigma_m = 0.0;  ///< ≥ 0, in any direction of the plane
  double yaw_sigma_rad = 0.0;        ///< ≥ 0

  /// The information of a match whose pairs give `pairs_information` (x, y, yaw; 1/m², 1/rad²;
  /// may be singular: a direction without information, along a wall, stays without): the inverse
  /// of its covariance plus this noise's, H (I + F H)⁻¹, symmetric.
  Eigen::Matrix3d information(const Eigen::Matrix3d& pairs_information) const;
};

/// The heading sensor's deviation δ(ψ) = a cos ψ + b sin ψ (odometry_noise.hpp) estimated from
/// scans matched to the one before: each match's turn minus the turn the navigation measured is
/// δ(ψ₂) − δ(ψ₁) plus both errors, linear in (a, b). Weighted least squares with the prior
/// 0 ± prior_sigma on each coefficient; a disagreement beyond 3σ of its variance (a wrong match)
/// is left out. Incremental: O(1) per match.
class HeadingDeviationEstimate {
 public:
  /// @param prior_sigma_rad  1σ of each coefficient before any evidence, ≥ 0 (0: no deviation;
  ///        the estimate stays zero with zero covariance).
  explicit HeadingDeviationEstimate(double prior_sigma_rad = 0.0);
  /// A match from heading `from_heading_rad` to `to_heading_rad` (the navigation's, NED yaw) that
  /// turned `turn_disagreement_rad` more than the navigation says, with that disagreement's
  /// variance (the match's turn variance plus the navigation's), rad².
  void add(double from_heading_rad, double to_heading_rad, double turn_disagreement_rad, double variance_rad2);
  /// (a, b), radians.
  Eigen::Vector2d coefficients() const;
  /// Their covariance from the stated variances, rad² (the scatter beyond them is the matches' and
  /// the navigation's own noise, which every path's covariance carries already).
  Eigen::Matrix2d covariance() const;
  /// Whether the matches show a deviation beyond `covered_rad`: its amplitude √(a² + b²) larger
  /// than that (a heading error the navigation's stated noise already covers needs no model, and the
  /// matches' own errors, which depend on the scene's geometry and so on the heading, show as a
  /// small one) and the coefficients' squared Mahalanobis distance from zero, divided by the
  /// residuals' mean square per degree of freedom where that exceeds 1, beyond χ²₂'s 99 % quantile
  /// (9.21). A heading sensor without one (a gyro, a well-compensated compass) is then not given one.
  bool observed(double covered_rad) const;

 private:
  Eigen::Matrix2d information_ = Eigen::Matrix2d::Zero();  ///< the prior's plus the matches'
  Eigen::Vector2d weighted_sum_ = Eigen::Vector2d::Zero();
  double weighted_squares_ = 0.0;  ///< Σ r² / variance of the matches kept
  std::size_t matches_ = 0;        ///< kept
  bool deviation_ = false;
};

/// Three scans a, b, c matched pairwise, each relative pose with its pairs' information (stated in
/// the frame of the pose's first scan; may be singular along a wall).
struct MatchTriangle {
  Pose2 ab, bc, ac;
  Eigen::Matrix3d ab_information, bc_information, ac_information;
};

/// The fewest triangles calibrateMatchNoise fits from.
inline constexpr std::size_t kMinMatchTriangles = 8;

/// The MatchNoise under which the triangles' disagreements (ac⁻¹ ∘ ab ∘ bc, with its first-order
/// covariance) are most likely: what the matches' errors are beyond their pairs' information.
/// Three matches of one place must agree whatever each measured, so a bias the matches share (a
/// match that sees a fixed share less of the motion) does not show here: only their scatter.
/// Zero noise for fewer than kMinMatchTriangles triangles. σ's within [0.1 mm, 100 m] and
/// [0.001°, 60°]. Deterministic.
MatchNoise calibrateMatchNoise(const std::vector<MatchTriangle>& triangles);

/// A loop closure's evidence on the dead reckoning over the path between its two scans.
struct LoopEvidence {
  Pose2 dead_reckoning;  ///< the later scan in the earlier one's frame by dead reckoning
  /// The path's covariance term by term (OdometryNoise::covarianceTerms of each step composed along
  /// it, OdometryChain): Σ σ_p² · path_terms[p] + path_terms[kOdometryNoiseTerms], the last holding
  /// what does not depend on the fitted parameters (the floor, the deviation's uncertainty).
  std::array<Eigen::Matrix3d, kOdometryNoiseTerms + 1> path_terms;
  Pose2 measured;  ///< the later scan in the earlier one's frame, as matched
  /// The match's information with its noise (MatchNoise::information).
  Eigen::Matrix3d measured_information = Eigen::Matrix3d::Zero();
};

/// The odometry noise under which the loop closures' disagreements with the dead reckoning are most
/// likely: the drift the navigation showed over the paths the loops close. Over a loop's path
/// the dead reckoning's drift outweighs a match's error, which is not so between consecutive scans,
/// where a match that sees a share less of the motion than there was looks the same as a
/// navigation that drifts. Fitted: `stated`'s noise parameters (kOdometryNoiseParameters), each
/// between the stated value and 1000 times it, with the stated value's logarithm as the prior's
/// centre (σ 1); a zero stays zero. The stated class is the best the navigation is taken to be:
/// loop closures that agree with the dead reckoning better than it says leave it as stated, since
/// the matches' own biases (a match that sees a share less of the motion) would otherwise be
/// taken for a better navigation. The stated noise stands, too, when it explains the loops: their
/// squared Mahalanobis distances under it sum to within χ²'s 99 % quantile for 3 degrees of freedom
/// each. `stated` for no evidence or without a measured position. Deterministic.
/// @throws ValueError for an invalid `stated` (OdometryNoise::validate).
OdometryNoise calibrateOdometryNoise(const std::vector<LoopEvidence>& loops, const OdometryNoise& stated);

}  // namespace sonarmap
