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
#include "sonarmap/slam/pose2.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// How far dead reckoning may be trusted: the noise model of odometry between two poses, in the
/// units of the sensors it stands for (a DVL's velocity, a compass's or gyro's heading). The
/// defaults describe a modest DVL and AHRS (drift of a few per cent of distance travelled).
struct OdometryNoise {
  double scale_sigma = 0.03;  ///< 1σ fractional error of the distance travelled (DVL scale), ≥ 0
  /// 1σ heading error, radians, ≥ 0: the cross-track error it causes grows with the distance.
  double heading_sigma_rad = 1.5 * 3.14159265358979323846 / 180.0;
  double velocity_noise_mps = 0.05;  ///< 1σ white noise of each velocity reading, m/s, ≥ 0
  double nav_period_s = 0.1;         ///< time between velocity readings (the navigation's fix period), > 0
  /// Heading random walk, rad/√s, ≥ 0 (a gyro's angle random walk; a compass: its noise).
  double gyro_walk_rad_per_sqrt_s = 0.05 * 3.14159265358979323846 / 180.0;
  /// Without navigation (a log mapped with --slam but no --nav): the vehicle is believed still,
  /// and may have moved at this speed (1σ, m/s, > 0) in any direction and turned at
  /// unknown_turn_sigma_radps.
  double unknown_speed_sigma_mps = 0.2;
  double unknown_turn_sigma_radps = 2.0 * 3.14159265358979323846 / 180.0;  ///< rad/s, > 0
  /// The vehicle's limits where the navigation measures no position (no navigation, or
  /// position_measured false): Localizer refuses a scan match that needs the vehicle to have moved
  /// faster than max_speed_mps (m/s, > 0) since the scan before or, without navigation, to have
  /// turned faster than max_turn_rate_radps (rad/s, > 0; with a heading sensor the turn is
  /// measured). The defaults bound small ROVs and AUVs: 2 m/s is above a BlueROV2's or a small
  /// survey AUV's top speed (1.5–2 m/s), 30°/s above a piloted ROV's usual yaw rate. A user who
  /// knows the vehicle's motion (a tethered ROV drifting in a pool) states tighter ones.
  double max_speed_mps = 2.0;
  double max_turn_rate_radps = 30.0 * 3.14159265358979323846 / 180.0;
  /// false: the navigation measures the heading only (an AHRS or a compass without a DVL or a
  /// positioning system, as a BlueROV2's flight log without one: north and east stay 0). Its
  /// position between two poses is then unknown, as without navigation (unknown_speed_sigma_mps),
  /// and its heading is measured (gyro_walk_rad_per_sqrt_s).
  bool position_measured = true;

  /// Covariance (x, y, yaw; m², rad²) of the relative motion `delta` (in the frame of its start)
  /// measured by dead reckoning over `duration_s`: along-track σ² = (scale_sigma · d)² + noise,
  /// cross-track σ² = (heading_sigma_rad · d)² + noise, where d = |delta's translation| and noise =
  /// velocity_noise² · nav_period · duration (white velocity noise integrated); yaw σ² =
  /// gyro_walk² · duration. `known` false: the no-navigation model, isotropic
  /// (unknown_speed_sigma · duration)² and (unknown_turn_sigma · duration)²; with `known` but
  /// position_measured false, the position's part is the no-navigation model's. A floor of
  /// (1 mm)² and (0.01°)² keeps it invertible.
  Eigen::Matrix3d covariance(const Pose2& delta, double duration_s, bool known = true) const;
  /// @throws ValueError naming the field when a value is negative, zero where it must be > 0, or
  ///         not finite.
  void validate() const;
};

/// The odometry noise of a class of navigation sensors (what a user knows of the vehicle), by name:
/// - "dvl-ahrs" (the default, OdometryNoise{}): a DVL with an AHRS or magnetic compass, drifting a
///   few per cent of the distance travelled (scale 3 %, heading 1.5°, velocity noise 0.05 m/s,
///   gyro walk 0.05°/√s);
/// - "dvl-ins": a DVL-aided inertial navigation system with a fibre-optic gyro, whose makers
///   state 0.1–0.3 % of the distance travelled (scale 0.3 %, heading 0.2°, velocity noise
///   0.01 m/s, gyro walk 0.01°/√s);
/// - "absolute": navigation aided by absolute fixes (USBL, DGPS at the surface) or
///   post-processed, centimetres over the scans' spacing (scale 0.1 %, heading 0.1°, velocity
///   noise 0.005 m/s, gyro walk 0.005°/√s);
/// - "ahrs": the heading only, from an AHRS or a magnetic compass without a DVL (a BlueROV2 without
///   one: its flight log's north and east stay 0). OdometryNoise::position_measured is false: the
///   position comes from the scans (Localizer), the heading is the AHRS's (heading 1.5°, gyro walk
///   0.05°/√s, as dvl-ahrs).
/// The scans move the navigation only as far as their information outweighs this noise, so a
/// good navigation stated as such is left nearly where it is.
/// @throws ValueError naming the known classes for any other name.
OdometryNoise odometryNoiseOf(std::string_view navigation_class);

/// The names odometryNoiseOf knows, the default first.
std::vector<std::string> navigationClasses();

/// The navigation class to assume of `track` when the user states none: "ahrs" when it has at
/// least two fixes and all of them share one north and east (a reader without a horizontal
/// position writes them 0: vehicle_log_navigation.hpp), else the default, "dvl-ahrs". A vehicle
/// that truly stayed put with a measured position is then localized from its heading alone too.
std::string navigationClassOf(const NavTrack& track);

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
  /// (docs/localization.md, issue 42's third round).
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
