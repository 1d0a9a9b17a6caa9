#pragma once
/// @file point_cloud.hpp
/// Point clouds: 3D points in metres. The frame is stated where a cloud is used (a scan's points
/// are in the sensor frame; a cloud given to insertPointCloud is in the map/world frame).

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sonarmap {

/// Points in metres, N × 3 as a vector of Eigen::Vector3d.
using PointCloud = std::vector<Eigen::Vector3d>;

/// One scan: points in the sensor frame and the sensor's pose in the world (OctoMap's ScanNode).
struct Scan {
  PointCloud points_m;                                         ///< sensor frame, metres
  Eigen::Isometry3d sensor_to_world = Eigen::Isometry3d::Identity();  ///< pose of the sensor
};

}  // namespace sonarmap
