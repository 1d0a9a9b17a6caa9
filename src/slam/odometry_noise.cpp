/// @file odometry_noise.cpp
/// OdometryNoise (odometry_noise.hpp): the covariance of dead reckoning's relative motion and the
/// navigation classes.

#include "sonarmap/slam/odometry_noise.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

void requireNonNegative(double value, const char* name) {
  if (!(std::isfinite(value) && value >= 0.0)) throw ValueError(std::string("odometry noise: ") + name + " must be ≥ 0");
}
void requirePositive(double value, const char* name) {
  if (!(std::isfinite(value) && value > 0.0)) throw ValueError(std::string("odometry noise: ") + name + " must be > 0");
}

}  // namespace

std::array<Eigen::Matrix3d, kOdometryNoiseTerms + 1> OdometryNoise::covarianceTerms(const Pose2& delta, double duration_s) const {
  const double t = std::abs(duration_s);
  const Eigen::Vector2d step = delta.translation();
  const double distance_m = step.norm();
  const Eigen::Vector2d along = distance_m > 1e-9 ? Eigen::Vector2d(step / distance_m) : Eigen::Vector2d::UnitX();
  const Eigen::Vector2d across(-along.y(), along.x());
  std::array<Eigen::Matrix3d, kOdometryNoiseTerms + 1> terms;
  for (Eigen::Matrix3d& term : terms) term.setZero();
  terms[0].topLeftCorner<2, 2>() = along * along.transpose() * distance_m * distance_m;     // scale: along-track, ∝ d²
  terms[1].topLeftCorner<2, 2>() = across * across.transpose() * distance_m * distance_m;   // heading: cross-track, ∝ d²
  terms[2].topLeftCorner<2, 2>() = Eigen::Matrix2d::Identity() * nav_period_s * t;           // white velocity noise integrated
  terms[3](2, 2) = t;                                                                         // heading random walk
  terms[4] = Eigen::Vector3d(1e-6, 1e-6, std::pow(0.01 * 3.14159265358979323846 / 180.0, 2)).asDiagonal();  // floor
  return terms;
}

Eigen::Matrix3d OdometryNoise::covariance(const Pose2& delta, double duration_s, bool known) const {
  const double t = std::abs(duration_s);
  if (known && position_measured) {
    const std::array<Eigen::Matrix3d, kOdometryNoiseTerms + 1> terms = covarianceTerms(delta, duration_s);
    Eigen::Matrix3d covariance = terms[kOdometryNoiseTerms];
    for (std::size_t p = 0; p < kOdometryNoiseTerms; ++p) covariance += std::pow(this->*kOdometryNoiseParameters[p], 2) * terms[p];
    return covariance;
  }
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  const double position_sigma_m = unknown_speed_sigma_mps * t;
  covariance.topLeftCorner<2, 2>() = Eigen::Matrix2d::Identity() * position_sigma_m * position_sigma_m;
  covariance(2, 2) = known ? gyro_walk_rad_per_sqrt_s * gyro_walk_rad_per_sqrt_s * t : std::pow(unknown_turn_sigma_radps * t, 2);
  covariance(0, 0) += 1e-6;
  covariance(1, 1) += 1e-6;
  covariance(2, 2) += std::pow(0.01 * 3.14159265358979323846 / 180.0, 2);
  return covariance;
}

namespace {

/// The classes odometryNoiseOf knows beside the default (scan_forming.hpp states their sources).
struct NavigationClass {
  const char* name;
  double scale_sigma;
  double heading_sigma_deg;
  double velocity_noise_mps;
  double gyro_walk_deg_per_sqrt_s;
  double deviation_sigma_deg;
  bool position_measured = true;
};
constexpr const char* kHeadingOnlyClass = "ahrs";
constexpr NavigationClass kNavigationClasses[] = {{"dvl-ins", 0.003, 0.2, 0.01, 0.01, 0.0},
                                                  {"absolute", 0.001, 0.1, 0.005, 0.005, 0.0},
                                                  {kHeadingOnlyClass, 0.0, 1.5, 0.0, 0.05, 2.0, false}};
constexpr const char* kDefaultNavigationClass = "dvl-ahrs";  // OdometryNoise{}

}  // namespace

OdometryNoise odometryNoiseOf(std::string_view navigation_class) {
  constexpr double kDegree = 3.14159265358979323846 / 180.0;
  OdometryNoise noise;
  if (navigation_class == kDefaultNavigationClass) return noise;
  for (const NavigationClass& known : kNavigationClasses) {
    if (navigation_class != known.name) continue;
    noise.scale_sigma = known.scale_sigma;
    noise.heading_sigma_rad = known.heading_sigma_deg * kDegree;
    noise.velocity_noise_mps = known.velocity_noise_mps;
    noise.gyro_walk_rad_per_sqrt_s = known.gyro_walk_deg_per_sqrt_s * kDegree;
    noise.deviation_sigma_rad = known.deviation_sigma_deg * kDegree;
    noise.position_measured = known.position_measured;
    return noise;
  }
  std::string names;
  for (const std::string& name : navigationClasses()) names += (names.empty() ? "" : ", ") + name;
  throw ValueError("navigation class '" + std::string(navigation_class) + "' is not one of " + names);
}

std::vector<std::string> navigationClasses() {
  std::vector<std::string> names{kDefaultNavigationClass};
  for (const NavigationClass& known : kNavigationClasses) names.emplace_back(known.name);
  return names;
}

std::string navigationClassOf(const NavTrack& track) {
  const bool still = track.size() >= 2 && std::all_of(track.begin(), track.end(), [&](const NavSample& fix) {
                       return fix.position_ned_m.head<2>() == track.front().position_ned_m.head<2>();
                     });
  return std::string(still ? kHeadingOnlyClass : kDefaultNavigationClass);
}

void OdometryNoise::validate() const {
  requireNonNegative(scale_sigma, "scale_sigma");
  requireNonNegative(heading_sigma_rad, "heading_sigma_rad");
  requireNonNegative(velocity_noise_mps, "velocity_noise_mps");
  requirePositive(nav_period_s, "nav_period_s");
  requireNonNegative(gyro_walk_rad_per_sqrt_s, "gyro_walk_rad_per_sqrt_s");
  requireNonNegative(deviation_sigma_rad, "deviation_sigma_rad");
  requirePositive(unknown_speed_sigma_mps, "unknown_speed_sigma_mps");
  requirePositive(unknown_turn_sigma_radps, "unknown_turn_sigma_radps");
  requirePositive(max_speed_mps, "max_speed_mps");
  requirePositive(max_turn_rate_radps, "max_turn_rate_radps");
}

}  // namespace sonarmap
