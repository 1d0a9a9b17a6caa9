#pragma once
/// @file pose_graph.hpp
/// A planar pose graph (Lu & Milios 1997; Grisetti et al. 2010, "A tutorial on graph-based SLAM")
/// over the scans' reference poses: odometry edges from dead reckoning, scan-match and loop-closure
/// edges from the scan matcher, solved by Ceres Solver (Agarwal et al., Debian libceres-dev) with
/// its Cauchy loss on the match edges, so one bad edge bends the map little. 3 degrees of freedom
/// (x, y, yaw in NED's plane, pose2.hpp); depth, roll and pitch come from the sensors.
///
/// Deterministic: one thread and a fixed order of blocks, so the same graph gives the same bytes.

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/slam/pose2.hpp"

namespace sonarmap {

/// What an edge stands for.
enum class EdgeKind {
  kOdometry,     ///< dead reckoning between consecutive scans (no robust loss)
  kScanMatch,    ///< a scan matched against the scans just before it
  kLoopClosure,  ///< a scan matched against scans seen long before
};

/// A relative-pose measurement: node `to` in the frame of node `from`.
struct PoseGraphEdge {
  std::size_t from = 0;
  std::size_t to = 0;
  Pose2 measurement;
  /// Information of the measurement (x, y, yaw in from's frame; 1/m², 1/rad²), symmetric positive
  /// semi-definite: a direction without information (along a wall) adds no constraint.
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  EdgeKind kind = EdgeKind::kOdometry;
  /// The navigation's headings at the two ends (odometry edges, NED yaw, radians): the heading
  /// sensor's deviation changes the measured turn by δ(to) − δ(from) (estimateHeadingDeviation).
  double from_heading_rad = 0.0;
  double to_heading_rad = 0.0;
};

/// Options of PoseGraph::optimize.
struct PoseGraphOptions {
  /// Scale of the Cauchy loss on match and loop-closure edges, in σ of their information: an edge
  /// off by much more than this many σ is down-weighted like an outlier. > 0.
  double robust_scale_sigma = 3.0;
  int max_iterations = 100;  ///< Levenberg–Marquardt iterations, ≥ 1
  /// Also compute the odometry scale's marginal σ at the solution (PoseGraph::odometryScaleSigma;
  /// ceres::Covariance over the whole graph, so asked for once, at the end).
  bool scale_covariance = false;
};

/// The graph: nodes (poses, the first held fixed) and edges.
class PoseGraph {
 public:
  /// Adds a node at `initial`; returns its index.
  std::size_t addNode(const Pose2& initial);
  /// @throws ValueError when an end is not a node, from == to, or the information is not finite.
  void addEdge(const PoseGraphEdge& edge);
  /// Solves for the poses that best explain the edges, starting from the current ones; the first
  /// node stays where it is. Returns false when Ceres reports no usable solution (the poses are
  /// then left as they were).
  /// @throws ValueError for invalid options.
  bool optimize(const PoseGraphOptions& options = {});

  /// Estimate one scale factor λ of every odometry edge's translation with the poses (a DVL's scale
  /// error is common to the whole run: per edge independent, its drift would be under-counted, and
  /// a loop closure cannot observe it): odometry residuals compare the nodes' relative translation
  /// with λ × the measured one; λ's prior is 1 ± prior_sigma. Scan matches that see features along
  /// the track measure it.
  /// @throws ValueError unless prior_sigma > 0.
  void estimateOdometryScale(double prior_sigma);
  /// Estimate the heading sensor's deviation with the poses: a magnetic compass's error depends on
  /// the heading, δ(ψ) = a cos ψ + b sin ψ (one cycle per turn, the deviation of a magnetised
  /// vehicle; Bowditch, "The American Practical Navigator", ch. 6), so the turns it measures between
  /// two headings are off by δ(to) − δ(from): passes in opposite directions disagree by up to twice
  /// its amplitude, which no constant bias explains. Odometry residuals compare the nodes' turn
  /// with the measured turn plus that change (PoseGraphEdge's headings); a and b have the prior
  /// 0 ± prior_sigma_rad each. A constant part of the deviation turns every node alike and is not
  /// observable.
  /// @throws ValueError unless prior_sigma_rad > 0.
  void estimateHeadingDeviation(double prior_sigma_rad);
  /// Stops estimating the deviation: it is zero from now on.
  void fixHeadingDeviation();
  /// Whether the deviation is estimated (estimateHeadingDeviation, and not fixed since).
  bool estimatesHeadingDeviation() const { return deviation_sigma_.has_value(); }
  /// (a, b) after the last optimize, radians (zero before, or without estimateHeadingDeviation).
  Eigen::Vector2d headingDeviation() const { return heading_deviation_; }
  /// λ after the last optimize (1 before, or without estimateOdometryScale).
  double odometryScale() const { return odometry_scale_; }
  /// Whether λ is estimated (estimateOdometryScale, and not fixed since).
  bool estimatesOdometryScale() const { return scale_sigma_.has_value(); }
  /// λ's marginal σ (prior and every edge together) from the last optimize with
  /// PoseGraphOptions::scale_covariance; 0 when not computed, not estimated, or Ceres cannot (a
  /// rank-deficient graph).
  double odometryScaleSigma() const { return odometry_scale_sigma_; }
  /// Stops estimating λ: it is 1 from now on (the odometry edges' information should then carry
  /// the scale error: setInformation).
  void fixOdometryScale();
  /// Replaces edge `edge`'s information. @throws ValueError for an index out of range or an
  /// information that is not finite.
  void setInformation(std::size_t edge, const Eigen::Matrix3d& information);

  std::size_t size() const { return poses_.size(); }
  const std::vector<Pose2>& poses() const { return poses_; }
  const Pose2& pose(std::size_t node) const { return poses_.at(node); }
  void setPose(std::size_t node, const Pose2& pose) { poses_.at(node) = pose; }
  const std::vector<PoseGraphEdge>& edges() const { return edges_; }

 private:
  std::vector<Pose2> poses_;
  std::vector<PoseGraphEdge> edges_;
  std::optional<double> scale_sigma_;
  std::optional<double> deviation_sigma_;
  Eigen::Vector2d heading_deviation_ = Eigen::Vector2d::Zero();
  double odometry_scale_ = 1.0;
  double odometry_scale_sigma_ = 0.0;
};

/// The square root S of a positive semi-definite information matrix (SᵀS = information), from its
/// eigen-decomposition with negative eigenvalues clamped to 0: residuals are S · error.
Eigen::Matrix3d informationSqrt(const Eigen::Matrix3d& information);

}  // namespace sonarmap
