/// @file test_navigation_calibration.cpp
/// The heading sensor's deviation (a compass's error that depends on the heading) estimated from
/// matches (HeadingDeviationEstimate) and in the pose graph (PoseGraph::estimateHeadingDeviation);
/// OdometryChain's deviation sensitivity against a finite difference; the match noise measured on
/// triangles of matches (calibrateMatchNoise); the odometry noise measured on loop closures
/// (calibrateOdometryNoise).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "sonarmap/slam/navigation_calibration.hpp"
#include "sonarmap/slam/odometry_chain.hpp"
#include "sonarmap/slam/pose_graph.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// The true heading where a compass with the deviation δ(ψ) = a cos ψ + b sin ψ reads ψ.
double trueOf(double compass_rad, const Eigen::Vector2d& deviation) {
  return compass_rad + deviation.x() * std::cos(compass_rad) + deviation.y() * std::sin(compass_rad);
}

/// A vehicle that turns through every heading, back and forth: the compass's readings.
std::vector<double> compassHeadings(int count) {
  std::vector<double> headings;
  for (int k = 0; k < count; ++k) headings.push_back(0.4 + 0.35 * k + 0.6 * std::sin(0.9 * k));
  return headings;
}

TEST(slamNavigationCalibration, DeviationEstimatedFromMatchedTurns) {
  const Eigen::Vector2d deviation(-2.0 * kDegree, 5.0 * kDegree);
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 0.5 * kDegree);
  HeadingDeviationEstimate estimate(3.0 * kDegree);
  const std::vector<double> compass = compassHeadings(300);
  for (std::size_t k = 1; k < compass.size(); ++k) {
    const double matched_turn = trueOf(compass[k], deviation) - trueOf(compass[k - 1], deviation) + noise(random);
    estimate.add(compass[k - 1], compass[k], matched_turn - (compass[k] - compass[k - 1]), std::pow(0.5 * kDegree, 2));
  }
  estimate.add(0.0, 1.0, 30.0 * kDegree, std::pow(0.5 * kDegree, 2));  // a wrong match: left out
  EXPECT_NEAR(estimate.coefficients().x(), deviation.x(), 0.3 * kDegree);
  EXPECT_NEAR(estimate.coefficients().y(), deviation.y(), 0.3 * kDegree);
  EXPECT_LT(std::sqrt(estimate.covariance()(0, 0)), 0.3 * kDegree);
  EXPECT_TRUE(estimate.observed(1.5 * kDegree));
  EXPECT_FALSE(estimate.observed(6.0 * kDegree));  // within what the navigation's noise covers
  // Without a deviation stated, nothing is estimated.
  HeadingDeviationEstimate none(0.0);
  none.add(0.0, 1.0, 0.1, 1e-4);
  EXPECT_EQ(none.coefficients(), Eigen::Vector2d::Zero());
  EXPECT_EQ(none.covariance(), Eigen::Matrix2d::Zero());
}

TEST(slamNavigationCalibration, PoseGraphEstimatesTheDeviation) {
  // Nodes on a circle turning through every heading; odometry from the compass, matches the truth.
  const Eigen::Vector2d deviation(3.0 * kDegree, -4.0 * kDegree);
  const std::vector<double> compass = compassHeadings(60);
  std::vector<Pose2> truth;
  for (std::size_t k = 0; k < compass.size(); ++k) {
    truth.push_back({2.0 * static_cast<double>(k), std::sin(0.3 * k), trueOf(compass[k], deviation)});
  }
  PoseGraph graph;
  graph.estimateHeadingDeviation(5.0 * kDegree);
  graph.addNode(truth[0]);
  for (std::size_t k = 1; k < truth.size(); ++k) {
    const double from = compass[k - 1], to = compass[k];
    const Pose2 believed_from{truth[k - 1].x_m, truth[k - 1].y_m, from}, believed_to{truth[k].x_m, truth[k].y_m, to};
    graph.addNode(graph.pose(k - 1) * believed_from.between(believed_to));
    PoseGraphEdge odometry{k - 1, k, believed_from.between(believed_to), Eigen::Vector3d(1e4, 1e4, 1e6).asDiagonal()};
    odometry.from_heading_rad = from;
    odometry.to_heading_rad = to;
    graph.addEdge(odometry);
    graph.addEdge({k - 1, k, truth[k - 1].between(truth[k]), Eigen::Vector3d(1e2, 1e2, 1e4).asDiagonal(), EdgeKind::kScanMatch});
  }
  ASSERT_TRUE(graph.optimize());
  EXPECT_NEAR(graph.headingDeviation().x(), deviation.x(), 0.2 * kDegree);
  EXPECT_NEAR(graph.headingDeviation().y(), deviation.y(), 0.2 * kDegree);
  for (std::size_t k = 1; k < truth.size(); ++k) {
    EXPECT_NEAR(wrapAngle_rad(graph.pose(0).between(graph.pose(k)).yaw_rad - truth[0].between(truth[k]).yaw_rad), 0.0, 0.2 * kDegree);
  }
}

