/// @file dead_reckoning.cpp
/// A true track turned into the track a dead-reckoning navigation believes (see dead_reckoning.hpp).

#include "sonarmap/sim/dead_reckoning.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Core>

#include "random.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Mixed into the seed so that the dead reckoning's stream differs from the sonar's of the same seed.
constexpr std::uint64_t kStreamConstant = 0x6a09e667f3bcc909ULL;

/// `angle_rad` wrapped into [−π, π).
double wrapAngle(double angle_rad) { return angle_rad - kTwoPi * std::floor((angle_rad + std::numbers::pi) / kTwoPi); }

/// SplitMix64's output function (Steele, Lea & Flood 2014): a well-mixed 64-bit value of `x`.
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// A horizontal (north, east) vector in the body's (forward, starboard) turned by `yaw_rad` to NED.
Eigen::Vector2d rotated(double yaw_rad, const Eigen::Vector2d& v) {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

void requireValidTrack(const NavTrack& track) {
  if (const std::optional<NavTrackFault> fault = findNavTrackFault(track)) {
    const std::size_t k = fault->index;
    if (fault->kind == NavTrackFault::Kind::kNotFinite) {
      throw ValueError("dead reckoning: fix " + std::to_string(k) + " of the true track holds a non-finite value");
    }
    throw ValueError("dead reckoning: fix " + std::to_string(k) + "'s time is not after the previous fix's");
  }
}

}  // namespace

bool DeadReckoningOptions::any() const {
  return dvl_noise_mps != 0.0 || dvl_scale_error != 0.0 || heading_bias_rad != 0.0 || gyro_walk_rad_per_sqrt_s != 0.0;
}

void DeadReckoningOptions::validate() const {
  if (!(std::isfinite(dvl_noise_mps) && dvl_noise_mps >= 0.0)) {
    throw ValueError("dead reckoning: dvl_noise_mps must be a finite number >= 0, got " + std::to_string(dvl_noise_mps));
  }
  if (!(std::isfinite(dvl_scale_error) && dvl_scale_error > -1.0)) {
    throw ValueError("dead reckoning: dvl_scale_error must be a finite number > -1, got " +
                     std::to_string(dvl_scale_error));
  }
  if (!std::isfinite(heading_bias_rad)) throw ValueError("dead reckoning: heading_bias_rad must be finite");
  if (!(std::isfinite(gyro_walk_rad_per_sqrt_s) && gyro_walk_rad_per_sqrt_s >= 0.0)) {
    throw ValueError("dead reckoning: gyro_walk_rad_per_sqrt_s must be a finite number >= 0, got " +
                     std::to_string(gyro_walk_rad_per_sqrt_s));
  }
}

NavTrack deadReckon(const NavTrack& truth, const DeadReckoningOptions& options) {
  options.validate();
  requireValidTrack(truth);
  if (!options.any() || truth.empty()) return truth;
  sim::Random random(splitmix64(options.seed ^ kStreamConstant));
  NavTrack believed = truth;
  believed.front().yaw_rad = truth.front().yaw_rad + options.heading_bias_rad;
  Eigen::Vector2d position_ne_m = truth.front().position_ned_m.head<2>();
  double walk_rad = 0.0;  // w_k
  for (std::size_t k = 0; k + 1 < truth.size(); ++k) {
    const NavSample& from = truth[k];
    const NavSample& to = truth[k + 1];
    const double dt_s = to.time_s - from.time_s;
    const double next_walk_rad = walk_rad + options.gyro_walk_rad_per_sqrt_s * std::sqrt(dt_s) * random.gaussian();
    const Eigen::Vector2d noise_mps(options.dvl_noise_mps * random.gaussian(), options.dvl_noise_mps * random.gaussian());
    // Midpoint yaws: the truth's, and the believed one (the truth's plus bias and mean walk).
    const double true_yaw_rad = from.yaw_rad + 0.5 * wrapAngle(to.yaw_rad - from.yaw_rad);
    const double error_rad = options.heading_bias_rad + 0.5 * (walk_rad + next_walk_rad);
    // R(ψ_b)·((1 + e)·R(−ψ_t)·d/dt + n)·dt, written as (1 + e)·R(ψ_b − ψ_t)·d + R(ψ_b)·n·dt.
    const Eigen::Vector2d displacement_m = (to.position_ned_m - from.position_ned_m).head<2>();
    position_ne_m += (1.0 + options.dvl_scale_error) * rotated(error_rad, displacement_m) +
                     rotated(true_yaw_rad + error_rad, noise_mps) * dt_s;
    walk_rad = next_walk_rad;
    NavSample& fix = believed[k + 1];
    fix.position_ned_m.head<2>() = position_ne_m;
    fix.yaw_rad = to.yaw_rad + options.heading_bias_rad + walk_rad;
  }
  return believed;
}

}  // namespace sonarmap
