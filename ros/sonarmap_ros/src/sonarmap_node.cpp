/// @file sonarmap_node.cpp
/// sonarmap_ros_node: the sonar topic of any driver (topic_tools::ShapeShifter: its definition and
/// bytes) mapped beam by beam by MappingCore and published on octomap_server's topics, with the
/// services ~reset, ~clear_bbx and ~save_map, and the lag on ~queue_delay_s and ~map_lag_s; with ~slam
/// the correction of the poses as TF's map → odom (REP 105). C++17 (the ROS side, mapping_core.hpp's
/// comment). See ros/sonarmap_ros/README.md.

#include <memory>
#include <vector>

#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <std_srvs/Empty.h>
#include <geometry_msgs/TransformStamped.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>
#include <topic_tools/shape_shifter.h>

#include "map_publisher.hpp"
#include "mapping_core.hpp"
#include "node_parameters.hpp"
#include "octomap_message.hpp"
#include "pose_input.hpp"

namespace sonarmap_ros {
namespace {

class SonarmapNode {
 public:
  SonarmapNode(ros::NodeHandle& node, ros::NodeHandle& private_node)
      : parameters_(readNodeParameters(private_node)),
        core_(parameters_.core,
              [this](const std::string& sonar_frame) { return pose_->sonarInBody(core_.bodyFrame(), sonar_frame, 2.0); }),
        publisher_(node, parameters_) {
    pose_ = std::make_unique<PoseInput>(
        node, parameters_,
        [this](double time_s, const Eigen::Vector3d& position_m, const Eigen::Quaterniond& orientation,
               const std::string& world, const std::string& body) {
          guarded([&] {
            last_pose_wall_s_ = ros::WallTime::now().toSec();
            core_.addPose(time_s, position_m, orientation, world, body);
          });
        });
    // A deep queue: a bag played fast delivers bursts while a sweep is integrated.
    sonar_ = node.subscribe(parameters_.core.sonar_topic, 100000, &SonarmapNode::receiveSonar, this);
    queue_delay_ = private_node.advertise<std_msgs::Float64>("queue_delay_s", 10);
    map_lag_ = private_node.advertise<std_msgs::Float64>("map_lag_s", 10);
    reset_ = private_node.advertiseService("reset", &SonarmapNode::reset, this);
    save_ = private_node.advertiseService("save_map", &SonarmapNode::saveMap, this);
    clear_box_ = private_node.advertiseService("clear_bbx", &SonarmapNode::clearBox, this);
    timer_ = node.createWallTimer(ros::WallDuration(0.1), [this](const ros::WallTimerEvent&) { guarded([&] { tick(); }); });
  }

 private:
  template <class F>
  void guarded(F&& body) {
    try {
      body();
    } catch (const std::exception& error) {
      ROS_ERROR_STREAM_THROTTLE(5.0, "sonarmap: " << error.what());
    }
  }

  void receiveSonar(const ros::MessageEvent<const topic_tools::ShapeShifter>& event) {
    guarded([&] {
      const topic_tools::ShapeShifter& shape = *event.getConstMessage();
      const double now_wall_s = ros::WallTime::now().toSec();
      // When roscpp received it (under sim time, now): the queue delay is measured from there.
      const double receipt_wall_s = ros::Time::isSimTime() ? now_wall_s : event.getReceiptTime().toSec();
      bytes_.resize(shape.size());
      ros::serialization::OStream stream(bytes_.data(), static_cast<std::uint32_t>(bytes_.size()));
      shape.write(stream);
      last_beam_wall_s_ = now_wall_s;
      committed_ = false;
      core_.addSonarMessage(shape.getDataType(), shape.getMessageDefinition(), bytes_.data(), bytes_.size(),
                            event.getReceiptTime().toSec(), receipt_wall_s);
    });
  }

