#pragma once
/// @file node_parameters.hpp
/// The node's ROS parameters, all private (~name): octomap_server's names where they mean the same
/// (frame_id, base_frame_id, resolution, sensor_model/miss, min, max and max_range, occupancy_min_z/max_z,
/// latch, publish_free_space, color/*, color_free/*; OctoMap/octomap_mapping's OctomapServer.cpp), a
/// WARN naming each of octomap_server's other parameters given (octomapServerParameters), and every
/// mapping option of `sonarmap map` by its Python keyword (mappingOptionNames: `false_alarm`,
/// `volume`, `hit_probability`). C++17 (the ROS side, mapping_core.hpp's comment).

#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "mapping_core.hpp"

namespace sonarmap_ros {

/// Where the vehicle's pose comes from.
enum class PoseSource {
  kNone,      ///< a sonar fixed at the map's origin (a tank, a pool), as `map` without navigation
  kTf,        ///< /tf's transforms odom_frame → base_frame
  kOdometry,  ///< a nav_msgs/Odometry topic (odom_topic)
};

/// A marker colour, each component in [0, 1] (std_msgs/ColorRGBA).
struct MarkerColor {
  double r = 0.0, g = 0.0, b = 0.0, a = 1.0;
};

/// One of octomap_server's parameters: the names its constructor reads (private_nh.param in
/// OctomapServer.cpp), those its dynamic_reconfigure server reads at start (cfg/OctomapServer.cfg) and
/// octomap_server_node's map_file.
struct OctomapServerParameter {
  const char* name;
  /// Why it does not apply to the node (a WARN says so when it is given); nullptr: the node reads it
  /// with octomap_server's meaning.
  const char* ignored;
  /// A switch given at this value asks for what the node does anyway: no WARN ("false" for filter_ground).
  const char* agrees = nullptr;
};

/// Every one of octomap_server's parameters and what the node does with it.
const std::vector<OctomapServerParameter>& octomapServerParameters();

struct NodeParameters {
  CoreParameters core;
  PoseSource pose_source = PoseSource::kTf;
  std::string odom_topic = "odom";       ///< kOdometry
  std::string odom_frame = "odom";       ///< kTf: the world frame of the vehicle's pose
  std::string base_frame = "base_link";  ///< kTf: the body frame (Odometry: its child_frame_id)
  double idle_commit_s = 2.0;            ///< sonar silence (wall seconds) after which the last sweep is committed
  double publish_period_s = 1.0;         ///< least wall time between two publications of the map
  std::string save_path = "map.bt";      ///< ~save_map's file (.bt or .ot)
  bool latch = true;                     ///< octomap_server's latch: the map's topics latched
  bool publish_free_space = false;       ///< octomap_server's: free_cells_vis_array (core.free_cells)
  MarkerColor color{0.0, 0.0, 1.0, 1.0};       ///< occupied_cells_vis_array's (octomap_server's color/*)
  MarkerColor color_free{0.0, 1.0, 0.0, 1.0};  ///< free_cells_vis_array's (octomap_server's color_free/*)
};

/// Reads the node's parameters from `private_node` (~name); a WARN names each of octomap_server's
/// parameters given that does not apply, and why.
/// @throws std::runtime_error naming the parameter for a value of the wrong kind or out of range.
NodeParameters readNodeParameters(const ros::NodeHandle& private_node);

}  // namespace sonarmap_ros
