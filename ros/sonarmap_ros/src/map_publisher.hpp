#pragma once
/// @file map_publisher.hpp
/// The map on octomap_server's topics, latched unless ~latch is false (OctoMap/octomap_mapping's
/// OctomapServer.cpp names): octomap_binary and octomap_full (octomap_msgs/Octomap:
/// octomap_message.hpp), occupied_cells_vis_array and, with ~publish_free_space,
/// free_cells_vis_array (MarkerArray: a CUBE_LIST per leaf size), octomap_point_cloud_centers
/// (PointCloud2 of the occupied leaves' centres) and projected_map (OccupancyGrid: the slice at the
/// vehicle's height); and octomap_server's services octomap_binary and octomap_full
/// (octomap_msgs/GetOctomap, which octomap_saver calls), answering the map last published. C++17 (the
/// ROS side): the data comes from MappingCore::snapshot().

#include <optional>
#include <string>

#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/service_server.h>

#include "mapping_core.hpp"
#include "node_parameters.hpp"
#include "octomap_message.hpp"

namespace sonarmap_ros {

class MapPublisher {
 public:
  /// Advertises the topics and services on `node` (the public namespace, as octomap_server does).
  MapPublisher(ros::NodeHandle& node, const NodeParameters& parameters);
  MapPublisher(const MapPublisher&) = delete;  // the services call back into this object
  MapPublisher& operator=(const MapPublisher&) = delete;
  /// Publishes `map`; unlatched, only on the topics that have a subscriber (as octomap_server).
  void publish(const MapData& map);

 private:
  /// GetOctomap: the map last published (binary or full); false before the first.
  bool answer(const std::optional<OctomapMessage>& map, GetOctomapResponse& response) const;

  std::string frame_id_;
  bool latch_ = true, free_space_ = false;
  MarkerColor color_, color_free_;
  ros::Publisher binary_, full_, markers_, free_markers_, cloud_, projected_;
  ros::ServiceServer binary_service_, full_service_;
  std::optional<OctomapMessage> last_binary_, last_full_;
  std::size_t marker_ids_ = 0, free_marker_ids_ = 0;  ///< markers published last (deleted when they empty)
};

}  // namespace sonarmap_ros
