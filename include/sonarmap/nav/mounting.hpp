#pragma once
/// @file mounting.hpp
/// The sonar's mounting on the vehicle as a user types it (`--mounting X,Y,Z,ROLL,PITCH,YAW` of
/// `sonarmap map`, `simulate`, `live` and `eval --heard-by`; the Python module's `mounting=`):
/// the sonar frame's pose in the body frame (both forward-right-down, navigation.hpp), X, Y, Z in
/// metres and ROLL, PITCH, YAW the Z-Y-X Euler angles in degrees. All zeros: upright and aligned
/// (defaultSonarToBody()); a head tilted 25° down is pitch −25 (docs/formats.md, "Frames").

#include <array>
#include <vector>

#include <Eigen/Geometry>

namespace sonarmap {

/// The sonar's mounting (sonar frame → body frame FRD, navigation.hpp) from X, Y, Z in metres and
/// ROLL, PITCH, YAW in degrees (Z-Y-X Euler angles, as a NavSample's attitude); empty: the default
/// mounting, upright and aligned (defaultSonarToBody()).
/// @throws ValueError when the list is neither empty nor six finite numbers.
Eigen::Isometry3d sonarToBodyOfMounting(const std::vector<double>& mounting);

/// The inverse of sonarToBodyOfMounting for any rigid pose (rotation `r`, translation `t`): X, Y, Z
/// in metres, then ROLL, PITCH, YAW in degrees of r = Rz(yaw)·Ry(pitch)·Rx(roll) (pitch in
/// [−90°, 90°]); the numbers of map --mounting and eval --sensor-pose.
std::array<double, 6> mountingOfPose(const Eigen::Matrix3d& r, const Eigen::Vector3d& t);

}  // namespace sonarmap
