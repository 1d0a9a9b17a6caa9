/// @file point_scan_map.cpp
/// placedScanPoints, scanMapResolution and mapScans (point_scan_map.hpp).

#include "sonarmap/slam/point_scan_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Eigenvalues>

#include "sonarmap/algorithms/point_cloud_insertion.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/core/statistics.hpp"
#include "sonarmap/mapping/local_origin.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

std::vector<Eigen::Vector2d> placedScanPoints(const std::vector<SonarScan>& scans, const std::vector<Pose2>& poses) {
  std::vector<Eigen::Vector2d> points;
  for (std::size_t k = 0; k < scans.size() && k < poses.size(); ++k) {
    for (const ScanPoint& point : scans[k].points) points.push_back(poses[k] * point.xy_m);
  }
  return points;
}

double scanMapResolution(const std::vector<SonarScan>& scans) {
  std::vector<double> sigmas;
  for (const SonarScan& scan : scans) {
    for (const ScanPoint& point : scan.points) {
      sigmas.push_back(std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(point.covariance_m2, Eigen::EigenvaluesOnly)
                                     .eigenvalues()(1)));
    }
  }
  if (sigmas.empty()) throw ValueError("scans: no point to measure");
  return percentile(sigmas, 0.5);
}

OcTree16 mapScans(const std::vector<SonarScan>& scans, const std::vector<Pose2>& poses, double resolution_m) {
  if (!(std::isfinite(resolution_m) && resolution_m > 0.0)) {
    throw ValueError("scan map: resolution " + std::to_string(resolution_m) + " m is not > 0");
  }
  OcTree16 map(resolution_m);
  const Eigen::Isometry3d ned_to_map = nedToMap();
  const auto inMap = [&ned_to_map](const Eigen::Vector2d& ned_m) { return ned_to_map * Eigen::Vector3d(ned_m.x(), ned_m.y(), 0.0); };
  // The points of each sonar position (one beam, or the whole scan of a still vehicle) together, in
  // the map frame; every one checked to lie in the map before any is inserted (insertPointCloud
  // would drop those outside).
  struct Sight {
    Eigen::Vector3d sonar_m;
    PointCloud points_m;
  };
  std::vector<Sight> sights;
  double farthest_m = 0.0;
  bool outside = false;
  const auto reach = [&](const Eigen::Vector3d& p_m) {
    farthest_m = std::max(farthest_m, p_m.cwiseAbs().maxCoeff());
    outside = outside || !map.coder().keyOf(p_m);
  };
  for (std::size_t k = 0; k < scans.size() && k < poses.size(); ++k) {
    const std::vector<ScanPoint>& points = scans[k].points;
    std::size_t i = 0;
    while (i < points.size()) {
      const Eigen::Vector2d sonar = points[i].xy_m + points[i].range_m * points[i].toward_sonar;
      std::size_t end = i + 1;
      while (end < points.size() && (points[end].xy_m + points[end].range_m * points[end].toward_sonar - sonar).norm() < 1e-6) ++end;
      Sight& sight = sights.emplace_back(Sight{inMap(poses[k] * sonar), {}});
      reach(sight.sonar_m);
      for (std::size_t p = i; p < end; ++p) reach(sight.points_m.emplace_back(inMap(poses[k] * points[p].xy_m)));
      i = end;
    }
  }
  if (outside) {
    const double half_m = mapHalfExtent_m(resolution_m);
    char message[256];
    std::snprintf(message, sizeof message,
                  "scan map: the scans reach %.4g m from the origin, outside the map, which spans ±%.4g m at %g m voxels; "
                  "a resolution of at least %.3g m holds them",
                  farthest_m, half_m, resolution_m, resolution_m * farthest_m / half_m);
    throw OutOfMapError(message);
  }
  for (const Sight& sight : sights) insertPointCloud(map, sight.points_m, sight.sonar_m);
  return map;
}

}  // namespace sonarmap
