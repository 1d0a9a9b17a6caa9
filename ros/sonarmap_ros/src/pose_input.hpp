#pragma once
/// @file pose_input.hpp
/// The vehicle's poses from /tf (the transforms odom_frame → base_frame) or a nav_msgs/Odometry
/// topic, each stamped by its header, handed on as ROS gives them (the core turns them into fixes:
/// rosPoseFix, the bag readers' conversion); and the sonar's frame in the body frame from TF (tf2's
/// buffer: /tf_static), as `map RUN.bag` reads the mounting. C++17 (the ROS side).

#include <functional>
#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <nav_msgs/Odometry.h>
#include <ros/node_handle.h>
#include <ros/subscriber.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "node_parameters.hpp"

namespace sonarmap_ros {

class PoseInput {
 public:
  /// Receives each pose: time (s), position (m), body-to-world orientation, world and body frames.
  using PoseSink = std::function<void(double time_s, const Eigen::Vector3d& position_m, const Eigen::Quaterniond& orientation,
                                      const std::string& world_frame, const std::string& body_frame)>;
  /// Subscribes as `parameters.pose_source` says; nothing for PoseSource::kNone.
  PoseInput(ros::NodeHandle& node, const NodeParameters& parameters, PoseSink sink);

  /// The pose of `sonar_frame` in `body_frame` from TF, waiting up to `timeout_s`; nullopt when TF
  /// joins no such frames (said in the log).
  std::optional<Eigen::Isometry3d> sonarInBody(const std::string& body_frame, const std::string& sonar_frame,
                                               double timeout_s) const;

 private:
  void receiveOdometry(const nav_msgs::Odometry::ConstPtr& odometry);
  void receiveTf(const tf2_msgs::TFMessage::ConstPtr& message);

  NodeParameters parameters_;
  PoseSink sink_;
  ros::Subscriber subscriber_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
};

/// tf2's name of a frame: without a leading '/'.
std::string tfName(const std::string& frame);

}  // namespace sonarmap_ros
