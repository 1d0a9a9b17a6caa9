#pragma once
/// @file scan_points.hpp
/// Private helper of the slam layer's scan forming (scan_forming.cpp from detected sweeps,
/// point_scans.cpp from SCANS.csv): a detected point placed in its scan's reference frame with its
/// covariance, the same way whichever way it was detected.

#include <cmath>
#include <optional>

#include <Eigen/Geometry>

#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/slam/pose2.hpp"
#include "sonarmap/slam/scan_forming.hpp"

namespace sonarmap::scan_points {

/// Where the body was at `time_s` by dead reckoning; nullopt outside the track. No track: the
/// origin, always (the vehicle believed still).
inline std::optional<Eigen::Isometry3d> deadReckoningAt(const std::optional<NavInterpolator>& nav, double time_s) {
  if (!nav) return Eigen::Isometry3d::Identity();
  return nav->bodyToNedAt(time_s);
}

/// How a point was measured.
struct Measurement {
  Eigen::Vector3d point_ned_m;   ///< the point, NED, metres (placed with the dead reckoning at its time)
  Eigen::Vector3d origin_ned_m;  ///< where it was seen from (the sonar), NED, metres
  Eigen::Isometry3d body_to_ned;  ///< the body's dead-reckoning pose at its time
  double time_s = 0.0;
  double range_m = 0.0;           ///< from the sonar, metres
  double range_sigma_m = 0.0;     ///< 1σ along the line of sight, metres
  double bearing_sigma_rad = 0.0;  ///< 1σ across it, radians
};

/// Appends `m` to `scan` (whose time_s and dead_reckoning are set): the point in the scan's
/// reference body frame; its covariance σ_r² along the line of sight and (range · σ_b)² across it
/// (Mallios et al. 2014), plus what dead reckoning adds between the point's time and the reference
/// time (OdometryNoise::covariance: the position's uncertainty, and the heading's, which swings the
/// point across the line of sight). A point straight below its sonar (no horizontal line of sight)
/// is skipped.
inline void appendPoint(SonarScan& scan, const Measurement& m, const ScanFormingOptions& forming, bool known) {
  const Pose2 ned_to_reference = scan.dead_reckoning.inverse();
  ScanPoint point;
  point.range_m = m.range_m;
  point.time_offset_s = m.time_s - scan.time_s;
  point.xy_m = ned_to_reference * Eigen::Vector2d(m.point_ned_m.x(), m.point_ned_m.y());
  Eigen::Vector2d along = ned_to_reference.rotation() * (m.point_ned_m - m.origin_ned_m).head<2>();
  if (along.norm() < 1e-9) return;
  along.normalize();
  point.toward_sonar = -along;
  const Eigen::Vector2d across(-along.y(), along.x());
  const double cross_sigma_m = m.range_m * m.bearing_sigma_rad;
  point.covariance_m2 = along * along.transpose() * (m.range_sigma_m * m.range_sigma_m) +
                        across * across.transpose() * (cross_sigma_m * cross_sigma_m);
  const Pose2 motion = scan.dead_reckoning.between(planarPose(m.body_to_ned));
  const Eigen::Matrix3d drift = forming.odometry.covariance(motion, m.time_s - scan.time_s, known);
  point.covariance_m2 += drift.topLeftCorner<2, 2>();  // already in the reference frame
  point.covariance_m2 += across * across.transpose() * (m.range_m * m.range_m * drift(2, 2));
  scan.points.push_back(point);
}

}  // namespace sonarmap::scan_points
