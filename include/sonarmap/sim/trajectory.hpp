#pragma once
/// @file trajectory.hpp
/// The simulated vehicle's motion: its navigation fix (pose in NED, navigation.hpp) as a function
/// of time. The simulator asks it for the pose at every beam's time and samples it into the run's
/// NavTrack.

#include <functional>

#include <Eigen/Core>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// Pose of the vehicle at `time_s` (seconds, the log's clock): position in NED (metres) and
/// roll/pitch/yaw (radians, navigation.hpp). The returned time_s is ignored (the caller sets it).
using Trajectory = std::function<NavSample(double time_s)>;

/// A vehicle that does not move: `pose` at every time (default: NED origin, zero attitude, where
/// an upright aligned sonar has the identity pose in the map).
Trajectory staticTrajectory(const NavSample& pose = {});

/// Straight, level-attitude motion: position start.position_ned_m + velocity_ned_mps · (t − start.time_s),
/// roll and pitch of `start`, yaw start.yaw_rad + yaw_rate_radps · (t − start.time_s).
/// @param velocity_ned_mps  velocity in NED, metres per second.
/// @param yaw_rate_radps    turn rate, radians per second (positive turns clockwise seen from above).
/// @throws ValueError when a value is not finite.
Trajectory constantVelocityTrajectory(const NavSample& start, const Eigen::Vector3d& velocity_ned_mps,
                                      double yaw_rate_radps = 0.0);

}  // namespace sonarmap
