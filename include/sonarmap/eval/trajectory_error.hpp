#pragma once
/// @file trajectory_error.hpp
/// How far an estimated vehicle track (a SLAM result, a dead-reckoning track) is from the true one:
/// the absolute trajectory error (ATE) and the relative pose error (RPE) of Sturm et al. 2012 ("A
/// benchmark for the evaluation of RGB-D SLAM systems", IROS; their evaluate_ate.py and
/// evaluate_rpe.py), with RPE over segments of a given distance travelled as Kümmerle et al. 2009
/// ("On measuring the accuracy of SLAM algorithms", Autonomous Robots 27(4)) and the KITTI
/// odometry benchmark measure it, and the final drift a navigation engineer quotes (% of distance
/// travelled). Positions in NED, metres (navigation.hpp).

#include <cstddef>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// Options of evaluateTrajectory.
struct TrajectoryErrorOptions {
  /// Align the estimate on the truth in SE(3) (rotation about any axis, 3D translation) for the
  /// ATE; false (the default): in SE(2), in the horizontal plane only (rotation about the vertical,
  /// north–east translation), the right alignment when depth is measured directly.
  bool se3 = false;
  /// Distance the truth travels over one RPE segment, metres, > 0.
  double segment_m = 10.0;
};

/// The errors of an estimated track against the truth (see evaluateTrajectory).
struct TrajectoryError {
  std::size_t poses = 0;        ///< estimate fixes within the truth's time span (associated)
  double distance_m = 0.0;      ///< distance the truth travels between the first and last of them, metres
  double ate_rmse_m = 0.0;      ///< RMSE of the position error after the rigid alignment, metres
  double ate_max_m = 0.0;       ///< largest position error after the alignment, metres
  /// RMSE of the position error with the start positions matched instead of a fit, metres: what a
  /// vehicle whose start position is known (a GPS fix at the surface) sees, a heading bias included.
  double ate_start_rmse_m = 0.0;
  std::size_t rpe_segments = 0;  ///< segments of segment_m the RPE is taken over (0: the truth travels less)
  double rpe_rmse_m = 0.0;       ///< RMSE of the segments' relative translation error, metres (NaN: no segment)
  double rpe_yaw_rmse_deg = 0.0;  ///< RMSE of the segments' relative yaw error, degrees (NaN: no segment)
  double final_drift_m = 0.0;     ///< |p_est − p_true| at the last associated fix, without alignment, metres
  double final_drift_pct = 0.0;   ///< final_drift_m in % of distance_m (NaN when the truth does not move)
};

/// Compares `estimate` with `truth`:
///  - Association: each estimate fix with the truth's pose interpolated at its time
///    (interpolateBodyToNed: positions linear, attitude slerp); fixes outside the truth's time span
///    are dropped.
///  - ATE: the estimate's positions rigidly aligned on the truth's by least squares (Umeyama 1991,
///    Eigen::umeyama, no scale): in the horizontal plane (SE(2)), the depth error then added
///    unaligned, or with options.se3 in 3D (SE(3)); the RMSE and the largest of the remaining
///    position errors.
///  - ATE from the start: the estimate shifted, not turned, so that its first associated position
///    coincides with the truth's (north and east, the depth unaligned; with options.se3 the depth
///    too), then the RMSE of the position errors. A heading bias grows with the distance from the
///    start here, where the fitted ATE turns it away.
///  - RPE: for each associated pose i, the first pose j whose truth distance travelled (along the
///    truth's own fixes) is at least segment_m beyond i's; the error of the estimate's relative pose
///    E_i⁻¹·E_j against the truth's T_i⁻¹·T_j, i.e. (T_i⁻¹·T_j)⁻¹·(E_i⁻¹·E_j): the RMSE over the
///    segments of its translation's length and of its yaw (the rotation's angle about the
///    vertical, atan2(R₁₀, R₀₀)). A constant heading bias or offset does not show here; a scale
///    error e gives e · segment_m.
///  - Final drift: the distance between the last associated estimate position and the truth's at
///    that time, unaligned (both tracks are assumed to start at the same place), and its share of
///    the truth's distance travelled.
/// Cost: O(estimate fixes · log(truth fixes) + truth fixes).
/// @throws ValueError when a track is empty, holds a non-finite value or its times do not increase
///         strictly, when segment_m is not > 0, or when fewer than 3 estimate fixes lie within the
///         truth's time span.
TrajectoryError evaluateTrajectory(const NavTrack& estimate, const NavTrack& truth,
                                   const TrajectoryErrorOptions& options = {});

}  // namespace sonarmap
