/// @file pose_graph.cpp
/// PoseGraph (pose_graph.hpp) on Ceres Solver: one 3-vector parameter block per node, an
/// automatically differentiated residual per edge.

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <ceres/ceres.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/slam/pose_graph.hpp"

namespace sonarmap {
namespace {

template <class T>
T wrapped(const T& angle) {
  using std::floor;
  const T two_pi = T(2.0 * std::numbers::pi);
  return angle - two_pi * floor((angle + T(std::numbers::pi)) / two_pi);
}

/// The error of an edge: the measured pose of `to` in `from`'s frame against the nodes' one,
/// (Δx, Δy in from's frame, Δyaw wrapped), times the information's square root.
struct RelativePoseError {
  RelativePoseError(const Pose2& measurement, const Eigen::Matrix3d& sqrt_information)
      : measurement_(measurement), sqrt_information_(sqrt_information) {}

  template <class T>
  bool operator()(const T* from, const T* to, T* residuals) const {
    return evaluate(from, to, T(1.0), residuals);
  }

  /// The odometry's form: the measured translation times the odometry's scale factor, the measured
  /// turn plus the change of the heading sensor's deviation δ(ψ) = a cos ψ + b sin ψ between the
  /// two headings the navigation gave.
  template <class T>
  bool operator()(const T* from, const T* to, const T* scale, const T* deviation, T* residuals) const {
    const T turn_error = deviation[0] * T(std::cos(to_heading_rad_) - std::cos(from_heading_rad_)) +
                         deviation[1] * T(std::sin(to_heading_rad_) - std::sin(from_heading_rad_));
    return evaluate(from, to, scale[0], residuals, turn_error);
  }

  void setHeadings(double from_heading_rad, double to_heading_rad) {
    from_heading_rad_ = from_heading_rad;
    to_heading_rad_ = to_heading_rad;
  }

 private:
  template <class T>
  bool evaluate(const T* from, const T* to, const T& scale, T* residuals, const T& turn_error = T(0.0)) const {
    using std::cos;
    using std::sin;
    const T c = cos(from[2]), s = sin(from[2]);
    const T dx = to[0] - from[0], dy = to[1] - from[1];
    const T x = c * dx + s * dy;  // to's position in from's frame: Rᵀ (t_to − t_from)
    const T y = -s * dx + c * dy;
    Eigen::Matrix<T, 3, 1> error(x - scale * T(measurement_.x_m), y - scale * T(measurement_.y_m),
                                 wrapped(to[2] - from[2] - T(measurement_.yaw_rad) - turn_error));
    // The information is stated in from's frame, like the measurement's translation.
    const Eigen::Matrix<T, 3, 1> weighted = sqrt_information_.cast<T>() * error;
    residuals[0] = weighted(0);
    residuals[1] = weighted(1);
    residuals[2] = weighted(2);
    return true;
  }

  Pose2 measurement_;
  Eigen::Matrix3d sqrt_information_;
  double from_heading_rad_ = 0.0;
  double to_heading_rad_ = 0.0;
};

/// The heading deviation's prior: (a, b) / σ.
struct DeviationPrior {
  double sigma_rad;
  template <class T>
  bool operator()(const T* deviation, T* residual) const {
    residual[0] = deviation[0] / T(sigma_rad);
    residual[1] = deviation[1] / T(sigma_rad);
    return true;
  }
};

/// The odometry scale's prior: (scale − 1) / σ.
struct ScalePrior {
  double sigma;
  template <class T>
  bool operator()(const T* scale, T* residual) const {
    residual[0] = (scale[0] - T(1.0)) / T(sigma);
    return true;
  }
};

}  // namespace

Eigen::Matrix3d informationSqrt(const Eigen::Matrix3d& information) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (information + information.transpose()));
  const Eigen::Vector3d roots = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return roots.asDiagonal() * eigen.eigenvectors().transpose();
}

std::size_t PoseGraph::addNode(const Pose2& initial) {
  poses_.push_back(initial);
  return poses_.size() - 1;
}

void PoseGraph::addEdge(const PoseGraphEdge& edge) {
  if (edge.from >= poses_.size() || edge.to >= poses_.size() || edge.from == edge.to) {
    throw ValueError("pose graph: an edge must join two different nodes");
  }
  if (!edge.information.allFinite() || !edge.measurement.vector().allFinite()) {
    throw ValueError("pose graph: an edge's measurement and information must be finite");
  }
  edges_.push_back(edge);
}

