#pragma once
// Test fixtures of the mapping tests: synthetic polar images, sonar poses.
#include <numbers>

#include <Eigen/Geometry>

#include <opencv2/core.hpp>

#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap::testing {

/// A sweep of `beams` beams over a full turn (bearing 2π i / beams, 0.05 s apart), all with `bins`
/// zero bins of `bin_m` metres.
inline PolarImage makeFullTurnSweep(int beams, int bins, double bin_m) {
  PolarImage polar;
  polar.intensities = cv::Mat::zeros(beams, bins, CV_8U);
  polar.valid_bins.assign(static_cast<std::size_t>(beams), bins);
  for (int i = 0; i < beams; ++i) {
    polar.bearing_rad.push_back(2.0 * std::numbers::pi * i / beams);
    polar.time_s.push_back(0.05 * i);
  }
  polar.bin_length_m = bin_m;
  return polar;
}

/// A sonar pose (sonar → map) at `origin_m` with roll, pitch and yaw (radians, Z-Y-X): a tilted,
/// turned sonar. Pitch > 0 turns its x axis down.
inline Eigen::Isometry3d tiltedPose(const Eigen::Vector3d& origin_m, double roll, double pitch, double yaw) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = origin_m;
  return pose;
}

}  // namespace sonarmap::testing
