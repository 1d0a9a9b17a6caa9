#pragma once
/// @file map_publisher.hpp
/// The map on octomap_server's topics, latched (OctoMap/octomap_mapping's OctomapServer.cpp names):
/// octomap_binary and octomap_full (octomap_msgs/Octomap: octomap_message.hpp),
/// occupied_cells_vis_array (MarkerArray: a CUBE_LIST per leaf size), octomap_point_cloud_centers
/// (PointCloud2 of the occupied leaves' centres) and projected_map (OccupancyGrid: the slice at the
/// vehicle's height). C++17 (the ROS side): the data comes from MappingCore::snapshot().

#include <string>

#include <ros/node_handle.h>
#include <ros/publisher.h>

#include "mapping_core.hpp"

namespace sonarmap_ros {

class MapPublisher {
 public:
  MapPublisher(ros::NodeHandle& node, std::string frame_id);
  void publish(const MapData& map);

 private:
  std::string frame_id_;
  ros::Publisher binary_, full_, markers_, cloud_, projected_;
  std::size_t marker_ids_ = 0;  ///< markers published last (deleted when they empty)
};

}  // namespace sonarmap_ros
