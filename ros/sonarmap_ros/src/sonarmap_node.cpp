/// @file sonarmap_node.cpp
/// sonarmap_ros_node: the sonar topic of any driver (SonarInput: its definition and bytes) mapped
/// beam by beam by MappingCore and published on octomap_server's topics, with the services ~reset,
/// ~clear_bbx and ~save_map, and the lag on ~queue_delay_s and ~map_lag_s; with ~slam the
/// correction of the poses as TF's map → odom (REP 105). It says (WARN, throttled) what keeps beams
/// out of the map: no pose, no mounting yet, a publisher of another type, lost messages, a jump
/// back in time (a new run). C++17 (the ROS side, mapping_core.hpp's comment). See
/// ros/sonarmap_ros/README.md.

#include <memory>
#include <vector>

#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <std_srvs/Empty.h>
#include <geometry_msgs/TransformStamped.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>

#include "map_publisher.hpp"
#include "mapping_core.hpp"
#include "node_parameters.hpp"
#include "octomap_message.hpp"
#include "pose_input.hpp"
#include "sonar_input.hpp"

namespace sonarmap_ros {
namespace {

class SonarmapNode {
 public:
  SonarmapNode(ros::NodeHandle& node, ros::NodeHandle& private_node)
      : parameters_(readNodeParameters(private_node)),
        core_(parameters_.core,
              [this](const std::string& sonar_frame) { return pose_->sonarInBody(core_.bodyFrame(), sonar_frame); }),
        publisher_(node, parameters_) {
    pose_ = std::make_unique<PoseInput>(
        node, parameters_,
        [this](double time_s, const Eigen::Vector3d& position_m, const Eigen::Quaterniond& orientation,
               const std::string& world, const std::string& body) {
          guarded([&] {
            last_pose_wall_s_ = ros::WallTime::now().toSec();
            if (core_.addPose(time_s, position_m, orientation, world, body)) newRun("a pose");
          });
        });
    sonar_ = std::make_unique<SonarInput>(
        node, parameters_.core.sonar_topic,
        [this](const std::string& publisher, const std::string& type, const std::string& definition,
               const std::vector<std::uint8_t>& bytes, double receipt_s, double receipt_wall_s) {
          guarded([&] { receiveSonar(publisher, type, definition, bytes, receipt_s, receipt_wall_s); });
        });
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

  void receiveSonar(const std::string& publisher, const std::string& type, const std::string& definition,
                    const std::vector<std::uint8_t>& bytes, double receipt_s, double receipt_wall_s) {
    try {
      if (core_.addSonarMessage(type, definition, bytes.data(), bytes.size(), receipt_s, receipt_wall_s)) {
        newRun("a beam");
      }
    } catch (const NotASonarType& error) {
      sonar_->refuse(publisher, type, error.what());
      return;
    }
    last_beam_wall_s_ = ros::WallTime::now().toSec();
    if (first_beam_wall_s_ == 0.0) first_beam_wall_s_ = last_beam_wall_s_;
    committed_ = false;
  }

  /// A beam or a pose stamped before the run's newest time: the core has cleared the map and the
  /// poses; TF's buffer forgets the old run's transforms too (its static ones kept by PoseInput).
  void newRun(const char* what) {
    pose_->clear();
    ROS_WARN("sonarmap: time went back (%s stamped more than %.1f s before the newest time: a bag played again or "
             "a new one): run %zu begins, the map and the poses of the last one cleared",
             what, parameters_.core.jump_back_s, core_.lag().runs);
  }

  /// What keeps the beams out of the map, said at most every 10 s: no pose, no mounting yet.
  void sayWaits(double now_s) {
    if (last_beam_wall_s_ == 0.0 || now_s - last_beam_wall_s_ > parameters_.idle_commit_s) return;
    // poses come at 1 Hz or more: 2 s of beams without one is a missing source, not a pause
    if (parameters_.pose_source != PoseSource::kNone && now_s - first_beam_wall_s_ >= 2.0 &&
        (last_pose_wall_s_ == 0.0 || now_s - last_pose_wall_s_ >= 5.0)) {
      const std::string why = pose_->lastTfError().empty() ? "" : " (TF: " + pose_->lastTfError() + ")";
      ROS_WARN_THROTTLE(10.0, "sonarmap: %zu beams and no pose from %s %s%s: beams are not mapped without one "
                        "(pose_source:=none for a sonar fixed in a tank)", core_.lag().beams + core_.beamsHeld(),
                        pose_->describe().c_str(), last_pose_wall_s_ == 0.0 ? "yet" : "in the last 5 s", why.c_str());
    }
    if (core_.waitingForMounting() && now_s - first_beam_wall_s_ >= 1.0) {  // a /tf_static is often a moment late
      ROS_WARN_THROTTLE(10.0, "sonarmap: %zu beams wait for TF to join the sonar's frame %s to the body's %s (a "
                        "/tf_static): up to %.0f s, then the sonar is taken at the body's origin",
                        core_.beamsHeld(), core_.sonarFrame().c_str(), core_.bodyFrame().c_str(),
                        parameters_.core.mounting_wait_s);
    } else if (core_.mountingMissing() && !mounting_said_) {
      mounting_said_ = true;
      ROS_WARN("sonarmap: no mounting of the sonar's frame '%s' on %s in TF after %.0f s: the sonar is taken at the "
               "body's origin, facing forward", core_.sonarFrame().c_str(), core_.bodyFrame().c_str(),
               parameters_.core.mounting_wait_s);
    }
  }

  void tick() {
    const double now_s = ros::WallTime::now().toSec();
    if (!committed_ && last_beam_wall_s_ > 0.0 && now_s - last_beam_wall_s_ >= parameters_.idle_commit_s) {
      committed_ = true;
      core_.commitAtSilence(now_s - last_pose_wall_s_ >= parameters_.idle_commit_s);
      const LagReport& lag = core_.lag();
      if (parameters_.pose_source != PoseSource::kNone && last_pose_wall_s_ == 0.0) {
        ROS_WARN("sonarmap: no pose from %s in the whole run: its beams are not mapped (pose_source:=none for a "
                 "sonar fixed in a tank)", pose_->describe().c_str());
      }
      // WARN when beams were left out: without navigation, unreadable, lost before the node
      const bool lost = lag.beams_without_nav > 0 || lag.rejected_messages > 0 || sonar_->lost() > 0;
      const char* format = "sonarmap: the sonar is silent: %zu beams, %zu sweeps in the map (%zu beams without "
                           "navigation, %zu messages skipped, %zu lost before the node); largest queue delay %.3f s, "
                           "largest lag of a beam into the map %.3f s";
      if (lost) {
        ROS_WARN(format, lag.beams, lag.sweeps, lag.beams_without_nav, lag.rejected_messages, sonar_->lost(),
                 lag.queue_delay_max_s, lag.map_lag_max_s);
      } else {
        ROS_INFO(format, lag.beams, lag.sweeps, lag.beams_without_nav, lag.rejected_messages, sonar_->lost(),
                 lag.queue_delay_max_s, lag.map_lag_max_s);
      }
      if (parameters_.core.slam) {
        ROS_INFO("sonarmap: slam session %zu: %zu scans, %zu matched to the scans before them", lag.slam_sessions,
                 lag.slam_scans, lag.slam_matched);
      }
    }
    sonar_->poll(now_s);
    pose_->poll(now_s);
    sayWaits(now_s);
    if (now_s - last_report_s_ >= 1.0 && last_beam_wall_s_ > 0.0) {
      last_report_s_ = now_s;
      std_msgs::Float64 value;
      value.data = core_.lag().queue_delay_max_s;
      queue_delay_.publish(value);
      value.data = core_.oldestWait_s(now_s);
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
  std::unique_ptr<SonarInput> sonar_;
  double first_beam_wall_s_ = 0.0, last_beam_wall_s_ = 0.0, last_pose_wall_s_ = 0.0, last_publish_s_ = 0.0, last_report_s_ = 0.0;
  double last_tf_stamp_s_ = -1.0;
  MappingCore::MapToOdom last_tf_;  ///< the last map → odom sent
  tf2_ros::TransformBroadcaster broadcaster_;
  bool committed_ = false, mounting_said_ = false;
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
