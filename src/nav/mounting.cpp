/// @file mounting.cpp
/// The sonar's mounting from and to the numbers a user types (see mounting.hpp).

#include "sonarmap/nav/mounting.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

}  // namespace

Eigen::Isometry3d sonarToBodyOfMounting(const std::vector<double>& mounting) {
  if (mounting.empty()) return defaultSonarToBody();
  if (mounting.size() != 6 || !std::all_of(mounting.begin(), mounting.end(), [](double v) { return std::isfinite(v); })) {
    throw ValueError("--mounting expects six finite numbers X,Y,Z,ROLL,PITCH,YAW (metres, degrees)");
  }
  NavSample pose;  // the sonar's pose in the body frame, built as a fix's body pose in NED
  pose.position_ned_m = Eigen::Vector3d(mounting[0], mounting[1], mounting[2]);
  pose.roll_rad = mounting[3] * kRadPerDeg;
  pose.pitch_rad = mounting[4] * kRadPerDeg;
  pose.yaw_rad = mounting[5] * kRadPerDeg;
  return bodyToNed(pose);
}

std::array<double, 6> mountingOfPose(const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  const double roll = std::atan2(r(2, 1), r(2, 2));
  const double yaw = std::atan2(r(1, 0), r(0, 0));
  // + 0.0 turns a negative zero into 0.
  return {t.x() + 0.0, t.y() + 0.0, t.z() + 0.0, roll / kRadPerDeg + 0.0, pitch / kRadPerDeg + 0.0, yaw / kRadPerDeg + 0.0};
}

}  // namespace sonarmap