TEST(slamNavigationCalibration, ChainDeviationSensitivityIsTheDerivative) {
  // A chain of compass-measured motions; the relative pose's change when the compass is corrected
  // by a small deviation, against the sensitivity.
  const std::vector<double> headings = compassHeadings(25);
  const auto chainFor = [&](const Eigen::Vector2d& correction) {
    // Positions integrated with the corrected headings from the same body-frame steps.
    std::vector<Pose2> poses;
    Eigen::Vector2d position = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < headings.size(); ++k) {
      const double heading = headings[k] + correction.x() * std::cos(headings[k]) + correction.y() * std::sin(headings[k]);
      if (k > 0) {
        const double previous = headings[k - 1] + correction.x() * std::cos(headings[k - 1]) + correction.y() * std::sin(headings[k - 1]);
        position += Eigen::Rotation2Dd(previous).toRotationMatrix() * Eigen::Vector2d(1.5, 0.2 * std::cos(0.7 * k));
      }
      poses.push_back({position.x(), position.y(), heading});
    }
    return poses;
  };
  const std::vector<Pose2> base = chainFor(Eigen::Vector2d::Zero());
  OdometryChain chain(base[0].yaw_rad);
  for (std::size_t k = 1; k < base.size(); ++k) chain.append(base[k - 1].between(base[k]), Eigen::Matrix3d::Identity() * 1e-4);
  constexpr double kStep = 1e-6;
  for (const auto& [a, b] : std::vector<std::pair<std::size_t, std::size_t>>{{0, 24}, {5, 18}, {18, 5}}) {
    const Eigen::Matrix<double, 3, 2> g = chain.deviationSensitivity(a, b);
    for (int c = 0; c < 2; ++c) {
      const std::vector<Pose2> moved = chainFor(c == 0 ? Eigen::Vector2d(kStep, 0.0) : Eigen::Vector2d(0.0, kStep));
      const Pose2 before = base[a].between(base[b]), after = moved[a].between(moved[b]);
      const Eigen::Vector3d numeric((after.x_m - before.x_m) / kStep, (after.y_m - before.y_m) / kStep,
                                    wrapAngle_rad(after.yaw_rad - before.yaw_rad) / kStep);
      EXPECT_LT((numeric - g.col(c)).norm(), 1e-3 * (1.0 + numeric.norm())) << a << " -> " << b << " column " << c;
    }
  }
}

TEST(slamNavigationCalibration, MatchNoiseFromTheTrianglesScatter) {
  // Matches that claim 1 cm and 0.05° but scatter by 0.2 m and 1°: the triangles say so.
  std::mt19937 random(11);
  std::normal_distribution<double> t(0.0, 0.2), r(0.0, 1.0 * kDegree);
  const Eigen::Matrix3d claimed = Eigen::Vector3d(1e4, 1e4, 1.0 / std::pow(0.05 * kDegree, 2)).asDiagonal();
  std::vector<MatchTriangle> triangles;
  for (int i = 0; i < 200; ++i) {
    const Pose2 ab{2.0, 0.3, 0.1}, bc{1.5, -0.2, -0.2};
    const Pose2 ac = ab * bc;
    const auto noisy = [&](const Pose2& p) { return Pose2{p.x_m + t(random), p.y_m + t(random), p.yaw_rad + r(random)}; };
    triangles.push_back({noisy(ab), noisy(bc), noisy(ac), claimed, claimed, claimed});
  }
  const MatchNoise noise = calibrateMatchNoise(triangles);
  EXPECT_NEAR(noise.translation_sigma_m, 0.2, 0.05);
  EXPECT_NEAR(noise.yaw_sigma_rad, 1.0 * kDegree, 0.25 * kDegree);
  EXPECT_EQ(calibrateMatchNoise({triangles.begin(), triangles.begin() + 3}).translation_sigma_m, 0.0);  // too few
}

