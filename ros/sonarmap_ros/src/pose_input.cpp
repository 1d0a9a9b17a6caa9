/// @file pose_input.cpp
/// The vehicle's poses and the sonar's frame from TF (pose_input.hpp).

#include "pose_input.hpp"

#include <ros/console.h>

namespace sonarmap_ros {

std::string tfName(const std::string& frame) { return !frame.empty() && frame.front() == '/' ? frame.substr(1) : frame; }

PoseInput::PoseInput(ros::NodeHandle& node, const NodeParameters& parameters, PoseSink sink)
    : parameters_(parameters), sink_(std::move(sink)), listener_(buffer_) {
  if (parameters.pose_source == PoseSource::kOdometry) {
    subscriber_ = node.subscribe(parameters.odom_topic, 10000, &PoseInput::receiveOdometry, this);
  } else if (parameters.pose_source == PoseSource::kTf) {
    subscriber_ = node.subscribe("/tf", 10000, &PoseInput::receiveTf, this);
  }
}

void PoseInput::receiveOdometry(const nav_msgs::Odometry::ConstPtr& odometry) {
  const auto& p = odometry->pose.pose.position;
  const auto& q = odometry->pose.pose.orientation;
  const std::string body = odometry->child_frame_id.empty() ? parameters_.base_frame : odometry->child_frame_id;
  sink_(odometry->header.stamp.toSec(), Eigen::Vector3d(p.x, p.y, p.z), Eigen::Quaterniond(q.w, q.x, q.y, q.z),
        tfName(odometry->header.frame_id), tfName(body));
}

void PoseInput::receiveTf(const tf2_msgs::TFMessage::ConstPtr& message) {
  const std::string odom = tfName(parameters_.odom_frame), base = tfName(parameters_.base_frame);
  for (const geometry_msgs::TransformStamped& transform : message->transforms) {
    if (tfName(transform.header.frame_id) != odom || tfName(transform.child_frame_id) != base) continue;
    const auto& t = transform.transform.translation;
    const auto& q = transform.transform.rotation;
    sink_(transform.header.stamp.toSec(), Eigen::Vector3d(t.x, t.y, t.z), Eigen::Quaterniond(q.w, q.x, q.y, q.z), odom, base);
  }
}

std::optional<Eigen::Isometry3d> PoseInput::sonarInBody(const std::string& body_frame, const std::string& sonar_frame,
                                                        double timeout_s) const {
  const std::string body = tfName(body_frame), sonar = tfName(sonar_frame);
  if (sonar.empty() || body.empty()) return std::nullopt;
  if (sonar == body) return Eigen::Isometry3d::Identity();
  try {
    const geometry_msgs::TransformStamped found = buffer_.lookupTransform(body, sonar, ros::Time(0), ros::Duration(timeout_s));
    const auto& t = found.transform.translation;
    const auto& q = found.transform.rotation;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
    pose.translation() = Eigen::Vector3d(t.x, t.y, t.z);
    return pose;
  } catch (const tf2::TransformException& error) {
    ROS_WARN_STREAM("sonarmap: no mounting of " << sonar << " on " << body << " in TF (" << error.what()
                    << "): the sonar taken at the body's origin, facing forward");
    return std::nullopt;
  }
}

}  // namespace sonarmap_ros
