// Point scans placed with their poses (slam/point_scan_map.hpp): the points moved by each scan's
// pose, the map's default resolution from the points' covariances, and the occupancy map of a
// vehicle passing a straight quay: hits on the quay, free water between the sonar and it, nothing
// known behind it, in the map's NWU frame; a resolution too fine for the scans' extent refused
// before any insertion.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/slam/point_scan_map.hpp"
#include "sonarmap/slam/point_scans.hpp"

namespace sonarmap {
namespace {

constexpr double kSpeed_mps = 0.5;  // due north
constexpr double kQuayEast_m = 4.1;  // mid-voxel at 0.2 m: no point on a voxel boundary

/// The vehicle sailing north at kSpeed_mps for 40 s, heading 0, a fix every 0.5 s.
NavTrack northwardTrack() {
  NavTrack track;
  for (int i = 0; i <= 80; ++i) {
    NavSample fix;
    fix.time_s = 0.5 * i;
    fix.position_ned_m = {kSpeed_mps * fix.time_s, 0.0, 0.0};
    track.push_back(fix);
  }
  return track;
}

/// Four scans of 10 s, a point every 0.2 s on the quay to starboard (east = kQuayEast_m), from 2 m
/// astern to 2 m ahead of the vehicle, in the body frame at the point's time.
std::vector<BodyPoint> quayPoints() {
  std::vector<BodyPoint> points;
  for (std::size_t scan = 0; scan < 4; ++scan) {
    for (int i = 0; i < 50; ++i) {
      BodyPoint point;
      point.scan = scan;
      point.time_s = 10.0 * static_cast<double>(scan) + 0.2 * i;
      point.xy_m = {-2.0 + 4.0 * i / 49.0, kQuayEast_m};
      points.push_back(point);
    }
  }
  return points;
}

TEST(slamPointScanMap, PointsArePlacedWithEachScansPose) {
  SonarScan a, b;
  a.points.resize(1);
  a.points[0].xy_m = {1.0, 0.0};
  b.points.resize(2);
  b.points[0].xy_m = {0.0, 2.0};
  b.points[1].xy_m = {3.0, 0.0};
  const std::vector<Eigen::Vector2d> placed =
      placedScanPoints({a, b}, {Pose2{1.0, 2.0, std::numbers::pi / 2.0}, Pose2{-1.0, 0.0, 0.0}});
  ASSERT_EQ(placed.size(), 3U);
  EXPECT_TRUE(placed[0].isApprox(Eigen::Vector2d(1.0, 3.0)));
  EXPECT_TRUE(placed[1].isApprox(Eigen::Vector2d(-1.0, 2.0)));
  EXPECT_TRUE(placed[2].isApprox(Eigen::Vector2d(2.0, 0.0)));
  EXPECT_EQ(placedScanPoints({a, b}, {Pose2{}}).size(), 1U) << "a scan without a pose is left out";
}

TEST(slamPointScanMap, TheResolutionIsTheMedianOfThePointsLargerSigma) {
  SonarScan scan;
  for (const double sigma_m : {0.2, 0.5, 0.3}) {
    ScanPoint point;
    point.covariance_m2 = Eigen::Vector2d(0.01, sigma_m * sigma_m).asDiagonal();
    scan.points.push_back(point);
  }
  EXPECT_NEAR(scanMapResolution({scan, SonarScan{}}), 0.3, 1e-12);
  EXPECT_THROW(scanMapResolution({SonarScan{}}), ValueError);
  // The quay's points: the beam's width at 4–4.6 m (1.5 degrees) is their larger sigma.
  const std::vector<SonarScan> scans = formPointScans(quayPoints(), northwardTrack());
  const double bearing_sigma_rad = PointScanOptions{}.bearing_sigma_rad;
  EXPECT_GT(scanMapResolution(scans), 4.0 * bearing_sigma_rad);
  EXPECT_LT(scanMapResolution(scans), 1.5 * 4.6 * bearing_sigma_rad);
}

TEST(slamPointScanMap, TheMapHoldsTheQuayAndTheWaterBeforeIt) {
  const std::vector<SonarScan> scans = formPointScans(quayPoints(), northwardTrack());
  ASSERT_EQ(scans.size(), 4U);
  std::vector<Pose2> poses;
  for (const SonarScan& scan : scans) poses.push_back(scan.dead_reckoning);
  const OcTree16 map = mapScans(scans, poses, 0.2);
  EXPECT_DOUBLE_EQ(map.resolution_m(), 0.2);
  // NWU: x north, y west (east is −y), z up; depth 0 in the voxel [0, 0.2).
  for (const double north_m : {2.0, 6.0, 10.0, 14.0, 18.0}) {
    SCOPED_TRACE(north_m);
    EXPECT_EQ(map.occupancyAt({north_m, -kQuayEast_m, 0.1}), Occupancy::kOccupied);
    EXPECT_EQ(map.occupancyAt({north_m, -2.0, 0.1}), Occupancy::kFree);
    EXPECT_EQ(map.occupancyAt({north_m, -3.7, 0.1}), Occupancy::kFree);
    EXPECT_EQ(map.occupancyAt({north_m, -6.0, 0.1}), Occupancy::kUnknown) << "behind the quay";
    EXPECT_EQ(map.occupancyAt({north_m, 2.0, 0.1}), Occupancy::kUnknown) << "to port, never looked at";
    EXPECT_EQ(map.occupancyAt({north_m, -kQuayEast_m, 0.3}), Occupancy::kUnknown) << "the map is one layer";
  }
  // The same scans placed 1 m further east: the quay moves with them.
  for (Pose2& pose : poses) pose.y_m += 1.0;
  const OcTree16 moved = mapScans(scans, poses, 0.2);
  EXPECT_EQ(moved.occupancyAt({10.0, -kQuayEast_m - 1.0, 0.1}), Occupancy::kOccupied);
  EXPECT_EQ(moved.occupancyAt({10.0, -kQuayEast_m, 0.1}), Occupancy::kFree);
}

TEST(slamPointScanMap, AResolutionTooFineForTheScansIsRefused) {
  const std::vector<SonarScan> scans = formPointScans(quayPoints(), northwardTrack());
  std::vector<Pose2> poses;
  for (const SonarScan& scan : scans) poses.push_back(scan.dead_reckoning);
  // At 0.1 mm a 16-level map spans ±3.3 m; the quay is 4.1 m off and the vehicle sails 20 m.
  try {
    mapScans(scans, poses, 1e-4);
    ADD_FAILURE() << "no error";
  } catch (const OutOfMapError& error) {
    EXPECT_NE(std::string(error.what()).find("0.0001 m voxels"), std::string::npos) << error.what();
  }
  EXPECT_THROW(mapScans(scans, poses, 0.0), ValueError);
  EXPECT_THROW(mapScans(scans, poses, std::nan("")), ValueError);
}

}  // namespace
}  // namespace sonarmap
