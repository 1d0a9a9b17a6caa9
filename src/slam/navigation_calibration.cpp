/// @file navigation_calibration.cpp
/// calibrateNavigation (navigation_calibration.hpp): Student-t maximum a posteriori in the
/// logarithms of the σ's, with Ceres' L-BFGS and central differences.

#include "sonarmap/slam/navigation_calibration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/slam/pose2_covariance.hpp"

namespace sonarmap {
namespace {

/// Degrees of freedom of the Student-t likelihood.
constexpr double kNu = 5.0;

/// Negative log-likelihood of a 3-vector residual r whose covariance is `covariance`, Student-t.
double studentCost(const Eigen::Vector3d& r, const Eigen::Matrix3d& covariance) {
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(0.5 * (covariance + covariance.transpose()));
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().array() > 0.0).all()) return 1e30;
  const double chi2 = r.dot(ldlt.solve(r));
  return 0.5 * ldlt.vectorD().array().log().sum() + 0.5 * (kNu + 3.0) * std::log1p(chi2 / kNu);
}

/// A cost of n parameters minimised by Ceres' L-BFGS, its gradient by central differences.
class NumericCost : public ceres::FirstOrderFunction {
 public:
  NumericCost(int parameters, std::function<double(const double*)> cost) : parameters_(parameters), cost_(std::move(cost)) {}
  int NumParameters() const override { return parameters_; }
  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    *cost = cost_(parameters);
    if (gradient == nullptr) return std::isfinite(*cost);
    std::array<double, 8> x{};
    std::copy(parameters, parameters + parameters_, x.begin());
    for (int i = 0; i < parameters_; ++i) {
      constexpr double kStep = 1e-5;
      x[i] = parameters[i] + kStep;
      const double up = cost_(x.data());
      x[i] = parameters[i] - kStep;
      const double down = cost_(x.data());
      x[i] = parameters[i];
      gradient[i] = (up - down) / (2.0 * kStep);
    }
    return std::isfinite(*cost);
  }

 private:
  int parameters_;
  std::function<double(const double*)> cost_;
};

/// Minimises `cost` from `x` (in place).
void minimise(int parameters, std::function<double(const double*)> cost, double* x) {
  ceres::GradientProblem problem(new NumericCost(parameters, std::move(cost)));
  ceres::GradientProblemSolver::Options options;
  options.line_search_direction_type = ceres::LBFGS;
  options.max_num_iterations = 200;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(options, problem, x, &summary);
}


}  // namespace

Eigen::Matrix3d MatchNoise::information(const Eigen::Matrix3d& pairs_information) const {
  const Eigen::Matrix3d floor =
      Eigen::Vector3d(translation_sigma_m * translation_sigma_m, translation_sigma_m * translation_sigma_m,
                      yaw_sigma_rad * yaw_sigma_rad)
          .asDiagonal();
  const Eigen::Matrix3d information = pairs_information * (Eigen::Matrix3d::Identity() + floor * pairs_information).inverse();
  return 0.5 * (information + information.transpose());
}

HeadingDeviationEstimate::HeadingDeviationEstimate(double prior_sigma_rad) : deviation_(prior_sigma_rad > 0.0) {
  if (deviation_) information_ = Eigen::Matrix2d::Identity() / (prior_sigma_rad * prior_sigma_rad);
}

void HeadingDeviationEstimate::add(double from_heading_rad, double to_heading_rad, double turn_disagreement_rad,
                                   double variance_rad2) {
  if (!deviation_ || !(variance_rad2 > 0.0) || !std::isfinite(turn_disagreement_rad)) return;
  const Eigen::Vector2d g(std::cos(to_heading_rad) - std::cos(from_heading_rad), std::sin(to_heading_rad) - std::sin(from_heading_rad));
  // Left out beyond 3σ of what the current estimate and the variance allow: a wrong match.
  const double expected = g.dot(coefficients());
  const double allowed = variance_rad2 + g.dot(covariance() * g);
  if (std::pow(turn_disagreement_rad - expected, 2) > 9.0 * allowed) return;
  information_ += g * g.transpose() / variance_rad2;
  weighted_sum_ += g * turn_disagreement_rad / variance_rad2;
  weighted_squares_ += turn_disagreement_rad * turn_disagreement_rad / variance_rad2;
  ++matches_;
}

