/// @file map_publisher.cpp
/// The map on octomap_server's topics (map_publisher.hpp).

#include "map_publisher.hpp"

#include <nav_msgs/OccupancyGrid.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <visualization_msgs/MarkerArray.h>

namespace sonarmap_ros {
namespace {

/// A MarkerArray of one CUBE_LIST per leaf size, as octomap_server's occupied_cells_vis_array and
/// free_cells_vis_array (namespace "map", one colour), and a DELETE for each id beyond them up to
/// `ids` (the markers published last), which it then sets to their count.
visualization_msgs::MarkerArray cubeMarkers(const std::vector<MapData::Cells>& levels, const MarkerColor& color,
                                            const std::string& frame_id, const ros::Time& stamp, std::size_t& ids) {
  visualization_msgs::MarkerArray markers;
  for (std::size_t i = 0; i < std::max(levels.size(), ids); ++i) {
    visualization_msgs::Marker marker;
    marker.header.frame_id = frame_id;
    marker.header.stamp = stamp;
    marker.ns = "map";
    marker.id = static_cast<int>(i);
    marker.type = visualization_msgs::Marker::CUBE_LIST;
    marker.pose.orientation.w = 1.0;
    marker.color.r = static_cast<float>(color.r);
    marker.color.g = static_cast<float>(color.g);
    marker.color.b = static_cast<float>(color.b);
    marker.color.a = static_cast<float>(color.a);
    if (i >= levels.size()) {
      marker.action = visualization_msgs::Marker::DELETE;
    } else {
      const MapData::Cells& level = levels[i];
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
    }
    markers.markers.push_back(std::move(marker));
  }
  ids = levels.size();
  return markers;
}

}  // namespace

MapPublisher::MapPublisher(ros::NodeHandle& node, const NodeParameters& parameters)
    : frame_id_(parameters.core.frame_id),
      latch_(parameters.latch),
      free_space_(parameters.publish_free_space),
      color_(parameters.color),
      color_free_(parameters.color_free) {
  binary_ = node.advertise<OctomapMessage>("octomap_binary", 1, latch_);
  full_ = node.advertise<OctomapMessage>("octomap_full", 1, latch_);
  markers_ = node.advertise<visualization_msgs::MarkerArray>("occupied_cells_vis_array", 1, latch_);
  free_markers_ = node.advertise<visualization_msgs::MarkerArray>("free_cells_vis_array", 1, latch_);
  cloud_ = node.advertise<sensor_msgs::PointCloud2>("octomap_point_cloud_centers", 1, latch_);
  projected_ = node.advertise<nav_msgs::OccupancyGrid>("projected_map", 1, latch_);
  binary_service_ = node.advertiseService<GetOctomapRequest, GetOctomapResponse>(
      "octomap_binary", [this](GetOctomapRequest&, GetOctomapResponse& response) { return answer(last_binary_, response); });
  full_service_ = node.advertiseService<GetOctomapRequest, GetOctomapResponse>(
      "octomap_full", [this](GetOctomapRequest&, GetOctomapResponse& response) { return answer(last_full_, response); });
}

bool MapPublisher::answer(const std::optional<OctomapMessage>& map, GetOctomapResponse& response) const {
  if (!map) return false;  // octomap_saver asks again a second later
  response.map = *map;
  return true;
}

void MapPublisher::publish(const MapData& map) {
  // unlatched, a topic without subscribers is skipped (octomap_server's publishAll)
  const auto wanted = [this](const ros::Publisher& topic) { return latch_ || topic.getNumSubscribers() > 0; };
  const ros::Time stamp(std::max(map.stamp_s, 0.0));
  OctomapMessage octomap;
  octomap.header.frame_id = frame_id_;
  octomap.header.stamp = stamp;
  octomap.resolution = map.resolution_m;
  octomap.binary = true;
  octomap.data = map.binary_data;
  last_binary_ = octomap;
  if (wanted(binary_)) binary_.publish(octomap);
  octomap.binary = false;
  octomap.data = map.full_data;
  last_full_ = std::move(octomap);
  if (wanted(full_)) full_.publish(*last_full_);

  if (wanted(markers_)) markers_.publish(cubeMarkers(map.occupied, color_, frame_id_, stamp, marker_ids_));
  if (free_space_ && wanted(free_markers_)) {
    free_markers_.publish(cubeMarkers(map.free, color_free_, frame_id_, stamp, free_marker_ids_));
  }

  if (wanted(cloud_)) {
    std::size_t cells = 0;
    for (const MapData::Cells& level : map.occupied) cells += level.centers.size();
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
  }

  if (map.grid_width == 0 || !wanted(projected_)) return;  // width 0: the vehicle outside the map
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
