#pragma once
/// @file pose_input.hpp
/// The vehicle's poses from TF (odom_frame → base_frame through any chain of frames, tf2's buffer)
/// or a nav_msgs/Odometry topic, each stamped by its header, handed on as ROS gives them (the core
/// turns them into fixes: rosPoseFix, the bag readers' conversion); and the sonar's frame in the
/// body frame from TF (/tf_static, taken whenever it arrives), as `map RUN.bag` reads the mounting.
/// C++17 (the ROS side).

#include <functional>
#include <map>
#include <optional>
#include <set>
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

  /// The pose of `sonar_frame` in `body_frame` from TF's latest transforms, without waiting
  /// (the identity when they are the same frame); nullopt when TF joins no such frames yet.
  std::optional<Eigen::Isometry3d> sonarInBody(const std::string& body_frame, const std::string& sonar_frame) const;
  /// Forgets every transform received (a jump back in time: a new run). The static ones are taken
  /// back by poll() after half of mounting_wait_s for the frames no new /tf_static has named by then
  /// (a robot's static transforms, sent once, stay; a new bag's replace the last bag's).
  void clear();
  /// Each tick of the node (wall seconds): the static transforms kept by clear() taken back when due.
  void poll(double now_wall_s);
  /// What the poses come from, for the log: "TF odom → base_link", "nav_msgs/Odometry on /odom".
  std::string describe() const;
  /// With kTf: why the last lookup of odom → base failed (tf2's error), empty when it succeeded.
  const std::string& lastTfError() const { return tf_error_; }

 private:
  void receiveOdometry(const nav_msgs::Odometry::ConstPtr& odometry);
  void receiveTf(const tf2_msgs::TFMessage::ConstPtr& message);
  void receiveStatic(const tf2_msgs::TFMessage::ConstPtr& message);

  NodeParameters parameters_;
  PoseSink sink_;
  ros::Subscriber subscriber_;
  tf2_ros::Buffer buffer_;
  /// On the node's callback queue (no thread of its own), made before subscriber_: a /tf message is
  /// in the buffer when receiveTf looks the chain up (roscpp calls a topic's callbacks in order).
  tf2_ros::TransformListener listener_;
  ros::Subscriber static_subscriber_;
  std::map<std::string, geometry_msgs::TransformStamped> statics_;  ///< /tf_static's of this run, by child frame
  std::map<std::string, geometry_msgs::TransformStamped> kept_statics_;  ///< the last run's, until poll() takes them back
  double cleared_wall_s_ = 0.0;
  std::set<ros::Time> pending_stamps_;  ///< /tf's stamps not yet looked up (a link of the chain missing there)
  double last_tf_stamp_s_ = -1.0;  ///< the newest pose handed on from TF
  std::string tf_error_;
};

/// tf2's name of a frame: without a leading '/'.
std::string tfName(const std::string& frame);

}  // namespace sonarmap_ros
