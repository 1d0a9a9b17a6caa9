/// @file map_publisher.cpp
/// The map on octomap_server's topics (map_publisher.hpp).

#include "map_publisher.hpp"

#include <nav_msgs/OccupancyGrid.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <visualization_msgs/MarkerArray.h>

#include "octomap_message.hpp"

namespace sonarmap_ros {

MapPublisher::MapPublisher(ros::NodeHandle& node, std::string frame_id) : frame_id_(std::move(frame_id)) {
  binary_ = node.advertise<OctomapMessage>("octomap_binary", 1, true);
  full_ = node.advertise<OctomapMessage>("octomap_full", 1, true);
  markers_ = node.advertise<visualization_msgs::MarkerArray>("occupied_cells_vis_array", 1, true);
  cloud_ = node.advertise<sensor_msgs::PointCloud2>("octomap_point_cloud_centers", 1, true);
  projected_ = node.advertise<nav_msgs::OccupancyGrid>("projected_map", 1, true);
}

void MapPublisher::publish(const MapData& map) {
  const ros::Time stamp(std::max(map.stamp_s, 0.0));
  OctomapMessage octomap;
  octomap.header.frame_id = frame_id_;
  octomap.header.stamp = stamp;
  octomap.resolution = map.resolution_m;
  octomap.binary = true;
  octomap.data = map.binary_data;
  binary_.publish(octomap);
  octomap.binary = false;
  octomap.data = map.full_data;
  full_.publish(octomap);

  // occupied_cells_vis_array: one CUBE_LIST per leaf size, as octomap_server's (its ids, the sizes)
  visualization_msgs::MarkerArray markers;
  std::size_t cells = 0;
  for (std::size_t i = 0; i < std::max(map.occupied.size(), marker_ids_); ++i) {
    visualization_msgs::Marker marker;
    marker.header.frame_id = frame_id_;
    marker.header.stamp = stamp;
    marker.ns = "map";
    marker.id = static_cast<int>(i);
    marker.type = visualization_msgs::Marker::CUBE_LIST;
    marker.pose.orientation.w = 1.0;
    marker.color.r = 0.2f;
    marker.color.g = 0.4f;
    marker.color.b = 1.0f;
    marker.color.a = 1.0f;
    if (i >= map.occupied.size()) {
      marker.action = visualization_msgs::Marker::DELETE;
    } else {
      const MapData::Cells& level = map.occupied[i];
      marker.action = visualization_msgs::Marker::ADD;
      marker.scale.x = marker.scale.y = marker.scale.z = level.edge_m;
      marker.points.reserve(level.centers.size());
      for (const Eigen::Vector3f& c : level.centers) {
        geometry_msgs::Point p;
        p.x = c.x();
        p.y = c.y();
        p.z = c.z();
        marker.points.push_back(p);
      }
      cells += level.centers.size();
    }
    markers.markers.push_back(marker);
  }
  marker_ids_ = map.occupied.size();
  markers_.publish(markers);

  sensor_msgs::PointCloud2 cloud;
  cloud.header.frame_id = frame_id_;
  cloud.header.stamp = stamp;
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(cells);
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
  for (const MapData::Cells& level : map.occupied) {
    for (const Eigen::Vector3f& c : level.centers) {
      *x = c.x();
      *y = c.y();
      *z = c.z();
      ++x, ++y, ++z;
    }
  }
  cloud_.publish(cloud);

  if (map.grid_width == 0) return;  // the vehicle outside the map
  nav_msgs::OccupancyGrid grid;
  grid.header.frame_id = frame_id_;
  grid.header.stamp = stamp;
  grid.info.map_load_time = stamp;
  grid.info.resolution = static_cast<float>(map.resolution_m);
  grid.info.width = map.grid_width;
  grid.info.height = map.grid_height;
  grid.info.origin.position.x = map.grid_x_m;
  grid.info.origin.position.y = map.grid_y_m;
  grid.info.origin.position.z = map.grid_z_m;
  grid.info.origin.orientation.w = 1.0;
  grid.data = map.grid;
  projected_.publish(grid);
}

}  // namespace sonarmap_ros
