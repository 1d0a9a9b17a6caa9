/// @file test_loop_consistency.cpp
/// Loop closures kept as the largest set that agrees pairwise (Localizer, consistency_graph.hpp),
/// and a corridor's match: its information says it cannot see the motion along the corridor, and
/// the track keeps the dead reckoning's motion there while the walls fix the rest.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sonarmap/slam/consistency_graph.hpp"
#include "sonarmap/slam/localizer.hpp"
#include "sonarmap/slam/scan_matcher.hpp"

namespace sonarmap {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(slamConsistencyGraph, LargestCliqueKeepsTheAgreeingSet) {
  // Vertices 0–4 agree with each other; 5 and 6 agree with each other and with 0 only.
  ConsistencyGraph graph;
  graph.addVertex({});
  for (std::size_t v = 1; v < 5; ++v) {
    std::vector<std::size_t> all;
    for (std::size_t u = 0; u < v; ++u) all.push_back(u);
    graph.addVertex(all);
  }
  graph.addVertex({0});
  graph.addVertex({0, 5});
  EXPECT_EQ(graph.largestClique(), (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(graph.cliqueFrom(6), (std::vector<std::size_t>{0, 5, 6}));
  EXPECT_TRUE(graph.joined(6, 5));
  EXPECT_FALSE(graph.joined(6, 1));
  EXPECT_THROW(graph.addVertex({9}), ValueError);
}

/// Scans without points along a square driven twice (20 m sides, 2 m a scan), their dead reckoning
/// 3 % long: loop closures are all the localizer has to go on.
struct SquareTwice {
  std::vector<Pose2> truth;
  Localizer localizer{SlamOptions{}};
  SquareTwice() {
    Pose2 pose;
    Pose2 believed;
    for (int k = 0; k < 80; ++k) {
      const Pose2 step = (k % 10 == 9) ? Pose2{2.0, 0.0, std::numbers::pi / 2.0} : Pose2{2.0, 0.0, 0.0};
      if (k > 0) {
        pose = pose * step;
        believed = believed * Pose2{1.03 * step.x_m, step.y_m, step.yaw_rad};
      }
      truth.push_back(pose);
      SonarScan scan;
      scan.time_s = 10.0 * k;
      scan.start_time_s = scan.time_s - 4.0;
      scan.end_time_s = scan.time_s + 4.0;
      scan.dead_reckoning = believed;
      scan.reach_m = 10.0;
      localizer.addScan(scan);
    }
  }
  /// Scan `to` seen from scan `from` as it truly was, stated with 5 cm and 0.5°.
  bool propose(std::size_t from, std::size_t to, const Pose2& error = {}) {
    const Pose2 measured = truth[from].between(truth[to]) * error;
    return localizer.proposeLoopClosure(from, to, measured, Eigen::Vector3d(400.0, 400.0, 1.0 / std::pow(0.5 * kDeg, 2)).asDiagonal());
  }
};

TEST(slamLoopConsistency, KeepsTheAgreeingLoopClosuresAndRefusesTheOneThatDisagrees) {
  SquareTwice square;
  // The second lap onto the first, where the truth says: they agree with each other.
  EXPECT_TRUE(square.propose(5, 45));
  EXPECT_TRUE(square.propose(15, 55));
  EXPECT_TRUE(square.propose(25, 65));
  // One 3 m along the side: it disagrees with all three.
  EXPECT_FALSE(square.propose(35, 75, Pose2{3.0, 0.0, 0.0}));
  EXPECT_EQ(square.localizer.report().loop_closures.back().reason, "inconsistent with the accepted loop closures");
  EXPECT_TRUE(square.propose(30, 70));
  square.localizer.optimize();
  const SlamReport& report = square.localizer.report();
  ASSERT_EQ(report.loop_closures.size(), 5U);
  EXPECT_EQ(report.loopClosuresAccepted(), 4U);
  EXPECT_FALSE(report.loop_closures[3].accepted);
  // The last scan where the truth puts it: the scale error taken out by the loops.
  const Pose2 end = square.localizer.graph().pose(0).between(square.localizer.graph().pose(79));
  const Pose2 true_end = square.truth[0].between(square.truth[79]);
  EXPECT_LT((end.translation() - true_end.translation()).norm(), 0.5);
}

TEST(slamLoopConsistency, TwoAgreeingLoopClosuresOutvoteOneAcceptedAlone) {
  SquareTwice square;
  // A wrong one first, alone: the dead reckoning over the 80 m between its scans cannot rule out
  // 1.5 m, so it stands...
  EXPECT_TRUE(square.propose(5, 45, Pose2{0.0, 1.5, 0.0}));
  // ... until two of the next scans, which agree with each other and, over the 2 m between them,
  // not with it, replace it.
  EXPECT_FALSE(square.propose(6, 46));
  EXPECT_TRUE(square.propose(7, 47));
  const SlamReport& report = square.localizer.report();
  EXPECT_FALSE(report.loop_closures[0].accepted);
  EXPECT_EQ(report.loop_closures[0].reason, "inconsistent with a larger set of loop closures that agree");
  EXPECT_TRUE(report.loop_closures[1].accepted);
  EXPECT_TRUE(report.loop_closures[2].accepted);
}

/// Points every 5 cm on the two walls of a corridor along north (east ±2 m), within 10 m of
/// `pose` (the body's true pose), in its frame, each facing it.
std::vector<ScanPoint> corridorScan(const Pose2& pose) {
  std::vector<ScanPoint> points;
  const Pose2 to_body = pose.inverse();
  for (const double east : {-2.0, 2.0}) {
    for (double north = pose.x_m - 10.0; north <= pose.x_m + 10.0; north += 0.05) {
      ScanPoint point;
      point.xy_m = to_body * Eigen::Vector2d(north, east);
      point.range_m = point.xy_m.norm();
      point.toward_sonar = -point.xy_m.normalized();
      point.covariance_m2 = Eigen::Matrix2d::Identity() * 0.02 * 0.02;
      points.push_back(point);
    }
  }
  return points;
}

TEST(slamCorridor, AMatchAlongACorridorSaysItCannotSeeTheMotionAlongIt) {
  const std::vector<ScanPoint> target = corridorScan({});
  const Pose2 truth{1.5, 0.1, 0.0};
  const ScanMatch match = matchScans(target, corridorScan(truth), Pose2{1.2, 0.0, 0.0},
                                     Eigen::Vector3d(0.25, 0.25, std::pow(2.0 * kDeg, 2)).asDiagonal(), false);
  EXPECT_EQ(match.reason.rfind("ambiguous: constrained", 0), 0U) << match.reason;
  // Across the corridor and in heading it measures; along it, nothing.
  EXPECT_NEAR(match.pose.y_m, 0.1, 0.02);
  EXPECT_LT(match.information(0, 0), 1e-6 * match.information(1, 1));
}

TEST(slamCorridor, TheTrackKeepsTheDeadReckoningAlongACorridorAndTheWallsAcrossIt) {
  // 30 scans 2 m apart down the corridor; the dead reckoning 10 % long and drifting 0.05 m a scan
  // towards the east wall.
  Localizer localizer{SlamOptions{}};
  std::vector<Pose2> truth, believed;
  for (int k = 0; k < 30; ++k) {
    truth.push_back({2.0 * k, 0.0, 0.0});
    believed.push_back({2.2 * k, 0.05 * k, 0.0});
    SonarScan scan;
    scan.time_s = 5.0 * k;
    scan.start_time_s = scan.time_s - 2.0;
    scan.end_time_s = scan.time_s + 2.0;
    scan.dead_reckoning = believed.back();
    scan.reach_m = 10.0;
    scan.points = corridorScan(truth.back());
    localizer.addScan(scan);
  }
  localizer.optimize();
  const Pose2 end = localizer.graph().pose(29);
  EXPECT_NEAR(end.y_m, 0.0, 0.1);                       // the walls took the drift across out
  EXPECT_NEAR(end.x_m, believed.back().x_m, 0.5);       // along, nothing pulled it from the dead reckoning
  EXPECT_GT(std::abs(end.x_m - truth.back().x_m), 5.0);  // (which no scan could correct)
}

}  // namespace
}  // namespace sonarmap