bool PoseGraph::optimize(const PoseGraphOptions& options) {
  if (!(std::isfinite(options.robust_scale_sigma) && options.robust_scale_sigma > 0.0) || options.max_iterations < 1) {
    throw ValueError("pose graph: robust_scale_sigma must be > 0 and max_iterations ≥ 1");
  }
  if (poses_.size() < 2 || edges_.empty()) return true;
  std::vector<std::array<double, 3>> state(poses_.size());
  for (std::size_t i = 0; i < poses_.size(); ++i) state[i] = {poses_[i].x_m, poses_[i].y_m, poses_[i].yaw_rad};
  ceres::Problem problem;
  double scale = odometry_scale_;
  std::array<double, 2> deviation{heading_deviation_.x(), heading_deviation_.y()};
  const bool navigation_parameters = scale_sigma_ || deviation_sigma_;
  for (const PoseGraphEdge& edge : edges_) {
    const Eigen::Matrix3d root = informationSqrt(edge.information);
    if (edge.kind == EdgeKind::kOdometry && navigation_parameters) {
      auto* error = new RelativePoseError(edge.measurement, root);
      error->setHeadings(edge.from_heading_rad, edge.to_heading_rad);
      auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 3, 3, 3, 1, 2>(error);
      problem.AddResidualBlock(cost, nullptr, state[edge.from].data(), state[edge.to].data(), &scale, deviation.data());
      continue;
    }
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 3, 3, 3>(new RelativePoseError(edge.measurement, root));
    ceres::LossFunction* loss = nullptr;
    if (edge.kind != EdgeKind::kOdometry) loss = new ceres::CauchyLoss(options.robust_scale_sigma);
    problem.AddResidualBlock(cost, loss, state[edge.from].data(), state[edge.to].data());
  }
  if (problem.HasParameterBlock(&scale)) {
    if (scale_sigma_) {  // its prior: 1 ± scale_sigma
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<ScalePrior, 1, 1>(new ScalePrior{*scale_sigma_}), nullptr, &scale);
    } else {
      problem.SetParameterBlockConstant(&scale);
    }
    if (deviation_sigma_) {  // its prior: 0 ± deviation_sigma for each coefficient
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<DeviationPrior, 2, 2>(new DeviationPrior{*deviation_sigma_}), nullptr,
                               deviation.data());
    } else {
      problem.SetParameterBlockConstant(deviation.data());
    }
  }
  problem.SetParameterBlockConstant(state.front().data());
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (!summary.IsSolutionUsable()) return false;
  for (std::size_t i = 0; i < poses_.size(); ++i) poses_[i] = {state[i][0], state[i][1], wrapAngle_rad(state[i][2])};
  odometry_scale_ = scale;
  heading_deviation_ = Eigen::Vector2d(deviation[0], deviation[1]);
  odometry_scale_sigma_ = 0.0;
  if (options.scale_covariance && scale_sigma_ && problem.HasParameterBlock(&scale)) {
    ceres::Covariance::Options covariance_options;
    covariance_options.num_threads = 1;
    ceres::Covariance covariance(covariance_options);
    const std::vector<std::pair<const double*, const double*>> blocks{{&scale, &scale}};
    double variance = 0.0;
    if (covariance.Compute(blocks, &problem) && covariance.GetCovarianceBlock(&scale, &scale, &variance) && variance > 0.0) {
      odometry_scale_sigma_ = std::sqrt(variance);
    }
  }
  return true;
}

void PoseGraph::fixOdometryScale() {
  scale_sigma_.reset();
  odometry_scale_ = 1.0;
  odometry_scale_sigma_ = 0.0;
}

void PoseGraph::setInformation(std::size_t edge, const Eigen::Matrix3d& information) {
  if (edge >= edges_.size()) throw ValueError("pose graph: no such edge");
  if (!information.allFinite()) throw ValueError("pose graph: an edge's information must be finite");
  edges_[edge].information = information;
}

void PoseGraph::fixHeadingDeviation() {
  deviation_sigma_.reset();
  heading_deviation_ = Eigen::Vector2d::Zero();
}

void PoseGraph::estimateHeadingDeviation(double prior_sigma_rad) {
  if (!(std::isfinite(prior_sigma_rad) && prior_sigma_rad > 0.0)) throw ValueError("pose graph: the deviation's prior σ must be > 0");
  deviation_sigma_ = prior_sigma_rad;
}

void PoseGraph::estimateOdometryScale(double prior_sigma) {
  if (!(std::isfinite(prior_sigma) && prior_sigma > 0.0)) throw ValueError("pose graph: the scale's prior σ must be > 0");
  scale_sigma_ = prior_sigma;
}

}  // namespace sonarmap
