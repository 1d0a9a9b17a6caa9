/// @file pose_input.cpp
/// The vehicle's poses and the sonar's frame from TF (pose_input.hpp).

#include "pose_input.hpp"

#include <ros/console.h>

namespace sonarmap_ros {

std::string tfName(const std::string& frame) { return !frame.empty() && frame.front() == '/' ? frame.substr(1) : frame; }

PoseInput::PoseInput(ros::NodeHandle& node, const NodeParameters& parameters, PoseSink sink)
    : parameters_(parameters), sink_(std::move(sink)), listener_(buffer_, node, false) {
  if (parameters.pose_source == PoseSource::kOdometry) {
    subscriber_ = node.subscribe(parameters.odom_topic, 10000, &PoseInput::receiveOdometry, this);
  } else if (parameters.pose_source == PoseSource::kTf) {
    subscriber_ = node.subscribe("/tf", 10000, &PoseInput::receiveTf, this);
  }
  static_subscriber_ = node.subscribe("/tf_static", 100, &PoseInput::receiveStatic, this);
}

void PoseInput::receiveStatic(const tf2_msgs::TFMessage::ConstPtr& message) {
  for (const geometry_msgs::TransformStamped& transform : message->transforms) statics_[tfName(transform.child_frame_id)] = transform;
}

std::string PoseInput::describe() const {
  if (parameters_.pose_source == PoseSource::kOdometry) return "nav_msgs/Odometry on " + parameters_.odom_topic;
  return "TF " + tfName(parameters_.odom_frame) + " -> " + tfName(parameters_.base_frame);  // ASCII: rosconsole's locale
}

void PoseInput::receiveOdometry(const nav_msgs::Odometry::ConstPtr& odometry) {
  const auto& p = odometry->pose.pose.position;
  const auto& q = odometry->pose.pose.orientation;
  const std::string body = odometry->child_frame_id.empty() ? parameters_.base_frame : odometry->child_frame_id;
  sink_(odometry->header.stamp.toSec(), Eigen::Vector3d(p.x, p.y, p.z), Eigen::Quaterniond(q.w, q.x, q.y, q.z),
        tfName(odometry->header.frame_id), tfName(body));
}

void PoseInput::receiveTf(const tf2_msgs::TFMessage::ConstPtr& message) {
  // odom → base through any chain (REP 105's odom → base_footprint → base_link as well as a direct
  // transform), looked up at each stamp /tf brings once TF holds every link there: a chain whose
  // static link comes late gets its poses from tf2's history (its cache: 10 s).
  for (const geometry_msgs::TransformStamped& transform : message->transforms) {
    if (transform.header.stamp.toSec() > last_tf_stamp_s_) pending_stamps_.insert(transform.header.stamp);
  }
  const std::string odom = tfName(parameters_.odom_frame), base = tfName(parameters_.base_frame);
  while (!pending_stamps_.empty()) {
    const ros::Time stamp = *pending_stamps_.begin();
    geometry_msgs::TransformStamped found;
    try {
      // tf2 reads time 0 as "the latest": a pose stamped 0 (a bag from 0 s) is looked up 1 ns later
      found = buffer_.lookupTransform(odom, base, stamp.isZero() ? ros::Time(0, 1) : stamp);
    } catch (const tf2::TransformException& error) {
      tf_error_ = error.what();
      // not there yet: kept while tf2 keeps that time, the newest stamp minus its cache
      const ros::Time newest = *pending_stamps_.rbegin();
      const ros::Duration kept = std::min(buffer_.getCacheLength(), ros::Duration(newest.toSec()));
      pending_stamps_.erase(pending_stamps_.begin(), pending_stamps_.lower_bound(newest - kept));
      return;
    }
    tf_error_.clear();
    pending_stamps_.erase(pending_stamps_.begin());
    last_tf_stamp_s_ = stamp.toSec();
    const auto& t = found.transform.translation;
    const auto& q = found.transform.rotation;
    sink_(stamp.toSec(), Eigen::Vector3d(t.x, t.y, t.z), Eigen::Quaterniond(q.w, q.x, q.y, q.z), odom, base);
  }
}

void PoseInput::clear() {
  buffer_.clear();
  pending_stamps_.clear();
  // A new bag sends its own /tf_static as it starts, on another connection than its first beams:
  // the last run's are taken back only if none came for their frames in half the mounting's wait.
  for (const auto& entry : statics_) kept_statics_[entry.first] = entry.second;
  statics_.clear();
  cleared_wall_s_ = ros::WallTime::now().toSec();
}

void PoseInput::poll(double now_wall_s) {
  if (kept_statics_.empty() || now_wall_s - cleared_wall_s_ < 0.5 * parameters_.core.mounting_wait_s) return;
  for (const auto& entry : kept_statics_) {
    if (statics_.count(entry.first) != 0) continue;
    buffer_.setTransform(entry.second, "sonarmap", true);
    statics_[entry.first] = entry.second;
  }
  kept_statics_.clear();
  last_tf_stamp_s_ = -1.0;
}

std::optional<Eigen::Isometry3d> PoseInput::sonarInBody(const std::string& body_frame, const std::string& sonar_frame) const {
  const std::string body = tfName(body_frame), sonar = tfName(sonar_frame);
  if (sonar.empty() || body.empty()) return std::nullopt;
  if (sonar == body) return Eigen::Isometry3d::Identity();
  try {
    const geometry_msgs::TransformStamped found = buffer_.lookupTransform(body, sonar, ros::Time(0));
    const auto& t = found.transform.translation;
    const auto& q = found.transform.rotation;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
    pose.translation() = Eigen::Vector3d(t.x, t.y, t.z);
    return pose;
  } catch (const tf2::TransformException&) {
    return std::nullopt;
  }
}

}  // namespace sonarmap_ros
