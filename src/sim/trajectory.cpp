/// @file trajectory.cpp
/// Simple vehicle trajectories (see trajectory.hpp).

#include "sonarmap/sim/trajectory.hpp"

#include <cmath>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

Trajectory staticTrajectory(const NavSample& pose) {
  return [pose](double time_s) {
    NavSample sample = pose;
    sample.time_s = time_s;
    return sample;
  };
}

Trajectory constantVelocityTrajectory(const NavSample& start, const Eigen::Vector3d& velocity_ned_mps,
                                      double yaw_rate_radps) {
  const bool finite = std::isfinite(start.time_s) && start.position_ned_m.allFinite() &&
                      std::isfinite(start.roll_rad) && std::isfinite(start.pitch_rad) && std::isfinite(start.yaw_rad) &&
                      velocity_ned_mps.allFinite() && std::isfinite(yaw_rate_radps);
  if (!finite) throw ValueError("constantVelocityTrajectory: the start pose, velocity and yaw rate must be finite");
  return [start, velocity_ned_mps, yaw_rate_radps](double time_s) {
    const double elapsed_s = time_s - start.time_s;
    NavSample sample = start;
    sample.time_s = time_s;
    sample.position_ned_m += velocity_ned_mps * elapsed_s;
    sample.yaw_rad += yaw_rate_radps * elapsed_s;
    return sample;
  };
}

}  // namespace sonarmap