/// 40 loop closures whose paths (10–39 steps of 2 m, 14 s) drifted as `truth` says.
std::vector<LoopEvidence> loopsDrifting(const OdometryNoise& truth) {
  std::mt19937 random(5);
  std::vector<LoopEvidence> loops;
  for (int i = 0; i < 40; ++i) {
    OdometryChain chain;
    std::array<OdometryChain, kOdometryNoiseTerms + 1> terms;
    const int steps = 10 + i % 30;
    for (int s = 0; s < steps; ++s) {
      const Pose2 step{2.0, 0.0, 0.05};
      chain.append(step, truth.covariance(step, 14.0));
      const auto unit = truth.covarianceTerms(step, 14.0);
      for (std::size_t p = 0; p < terms.size(); ++p) terms[p].append(step, unit[p]);
    }
    const Eigen::Matrix3d covariance = chain.covariance(0, static_cast<std::size_t>(steps));
    const Eigen::LLT<Eigen::Matrix3d> root(covariance);
    std::normal_distribution<double> unit(0.0, 1.0);
    const Eigen::Vector3d error = root.matrixL() * Eigen::Vector3d(unit(random), unit(random), unit(random));
    LoopEvidence loop;
    loop.dead_reckoning = chain.between(0, static_cast<std::size_t>(steps));
    for (std::size_t p = 0; p < terms.size(); ++p) loop.path_terms[p] = terms[p].covariance(0, static_cast<std::size_t>(steps));
    loop.measured = {loop.dead_reckoning.x_m + error.x(), loop.dead_reckoning.y_m + error.y(), loop.dead_reckoning.yaw_rad + error.z()};
    loop.measured_information = Eigen::Vector3d(1e4, 1e4, 1e6).asDiagonal();
    loops.push_back(loop);
  }
  return loops;
}

TEST(slamNavigationCalibration, OdometryNoiseFromLoopClosures) {
  // Loops whose paths drifted as a heading random walk of 0.5°/√s, stated as 0.05°/√s.
  const OdometryNoise stated;
  OdometryNoise truth = stated;
  truth.gyro_walk_rad_per_sqrt_s = 0.5 * kDegree;
  const std::vector<LoopEvidence> loops = loopsDrifting(truth);
  const OdometryNoise fitted = calibrateOdometryNoise(loops, stated);
  EXPECT_GT(fitted.gyro_walk_rad_per_sqrt_s, 0.25 * kDegree);
  EXPECT_LT(fitted.gyro_walk_rad_per_sqrt_s, 1.0 * kDegree);
  EXPECT_EQ(calibrateOdometryNoise({}, stated).gyro_walk_rad_per_sqrt_s, stated.gyro_walk_rad_per_sqrt_s);
}

TEST(slamNavigationCalibration, ANavigationAsGoodAsStatedKeepsItsNoise) {
  // Loops that drifted as stated, and as a tenth of it: the stated noise explains both and stands
  // (the class is the best the navigation is taken to be).
  const OdometryNoise stated;
  OdometryNoise better = stated;
  for (double OdometryNoise::*field : kOdometryNoiseParameters) better.*field = 0.1 * stated.*field;
  for (const OdometryNoise& truth : {stated, better}) {
    const OdometryNoise fitted = calibrateOdometryNoise(loopsDrifting(truth), stated);
    for (double OdometryNoise::*field : kOdometryNoiseParameters) EXPECT_EQ(fitted.*field, stated.*field);
  }
}

}  // namespace
}  // namespace sonarmap
