#pragma once
/// @file ros2_definitions.hpp
/// Private to formats: the ros2msg definitions of the message types a vehicle's ROS 2 log most
/// often holds, for rosbag2 SQLite logs that store only type names (rosbag2 before ROS 2 Iron,
/// which added the `message_definitions` table). Each is the type's .msg file as its package
/// publishes it (ROS 2 Humble's common_interfaces; CentraleNantesRobotics/ping360_sonar's
/// msg/SonarEcho.msg), without comments, with every type it uses after a rule, as rosbag2 writes
/// definitions: std_msgs/msg/Header, geometry_msgs/msg/{PoseStamped, PoseWithCovarianceStamped,
/// TwistStamped, TwistWithCovarianceStamped}, nav_msgs/msg/Odometry, sensor_msgs/msg/{Imu,
/// FluidPressure}, ping360_sonar_msgs/msg/SonarEcho.

#include <string>

namespace sonarmap::detail {

/// The definition of `type` ("pkg/msg/Name"), or empty when it is not one of the types above.
std::string builtinRos2Definition(const std::string& type);

/// The definition of `type` assembled from the `.msg` files under `msg_path` (the CLI's
/// --msg-path: a folder laid out as a ROS 2 workspace's share folders or a package's source,
/// `PKG/msg/NAME.msg`, or holding `PKG/NAME.msg` or `NAME.msg`): the type's file, then each type it
/// uses (nested ones too, each once) after a rule, as rosbag2 writes definitions; a used type found
/// in no file is taken from the built-in ones above, builtin_interfaces' Time and Duration are
/// builtins. Empty when `msg_path` is empty or holds no file for `type`.
/// @throws Error naming the file when a used type is found nowhere.
std::string msgPathDefinition(const std::string& type, const std::string& msg_path);

}  // namespace sonarmap::detail
