#pragma once
/// @file scan_forming.hpp
/// Scans for scan matching: the obstacles a mechanically scanned sonar detects over one sweep (a
/// full turn, or one pass across a sector), each placed with the dead-reckoning pose at its own
/// beam's time and expressed in the frame of one reference pose of the sweep, with its uncertainty
/// (motion compensation, as MSISpIC: Mallios et al. 2010, "Probabilistic sonar scan matching for an
/// AUV", IROS; and 2014, J. Field Robotics 31(1)). A Micron turn takes about 8.6 s and a SeaKing's
/// about 28 s, during which the vehicle moves metres: points placed with one pose would smear a
/// wall into a curve.
///
/// Frames: NED's horizontal plane (pose2.hpp); a scan's points are in its reference body frame
/// (x forward, y starboard, metres), the vehicle's dead-reckoning pose at the scan's reference time.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/mapping/detected_log.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/slam/odometry_noise.hpp"
#include "sonarmap/slam/pose2.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// One detected obstacle of a scan.
struct ScanPoint {
  Eigen::Vector2d xy_m = Eigen::Vector2d::Zero();  ///< in the scan's reference body frame, metres
  /// Covariance of xy_m, m²: the range's (a bin, the echo's rise) along the beam, the beam width's
  /// across it, plus what dead reckoning adds between the beam's time and the reference time.
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Identity();
  double range_m = 0.0;  ///< from the sonar, metres
  /// Unit vector from the point back towards the sonar that saw it (scan frame); zero: unknown. A
  /// sonar sees the side of a surface that faces it, so an isolated point (a pile) is matched
  /// along this direction only: the same pile seen from elsewhere gives points up to its radius
  /// apart across it, and pairing them as one point would bias the match towards no motion.
  Eigen::Vector2d toward_sonar = Eigen::Vector2d::Zero();
  /// The time the point was measured, seconds after the scan's reference time (SonarScan::time_s;
  /// negative before it).
  double time_offset_s = 0.0;
};

/// The detections of one sweep, motion-compensated.
struct SonarScan {
  double time_s = 0.0;            ///< reference time: the time of the sweep's middle beam
  Pose2 dead_reckoning;           ///< the body's dead-reckoning pose in NED at time_s
  double start_time_s = 0.0;      ///< first beam's time
  double end_time_s = 0.0;        ///< last beam's time
  std::size_t first_beam = 0;     ///< index of the sweep's first beam in the log
  std::size_t beams = 0;          ///< beams in the sweep
  double reach_m = 0.0;           ///< longest beam range of the sweep, metres
  std::vector<ScanPoint> points;  ///< one per beam with an obstacle
  /// Point scans (formPointScans): rows left out as lying behind their echo's leading edge.
  std::size_t points_behind_echoes = 0;
};

/// How scans are formed.
struct ScanFormingOptions {
  OdometryNoise odometry;
  /// 1σ of an obstacle's range, metres, ≥ 0; 0: automatic, max(bin length, the echo's rise / 2,
  /// 2 cm).
  double range_sigma_m = 0.0;
  /// 1σ of its bearing, radians, ≥ 0; 0: automatic, half the mapper's horizontal beam width
  /// (MapperOptions::beam_width_rad), at least half the bearing step.
  double bearing_sigma_rad = 0.0;
  /// Most dead-reckoning travel within one scan, metres, ≥ 0: a sweep during which the vehicle
  /// travels farther is cut into consecutive scans of about this much travel each, so that dead
  /// reckoning's drift within a scan stays small (a SeaKing turn at 30 m takes 24 s: 36 m at
  /// 1.5 m/s). 0: automatic, half the sweep's reach (the Micron at 0.25 m/s, 2.2 m a turn, keeps
  /// whole turns).
  double max_travel_m = 0.0;
  /// Place each point of a surface seen obliquely at the bearing its leading edge came from (off its
  /// beam's axis towards the surface's normal, by up to half the beam width: scan_forming.cpp,
  /// leadingEdgeTurns) instead of on the beam's axis, where a 3° beam at 25 m draws a quay seen at
  /// 40° a quarter to a third of a metre too near. Off by default: with the true navigation stated
  /// as a DVL-aided INS it takes the SeaKing's and Ping360's error from 0.035–0.103 m to
  /// 0.006–0.026 m (the SeaKing hull loop excepted: 0.074 → 0.090 m), but with drifting dead
  /// reckoning it makes most missions worse and the Micron hull loop closes loops wrongly
  /// (docs/localization.md).
  bool leading_edge_bearing = false;

  /// @throws ValueError for a sigma or travel that is negative or not finite, or invalid odometry
  ///         noise (OdometryNoise::validate).
  void validate() const;
};

/// Forms one scan per detected sweep of `detected` (detectSonarLog: the mapper's sweeps and
/// detections; several scans when the vehicle travels farther than
/// ScanFormingOptions::max_travel_m during one), placing each first obstacle with the dead-reckoning body
/// pose at its beam's time (interpolateBodyToNed on `dead_reckoning`), the sonar's mounting
/// `sonar_to_body` and the horizontal projection of the beam. Beams outside the navigation's span
/// are skipped. An empty `dead_reckoning`: the vehicle is believed still at the origin (every pose
/// zero). The beams' width (the bearing's uncertainty when ScanFormingOptions leaves it automatic)
/// is detected.options.beam_width_rad.
/// @throws ValueError for invalid options or an invalid navigation track (NavInterpolator).
std::vector<SonarScan> formScans(const DetectedLog& detected, const NavTrack& dead_reckoning,
                                 const Eigen::Isometry3d& sonar_to_body, const ScanFormingOptions& forming = {});

/// formScans(detectSonarLog(log, options), ...): the log's sweeps detected as the mapper detects
/// them. Cost: the detection of every sweep (about the mapper's detection time).
/// @throws ValueError as detectSonarLog and the overload above.
std::vector<SonarScan> formScans(const SonarLog& log, const NavTrack& dead_reckoning,
                            const Eigen::Isometry3d& sonar_to_body, const MapperOptions& options,
                            const ScanFormingOptions& forming = {});

/// The planar pose (x, y, heading) of a body-to-NED transform: its translation's x, y and the yaw of
/// its rotation (Z-Y-X Euler angles: atan2(R(1,0), R(0,0))).
Pose2 planarPose(const Eigen::Isometry3d& body_to_ned);

}  // namespace sonarmap
