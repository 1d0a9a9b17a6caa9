/// @file test_odometry_chain.cpp
/// OdometryChain (slam/odometry_chain.hpp): the prefix-sum covariance of any path equals the
/// covariance composed edge by edge (composeCovariance), forwards and backwards, before and after
/// the edges' covariances are restated.

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "sonarmap/slam/odometry_chain.hpp"
#include "sonarmap/slam/pose2_covariance.hpp"

namespace sonarmap {
namespace {

Eigen::Matrix3d randomCovariance(std::mt19937& random) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Matrix3d a;
  for (int i = 0; i < 9; ++i) a(i / 3, i % 3) = normal(random);
  const Eigen::Vector3d scale(0.05, 0.08, 0.01);
  return scale.asDiagonal() * (a * a.transpose() + 0.1 * Eigen::Matrix3d::Identity()) * scale.asDiagonal();
}

/// The covariance of node b in node a's frame composed edge by edge.
Eigen::Matrix3d composed(const std::vector<Pose2>& motions, const std::vector<Eigen::Matrix3d>& covariances, std::size_t a,
                         std::size_t b) {
  Pose2 chain;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t i = a + 1; i <= b; ++i) {
    covariance = composeCovariance(chain, covariance, motions[i], covariances[i]);
    chain = chain * motions[i];
  }
  return covariance;
}

TEST(slamOdometryChain, PathCovarianceEqualsTheComposedOne) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> step(-3.0, 3.0), turn(-0.6, 0.6);
  std::vector<Pose2> motions{Pose2{}};
  std::vector<Eigen::Matrix3d> covariances{Eigen::Matrix3d::Zero()};
  OdometryChain chain;
  for (int i = 1; i < 40; ++i) {
    motions.push_back({step(random) + 3.0, step(random), turn(random)});
    covariances.push_back(randomCovariance(random));
    chain.append(motions.back(), covariances.back());
  }
  ASSERT_EQ(chain.size(), 40u);
  for (const auto& [a, b] : std::vector<std::pair<std::size_t, std::size_t>>{{0, 39}, {3, 17}, {10, 11}, {25, 39}, {5, 5}}) {
    const Eigen::Matrix3d expected = composed(motions, covariances, a, b);
    EXPECT_LT((chain.covariance(a, b) - expected).norm(), 1e-9 * (1.0 + expected.norm())) << a << " -> " << b;
    if (a != b) {
      const Eigen::Matrix3d backwards = inverseCovariance(chain.between(b, a).inverse(), expected);
      EXPECT_LT((chain.covariance(b, a) - backwards).norm(), 1e-9 * (1.0 + backwards.norm())) << b << " -> " << a;
    }
    Pose2 pose;
    for (std::size_t i = a + 1; i <= b; ++i) pose = pose * motions[i];
    EXPECT_NEAR(chain.between(a, b).x_m, pose.x_m, 1e-9);
    EXPECT_NEAR(chain.between(a, b).yaw_rad, pose.yaw_rad, 1e-9);
  }
  // Restated covariances: the same sums anew.
  for (std::size_t i = 1; i < covariances.size(); ++i) covariances[i] = 4.0 * randomCovariance(random);
  chain.restate(covariances);
  const Eigen::Matrix3d expected = composed(motions, covariances, 2, 33);
  EXPECT_LT((chain.covariance(2, 33) - expected).norm(), 1e-9 * (1.0 + expected.norm()));
}

}  // namespace
}  // namespace sonarmap