Eigen::Vector2d HeadingDeviationEstimate::coefficients() const {
  return deviation_ ? Eigen::Vector2d(information_.ldlt().solve(weighted_sum_)) : Eigen::Vector2d::Zero();
}

Eigen::Matrix2d HeadingDeviationEstimate::covariance() const {
  return deviation_ ? Eigen::Matrix2d(information_.inverse()) : Eigen::Matrix2d::Zero();
}

bool HeadingDeviationEstimate::observed(double covered_rad) const {
  if (!deviation_) return false;
  const Eigen::Vector2d c = coefficients();
  // The residuals' mean square per degree of freedom (Σ w r² − bᵀ c over the matches less the two
  // coefficients), where it exceeds 1, widens the test: the matches' errors depend on the scene's
  // geometry, and so on the heading, more than their stated variances say.
  double scatter = 1.0;
  if (matches_ > 2) scatter = std::max(1.0, (weighted_squares_ - weighted_sum_.dot(c)) / static_cast<double>(matches_ - 2));
  return c.norm() > covered_rad && c.dot(information_ * c) / scatter > 9.21;
}

MatchNoise calibrateMatchNoise(const std::vector<MatchTriangle>& triangles) {
  if (triangles.size() < kMinMatchTriangles) return {};
  // Per triangle: the disagreement e = ac⁻¹ ∘ (ab ∘ bc) and its first-order covariance
  // (composeCovariance, inverseCovariance) from each match's pairs' covariance plus the floor F,
  // written as P + σ_t² T + σ_yaw² Y (the composition rules are linear in the inputs' covariances).
  struct Prepared {
    Eigen::Vector3d disagreement;
    Eigen::Matrix3d pairs;
    Eigen::Matrix3d unit_translation;
    Eigen::Matrix3d unit_yaw;
  };
  std::vector<Prepared> prepared;
  for (const MatchTriangle& t : triangles) {
    const Pose2 chain = t.ab * t.bc;
    const Pose2 inverse_ac = t.ac.inverse();
    const Pose2 e = inverse_ac * chain;
    const auto push = [&](const Eigen::Matrix3d& ab, const Eigen::Matrix3d& bc, const Eigen::Matrix3d& ac) {
      return composeCovariance(inverse_ac, inverseCovariance(t.ac, ac), chain, composeCovariance(t.ab, ab, t.bc, bc));
    };
    const auto covarianceOf = [](const Eigen::Matrix3d& information) {
      return (0.5 * (information + information.transpose()) + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
    };
    const Eigen::Matrix3d unit_translation = Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
    const Eigen::Matrix3d unit_yaw = Eigen::Vector3d(0.0, 0.0, 1.0).asDiagonal();
    prepared.push_back({Eigen::Vector3d(e.x_m, e.y_m, wrapAngle_rad(e.yaw_rad)),
                        push(covarianceOf(t.ab_information), covarianceOf(t.bc_information), covarianceOf(t.ac_information)),
                        push(unit_translation, unit_translation, unit_translation), push(unit_yaw, unit_yaw, unit_yaw)});
  }
  constexpr double kMinT = 1e-4, kMaxT = 100.0, kMinYaw = 0.001 * std::numbers::pi / 180.0, kMaxYaw = std::numbers::pi / 3.0;
  // Start from the disagreements' medians.
  std::vector<double> translation, yaw;
  for (const Prepared& p : prepared) {
    translation.push_back(p.disagreement.head<2>().norm());
    yaw.push_back(std::abs(p.disagreement(2)));
  }
  std::nth_element(translation.begin(), translation.begin() + static_cast<std::ptrdiff_t>(translation.size() / 2), translation.end());
  std::nth_element(yaw.begin(), yaw.begin() + static_cast<std::ptrdiff_t>(yaw.size() / 2), yaw.end());
  std::array<double, 2> x{std::log(std::clamp(translation[translation.size() / 2], kMinT, kMaxT)),
                          std::log(std::clamp(yaw[yaw.size() / 2], kMinYaw, kMaxYaw))};
  const auto cost = [&](const double* u) {
    const double t2 = std::exp(2.0 * std::clamp(u[0], std::log(kMinT), std::log(kMaxT)));
    const double y2 = std::exp(2.0 * std::clamp(u[1], std::log(kMinYaw), std::log(kMaxYaw)));
    double sum = 0.0;
    for (const Prepared& p : prepared) sum += studentCost(p.disagreement, p.pairs + t2 * p.unit_translation + y2 * p.unit_yaw);
    return sum;
  };
  minimise(2, cost, x.data());
  MatchNoise noise;
  noise.translation_sigma_m = std::clamp(std::exp(x[0]), kMinT, kMaxT);
  noise.yaw_sigma_rad = std::clamp(std::exp(x[1]), kMinYaw, kMaxYaw);
  return noise;
}

OdometryNoise calibrateOdometryNoise(const std::vector<LoopEvidence>& loops, const OdometryNoise& stated) {
  stated.validate();
  if (loops.empty() || !stated.position_measured) return stated;
  // The fitted fields: the noise parameters; a zero stays zero.
  std::vector<double OdometryNoise::*> fitted;
  for (double OdometryNoise::*field : kOdometryNoiseParameters) {
    if (stated.*field > 0.0) fitted.push_back(field);
  }
  if (fitted.empty()) return stated;
  constexpr double kMaxFactorLog = 6.907755278982137;  // ln 1000
  const auto noiseOf = [&](const double* u) {
    OdometryNoise noise = stated;
    for (std::size_t i = 0; i < fitted.size(); ++i) {
      noise.*fitted[i] = stated.*fitted[i] * std::exp(std::clamp(u[i], 0.0, kMaxFactorLog));
    }
    return noise;
  };
  std::vector<Eigen::Vector3d> residuals;
  std::vector<Eigen::Matrix3d> measured_covariances;
  for (const LoopEvidence& loop : loops) {
    const Pose2 r = loop.dead_reckoning.between(loop.measured);
    residuals.emplace_back(r.x_m, r.y_m, wrapAngle_rad(r.yaw_rad));
    const Eigen::Matrix3d information = 0.5 * (loop.measured_information + loop.measured_information.transpose());
    measured_covariances.push_back((information + 1e-9 * Eigen::Matrix3d::Identity()).inverse());
  }
  const auto covarianceOf = [&](const OdometryNoise& noise, std::size_t l) {
    Eigen::Matrix3d covariance = loops[l].path_terms[kOdometryNoiseTerms] + measured_covariances[l];
    for (std::size_t p = 0; p < kOdometryNoiseTerms; ++p) {
      covariance += std::pow(noise.*kOdometryNoiseParameters[p], 2) * loops[l].path_terms[p];
    }
    return covariance;
  };
  // The stated noise stands when it explains the loops: their squared Mahalanobis distances sum to
  // within χ²'s 99 % quantile for their 3 n degrees of freedom (Wilson & Hilferty 1931).
  double chi2 = 0.0;
  for (std::size_t l = 0; l < loops.size(); ++l) chi2 += residuals[l].dot(covarianceOf(stated, l).ldlt().solve(residuals[l]));
  const double dof = 3.0 * static_cast<double>(loops.size());
  const double quantile = dof * std::pow(1.0 - 2.0 / (9.0 * dof) + 2.326 * std::sqrt(2.0 / (9.0 * dof)), 3);
  if (chi2 <= quantile) return stated;
  const auto cost = [&](const double* u) {
    const OdometryNoise noise = noiseOf(u);
    double sum = 0.0;
    for (std::size_t i = 0; i < fitted.size(); ++i) sum += 0.5 * u[i] * u[i];  // the stated class, σ 1 in the logarithm
    for (std::size_t l = 0; l < loops.size(); ++l) sum += studentCost(residuals[l], covarianceOf(noise, l));
    return sum;
  };
  std::array<double, 8> u{};
  minimise(static_cast<int>(fitted.size()), cost, u.data());
  return noiseOf(u.data());
}

}  // namespace sonarmap