  void tick() {
    const double now_s = ros::WallTime::now().toSec();
    if (!committed_ && last_beam_wall_s_ > 0.0 && now_s - last_beam_wall_s_ >= parameters_.idle_commit_s) {
      committed_ = true;
      core_.commitAtSilence(now_s - last_pose_wall_s_ >= parameters_.idle_commit_s);
      const LagReport& lag = core_.lag();
      ROS_INFO("sonarmap: the sonar is silent: %zu beams, %zu sweeps in the map (%zu beams without navigation, %zu "
               "messages skipped); largest queue delay %.3f s, largest lag of a beam into the map %.3f s",
               lag.beams, lag.sweeps, lag.beams_without_nav, lag.rejected_messages, lag.queue_delay_max_s, lag.map_lag_max_s);
      if (parameters_.core.slam) {
        ROS_INFO("sonarmap: slam session %zu: %zu scans, %zu matched to the scans before them", lag.slam_sessions,
                 lag.slam_scans, lag.slam_matched);
      }
    }
    if (now_s - last_report_s_ >= 1.0 && core_.lag().beams > 0) {
      last_report_s_ = now_s;
      std_msgs::Float64 value;
      value.data = core_.lag().queue_delay_max_s;
      queue_delay_.publish(value);
      value.data = core_.lag().last_map_lag_s;
      map_lag_.publish(value);
    }
    if (core_.changed() && now_s - last_publish_s_ >= parameters_.publish_period_s) publish(now_s);
    publishMapToOdom();
  }

  /// map → odom at each newer pose, and when the correction changes without one (the session's
  /// final optimisation after the last pose): then 1 ms after the last stamp, as tf2's buffers keep
  /// one transform per stamp and refuse a second.
  void publishMapToOdom() {
    const std::optional<MappingCore::MapToOdom> correction = core_.mapToOdom();
    if (!correction) return;
    const bool newer = correction->stamp_s > last_tf_stamp_s_;
    if (!newer && correction->transform.isApprox(last_tf_.transform)) return;
    last_tf_stamp_s_ = newer ? correction->stamp_s : last_tf_stamp_s_ + 1e-3;
    last_tf_ = *correction;
    geometry_msgs::TransformStamped message;
    message.header.stamp = ros::Time(last_tf_stamp_s_);
    message.header.frame_id = tfName(parameters_.core.frame_id);
    message.child_frame_id = tfName(correction->odom_frame);
    const Eigen::Vector3d& t = correction->transform.translation();
    const Eigen::Quaterniond q(correction->transform.linear());
    message.transform.translation.x = t.x();
    message.transform.translation.y = t.y();
    message.transform.translation.z = t.z();
    message.transform.rotation.x = q.x();
    message.transform.rotation.y = q.y();
    message.transform.rotation.z = q.z();
    message.transform.rotation.w = q.w();
    broadcaster_.sendTransform(message);
  }

  void publish(double now_s) {
    last_publish_s_ = now_s;
    if (const std::optional<MapData> map = core_.snapshot()) publisher_.publish(*map);
  }

  bool reset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    guarded([&] {
      core_.reset();
      publish(ros::WallTime::now().toSec());
      ROS_INFO("sonarmap: map reset");
    });
    return true;
  }

  bool clearBox(BoundingBoxQueryRequest& request, BoundingBoxQueryResponse&) {
    guarded([&] {
      const Eigen::Vector3d lo(request.min.x, request.min.y, request.min.z), hi(request.max.x, request.max.y, request.max.z);
      if (core_.clearBox(lo, hi)) publish(ros::WallTime::now().toSec());
    });
    return true;
  }

  bool saveMap(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
    try {
      core_.save(parameters_.save_path);
      response.success = true;
      response.message = parameters_.save_path;
    } catch (const std::exception& error) {
      response.success = false;
      response.message = error.what();
    }
    return true;
  }

  NodeParameters parameters_;
  std::unique_ptr<PoseInput> pose_;  ///< made after core_, which asks it for the mounting
  MappingCore core_;
  MapPublisher publisher_;
  std::vector<std::uint8_t> bytes_;
  double last_beam_wall_s_ = 0.0, last_pose_wall_s_ = 0.0, last_publish_s_ = 0.0, last_report_s_ = 0.0;
  double last_tf_stamp_s_ = -1.0;
  MappingCore::MapToOdom last_tf_;  ///< the last map → odom sent
  tf2_ros::TransformBroadcaster broadcaster_;
  bool committed_ = false;
  ros::Subscriber sonar_;
  ros::Publisher queue_delay_, map_lag_;
  ros::ServiceServer reset_, save_, clear_box_;
  ros::WallTimer timer_;
};

}  // namespace
}  // namespace sonarmap_ros

int main(int argc, char** argv) {
  ros::init(argc, argv, "sonarmap");
  ros::NodeHandle node, private_node("~");
  try {
    sonarmap_ros::SonarmapNode mapper(node, private_node);
    ros::spin();
  } catch (const std::exception& error) {
    ROS_FATAL_STREAM("sonarmap: " << error.what());
    return 1;
  }
  return 0;
}
