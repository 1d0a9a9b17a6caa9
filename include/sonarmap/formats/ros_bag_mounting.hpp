#pragma once
/// @file ros_bag_mounting.hpp
/// The sonar's mounting on the vehicle as a ROS log records it: the static transforms of
/// `/tf_static` (tf2_msgs/TFMessage: geometry_msgs/TransformStamped[] transforms, each the pose of
/// `child_frame_id` in `header.frame_id`, as tf2's static_transform_publisher and
/// robot_state_publisher latch them), chained from the navigation's body frame to the frame the
/// sonar's messages name.
///
/// Frames: ROS's body and sensor frames are forward-left-up (REP 103); the mapper's sonar and body
/// frames are forward-right-down (navigation.hpp). A frame whose name says FRD or NED
/// ("base_link_frd", "sonar_frd") is taken as forward-right-down, any other as FLU and turned by
/// diag(1, −1, −1). The result is the `sonar_to_body` the mapper takes (navigation.hpp): an
/// identity transform between two FLU frames (or two FRD ones) gives defaultSonarToBody(), the
/// identity.

#include <optional>
#include <string>

#include <Eigen/Geometry>

namespace sonarmap {

/// A mounting found in a ROS log.
struct RosBagMounting {
  Eigen::Isometry3d sonar_to_body = Eigen::Isometry3d::Identity();  ///< sonar frame → body FRD
  std::string chain;  ///< the frames joined, for a summary: "base_link -> sonar_mount -> sonar"
};

/// The mounting of the frame `sonar_frame` on `body_frame`, composed from the transforms of every
/// `/tf_static` message of the ROS log at `path` (a transform given twice: the last). nullopt when
/// either frame is empty, the log has no /tf_static topic, or no chain of its transforms joins the
/// two frames (a message that does not decode is skipped).
/// @throws FileError naming the file when it is no readable ROS log.
std::optional<RosBagMounting> readRosBagMounting(const std::string& path, const std::string& sonar_frame,
                                                 const std::string& body_frame);

}  // namespace sonarmap
