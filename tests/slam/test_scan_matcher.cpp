// The scan matcher (slam/scan_matcher.hpp): known offsets recovered, ambiguity reported, and the
// pose graph's square-root information.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sonarmap/slam/pose_graph.hpp"
#include "sonarmap/slam/scan_matcher.hpp"

namespace sonarmap {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

ScanPoint point(double x, double y, double sigma_m = 0.03) {
  ScanPoint p;
  p.xy_m = {x, y};
  p.covariance_m2 = Eigen::Matrix2d::Identity() * sigma_m * sigma_m;
  p.range_m = std::hypot(x, y);
  return p;
}

/// Two walls at a corner (x = 4, y from −3 to 3; y = 3, x from −2 to 4) and two piles.
std::vector<ScanPoint> corner(double spacing_m = 0.1) {
  std::vector<ScanPoint> points;
  for (double y = -3.0; y <= 3.0; y += spacing_m) points.push_back(point(4.0, y));
  for (double x = -2.0; x < 4.0; x += spacing_m) points.push_back(point(x, 3.0));
  for (const double angle : {0.0, 1.0, 2.0, 3.0, 4.0, 5.0}) {
    points.push_back(point(1.0 + 0.2 * std::cos(angle), -1.5 + 0.2 * std::sin(angle)));
  }
  return points;
}

/// `points` as seen from `pose` (their coordinates in that frame).
std::vector<ScanPoint> seenFrom(const std::vector<ScanPoint>& points, const Pose2& pose) {
  std::vector<ScanPoint> seen;
  for (const ScanPoint& p : points) {
    ScanPoint q = p;
    q.xy_m = pose.inverse() * p.xy_m;
    seen.push_back(q);
  }
  return seen;
}

Eigen::Matrix3d prior(double sigma_m, double sigma_rad) {
  return Eigen::Vector3d(sigma_m * sigma_m, sigma_m * sigma_m, sigma_rad * sigma_rad).asDiagonal();
}

TEST(slamScanMatcher, RecoversAKnownOffsetFromTheInitialGuess) {
  const std::vector<ScanPoint> target = corner();
  const Pose2 truth{0.25, -0.15, 3.0 * kDeg};
  const std::vector<ScanPoint> source = seenFrom(target, truth);
  const ScanMatch match = matchScans(target, source, Pose2{}, prior(0.3, 5.0 * kDeg), false);
  ASSERT_TRUE(match.accepted) << match.reason;
  EXPECT_NEAR(match.pose.x_m, truth.x_m, 0.01);
  EXPECT_NEAR(match.pose.y_m, truth.y_m, 0.01);
  EXPECT_NEAR(match.pose.yaw_rad, truth.yaw_rad, 0.2 * kDeg);
}

TEST(slamScanMatcher, CorrelativeSearchFindsAnOffsetBeyondTheIcpBasin) {
  const std::vector<ScanPoint> target = corner();
  const Pose2 truth{1.2, -0.9, 6.0 * kDeg};
  const std::vector<ScanPoint> source = seenFrom(target, truth);
  const ScanMatch match = matchScans(target, source, Pose2{}, prior(0.8, 4.0 * kDeg), true);
  ASSERT_TRUE(match.accepted) << match.reason;
  EXPECT_TRUE(match.searched);
  EXPECT_NEAR(match.pose.x_m, truth.x_m, 0.02);
  EXPECT_NEAR(match.pose.y_m, truth.y_m, 0.02);
  EXPECT_NEAR(match.pose.yaw_rad, truth.yaw_rad, 0.3 * kDeg);
}

TEST(slamScanMatcher, OneLongWallIsAmbiguousAndSaysWhy) {
  std::vector<ScanPoint> wall;
  for (double y = -10.0; y <= 10.0; y += 0.1) wall.push_back(point(4.0, y));
  const std::vector<ScanPoint> source = seenFrom(wall, Pose2{0.1, 0.5, 0.0});
  const ScanMatch match = matchScans(wall, source, Pose2{}, prior(1.0, 2.0 * kDeg), true);
  EXPECT_FALSE(match.accepted);
  EXPECT_NE(match.reason.find("ambiguous"), std::string::npos) << match.reason;
  // The offset across the wall is still measured, and information along the wall is nil.
  EXPECT_NEAR(match.pose.x_m, 0.1, 0.02);
  EXPECT_LT(match.information(1, 1), 1e-3 * match.information(0, 0));
}

TEST(slamScanMatcher, TooFewPointsAreRefused) {
  const std::vector<ScanPoint> few{point(1, 0), point(2, 0), point(3, 1)};
  const ScanMatch match = matchScans(corner(), few, Pose2{}, prior(0.3, 0.1), false);
  EXPECT_FALSE(match.accepted);
  EXPECT_NE(match.reason.find("too few"), std::string::npos);
}

TEST(slamScanMatcher, IsDeterministic) {
  const std::vector<ScanPoint> target = corner();
  const std::vector<ScanPoint> source = seenFrom(target, Pose2{0.7, 0.4, -4.0 * kDeg});
  const ScanMatch a = matchScans(target, source, Pose2{}, prior(0.6, 5.0 * kDeg), true);
  const ScanMatch b = matchScans(target, source, Pose2{}, prior(0.6, 5.0 * kDeg), true);
  EXPECT_EQ(a.pose.x_m, b.pose.x_m);
  EXPECT_EQ(a.pose.y_m, b.pose.y_m);
  EXPECT_EQ(a.pose.yaw_rad, b.pose.yaw_rad);
}

TEST(slamScanMatcher, RejectsInvalidOptions) {
  ScanMatchOptions options;
  options.min_overlap = 0.0;
  EXPECT_THROW(matchScans(corner(), corner(), Pose2{}, prior(0.1, 0.1), false, options), ValueError);
}

TEST(slamPoseGraph, SquareRootOfInformationReproducesIt) {
  Eigen::Matrix3d information;
  information << 4, 1, 0, 1, 3, 0.5, 0, 0.5, 2;
  const Eigen::Matrix3d root = informationSqrt(information);
  EXPECT_TRUE((root.transpose() * root).isApprox(information, 1e-12));
  // A direction without information stays without it.
  const Eigen::Matrix3d singular = Eigen::Vector3d(1.0, 0.0, 1.0).asDiagonal();
  EXPECT_NEAR((informationSqrt(singular).transpose() * informationSqrt(singular))(1, 1), 0.0, 1e-12);
}

TEST(slamPoseGraph, OdometryAndALoopClosureSpreadTheError) {
  PoseGraph graph;
  // A square of four 1 m sides whose odometry says each turn is 95°: the loop closure says the last
  // node is back at the first.
  graph.addNode(Pose2{});
  const Pose2 step{1.0, 0.0, 95.0 * kDeg};
  for (int i = 1; i <= 4; ++i) {
    graph.addNode(graph.pose(static_cast<std::size_t>(i - 1)) * step);
    graph.addEdge({static_cast<std::size_t>(i - 1), static_cast<std::size_t>(i), step,
                   Eigen::Vector3d(100.0, 100.0, 100.0).asDiagonal(), EdgeKind::kOdometry});
  }
  graph.addEdge({0, 4, Pose2{0.0, 0.0, 0.0}, Eigen::Vector3d(1e4, 1e4, 1e4).asDiagonal(), EdgeKind::kLoopClosure});
  const double before = graph.pose(4).translation().norm();
  ASSERT_TRUE(graph.optimize());
  EXPECT_GT(before, 0.05);
  EXPECT_LT(graph.pose(4).translation().norm(), 0.01);
  EXPECT_EQ(graph.pose(0).x_m, 0.0);  // the first node is held
}

TEST(slamPoseGraph, TheScaleSigmaSaysWhetherTheEdgesConstrainIt) {
  // Ten 1 m odometry steps along x; matches say each step was 1.02 m. With the matches, the scale
  // is measured (1.02, σ well under the prior's 3 %); with odometry alone, only the prior speaks.
  const auto chain = [](bool with_matches) {
    PoseGraph graph;
    graph.estimateOdometryScale(0.03);
    graph.addNode(Pose2{});
    for (std::size_t i = 1; i <= 10; ++i) {
      graph.addNode(graph.pose(i - 1) * Pose2{1.0, 0.0, 0.0});
      graph.addEdge({i - 1, i, Pose2{1.0, 0.0, 0.0}, Eigen::Vector3d(1e4, 1e4, 1e6).asDiagonal(), EdgeKind::kOdometry});
      if (with_matches) {
        graph.addEdge({i - 1, i, Pose2{1.02, 0.0, 0.0}, Eigen::Vector3d(1e4, 1e4, 1e6).asDiagonal(), EdgeKind::kScanMatch});
      }
    }
    PoseGraphOptions options;
    options.scale_covariance = true;
    EXPECT_TRUE(graph.optimize(options));
    return graph;
  };
  const PoseGraph measured = chain(true);
  EXPECT_NEAR(measured.odometryScale(), 1.02, 0.002);
  EXPECT_GT(measured.odometryScaleSigma(), 0.0);
  EXPECT_LT(measured.odometryScaleSigma(), 0.01);
  const PoseGraph unmeasured = chain(false);
  EXPECT_NEAR(unmeasured.odometryScaleSigma(), 0.03, 0.003);
  // Not asked for: not computed.
  PoseGraph plain = chain(true);
  ASSERT_TRUE(plain.optimize());
  EXPECT_EQ(plain.odometryScaleSigma(), 0.0);
  // Fixed, the scale is 1 and the graph follows the edges as they are.
  plain.fixOdometryScale();
  EXPECT_FALSE(plain.estimatesOdometryScale());
  EXPECT_EQ(plain.odometryScale(), 1.0);
  EXPECT_THROW(plain.setInformation(plain.edges().size(), Eigen::Matrix3d::Identity()), ValueError);
}

}  // namespace
}  // namespace sonarmap
