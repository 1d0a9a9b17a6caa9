#pragma once
/// @file node_parameters.hpp
/// The node's ROS parameters, all private (~name): octomap_server's names where it has one
/// (frame_id, resolution, sensor_model/*, occupancy_min_z/max_z; OctoMap/octomap_mapping's
/// OctomapServer.cpp) and every mapping option of `sonarmap map` by its Python keyword
/// (mappingOptionNames: `false_alarm`, `volume`). C++17 (the ROS side, mapping_core.hpp's comment).

#include <string>

#include <ros/node_handle.h>

#include "mapping_core.hpp"

namespace sonarmap_ros {

/// Where the vehicle's pose comes from.
enum class PoseSource {
  kNone,      ///< a sonar fixed at the map's origin (a tank, a pool), as `map` without navigation
  kTf,        ///< /tf's transforms odom_frame → base_frame
  kOdometry,  ///< a nav_msgs/Odometry topic (odom_topic)
};

struct NodeParameters {
  CoreParameters core;
  PoseSource pose_source = PoseSource::kTf;
  std::string odom_topic = "odom";       ///< kOdometry
  std::string odom_frame = "odom";       ///< kTf: the world frame of the vehicle's pose
  std::string base_frame = "base_link";  ///< kTf: the body frame (Odometry: its child_frame_id)
  double idle_commit_s = 2.0;            ///< sonar silence (wall seconds) after which the last sweep is committed
  double publish_period_s = 1.0;         ///< least wall time between two publications of the map
  std::string save_path = "map.bt";      ///< ~save_map's file (.bt or .ot)
};

/// Reads the node's parameters from `private_node` (~name).
/// @throws std::runtime_error naming the parameter for a value of the wrong kind or out of range.
NodeParameters readNodeParameters(const ros::NodeHandle& private_node);

}  // namespace sonarmap_ros
