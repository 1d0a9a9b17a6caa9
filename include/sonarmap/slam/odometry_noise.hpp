#pragma once
/// @file odometry_noise.hpp
/// How far dead reckoning may be trusted between two poses: the noise model of the odometry edges,
/// the gates and the scans' motion compensation (scan_forming.hpp), in the units of the sensors it
/// stands for (a DVL's velocity, a compass's or gyro's heading), and the classes of navigation
/// sensors a user can name.

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/slam/pose2.hpp"

namespace sonarmap {

/// The number of noise parameters of a measured position (OdometryNoise::covarianceTerms).
inline constexpr std::size_t kOdometryNoiseTerms = 4;

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
  /// 1σ of each coefficient of a magnetic compass's deviation, δ(ψ) = a cos ψ + b sin ψ, radians,
  /// ≥ 0 (0: no heading-dependent error, a gyrocompass or a fibre-optic INS). Common to the whole
  /// log, so the Localizer estimates it (PoseGraph::estimateHeadingDeviation): the heading error
  /// between two poses is δ(ψ₂) − δ(ψ₁), up to twice the amplitude between opposite headings.
  double deviation_sigma_rad = 2.0 * 3.14159265358979323846 / 180.0;
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
  /// The measured-position covariance (known, position_measured) term by term: it is
  /// Σ σ_p² · terms[p] + terms[kOdometryNoiseTerms], σ_p the p-th of kOdometryNoiseParameters and
  /// the last term the floor. Linear in the variances, so a path's covariance composed from them is too.
  std::array<Eigen::Matrix3d, kOdometryNoiseTerms + 1> covarianceTerms(const Pose2& delta, double duration_s) const;
  /// @throws ValueError naming the field when a value is negative, zero where it must be > 0, or
  ///         not finite.
  void validate() const;
};

/// The noise parameters of a measured position, in the order of OdometryNoise::covarianceTerms:
/// scale_sigma, heading_sigma_rad, velocity_noise_mps, gyro_walk_rad_per_sqrt_s.
inline constexpr std::array<double OdometryNoise::*, kOdometryNoiseTerms> kOdometryNoiseParameters{
    &OdometryNoise::scale_sigma, &OdometryNoise::heading_sigma_rad, &OdometryNoise::velocity_noise_mps,
    &OdometryNoise::gyro_walk_rad_per_sqrt_s};

/// The odometry noise of a class of navigation sensors (what a user knows of the vehicle), by name:
/// - "dvl-ahrs" (the default, OdometryNoise{}): a DVL with an AHRS or magnetic compass, drifting a
///   few per cent of the distance travelled (scale 3 %, heading 1.5°, velocity noise 0.05 m/s,
///   gyro walk 0.05°/√s, deviation 2°);
/// - "dvl-ins": a DVL-aided inertial navigation system with a fibre-optic gyro, whose makers
///   state 0.1–0.3 % of the distance travelled (scale 0.3 %, heading 0.2°, velocity noise
///   0.01 m/s, gyro walk 0.01°/√s, no deviation);
/// - "absolute": navigation aided by absolute fixes (USBL, DGPS at the surface) or
///   post-processed, centimetres over the scans' spacing (scale 0.1 %, heading 0.1°, velocity
///   noise 0.005 m/s, gyro walk 0.005°/√s, no deviation);
/// - "ahrs": the heading only, from an AHRS or a magnetic compass without a DVL (a BlueROV2 without
///   one: its flight log's north and east stay 0). OdometryNoise::position_measured is false: the
///   position comes from the scans (Localizer), the heading is the AHRS's (heading 1.5°, gyro walk
///   0.05°/√s, deviation 2°, as dvl-ahrs).
/// These are what the localization starts from, the best the navigation is taken to be: with
/// navigation, the Localizer raises them where the log shows a navigation that drifts more
/// (navigation_calibration.hpp), and measures a compass's deviation where the matches show one.
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

}  // namespace sonarmap
