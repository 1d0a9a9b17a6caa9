#pragma once
/// @file dead_reckoning.hpp
/// What a vehicle believes its track is when it navigates by dead reckoning: a Doppler velocity
/// log (DVL) measures its velocity over ground in the body frame, a compass or gyro its heading, and
/// the navigation integrates the one rotated by the other. The simulator's true track (the ground
/// truth) turned into such a believed track, for studies of mapping and SLAM under navigation
/// drift.
///
/// Error model (per interval k between the true fixes k and k + 1, dt = t_{k+1} − t_k):
///  - Heading: yaw_believed(t_k) = yaw_true(t_k) + heading_bias_rad + w_k, with w_0 = 0 and
///    w_{k+1} = w_k + N(0, gyro_walk² · dt) (angle random walk).
///  - Velocity: the true horizontal velocity in the body frame (forward, starboard) over the
///    interval, v_b = R(−ψ_true)·(p_{k+1} − p_k)/dt, ψ_true the true yaw at the interval's
///    midpoint (the mean of its ends' yaws, taken the shorter way round), is measured as
///    (1 + dvl_scale_error) · v_b + n, n ~ N(0, dvl_noise²) on each component.
///  - Position: p_believed(k+1) = p_believed(k) + R(ψ_believed) · v_measured · dt, ψ_believed the
///    believed yaw at the interval's midpoint (ψ_true + bias + (w_k + w_{k+1}) / 2).
///  - Depth (z), roll and pitch are the truth's: a pressure sensor and an AHRS measure them
///    directly, without drift. Times are the truth's.
/// The believed track starts at the truth's first position (the vehicle starts from a known fix).
///
/// Drift this gives on a straight track of length L: a scale error e puts the end e · L too far
/// along track (0.02: 2 m on 100 m); a heading bias b puts it L · sin b across track (1°: 1.75 m
/// on 100 m, 1.7 %); velocity noise σ on fixes dt apart gives a random walk of σ · dt · √N on each
/// axis after N fixes; a gyro walk q gives a heading error of q · √t after t seconds, and so a
/// cross-track error growing as t^{3/2}.
///
/// Randomness: std::mt19937_64 seeded with splitmix64(seed ⊕ 0x6a09e667f3bcc909) (a stream of its
/// own, so that the sonar simulator's draws with the same seed do not change), Gaussian draws by
/// Box–Muller from its uniform draws (no std::*_distribution: a seed gives the same track with any
/// standard library, up to the last bit of libm's log, cos and sin). Three draws per interval, in
/// this order: the heading walk's increment, the forward, the starboard velocity noise; they are
/// drawn whatever options are zero, so that the noise of one error does not depend on the others.

#include <cstdint>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// Errors of the dead-reckoning sensors (see the file's comment); all zero: a perfect navigation.
struct DeadReckoningOptions {
  /// σ of the white noise on each body-frame horizontal velocity component (forward, starboard),
  /// drawn once per interval between fixes, metres per second, ≥ 0.
  double dvl_noise_mps = 0.0;
  /// Fractional scale error of the DVL's velocity (0.02: it reads 2 % fast), > −1.
  double dvl_scale_error = 0.0;
  /// Constant compass / gyro heading bias, radians (positive: the believed heading is clockwise of
  /// the true one seen from above).
  double heading_bias_rad = 0.0;
  /// Heading random walk (angle random walk), radians per √second, ≥ 0.
  double gyro_walk_rad_per_sqrt_s = 0.0;
  std::uint64_t seed = 1;  ///< seed of the noise draws (see the file's comment)

  /// Whether any error is set (a non-zero noise, scale error, bias or walk).
  bool any() const;
  /// @throws ValueError naming the field when a value is not finite or out of its range.
  void validate() const;
};

/// The track a dead-reckoning navigation with `options`' errors believes the vehicle flew when it
/// flew `truth` (see the file's comment): the same times, depths, rolls and pitches; the first fix
/// at the truth's first position; positions and yaws drifting. With no error set (any() false)
/// the result is `truth` itself, bit for bit.
/// Cost: O(fixes).
/// @throws ValueError for invalid options (DeadReckoningOptions::validate), or a track holding a
///         non-finite value or times that are not strictly increasing. An empty track gives an
///         empty track.
NavTrack deadReckon(const NavTrack& truth, const DeadReckoningOptions& options);

}  // namespace sonarmap
