#pragma once
/// @file ros_frames.hpp
/// Private to formats: a ROS pose turned into a NavSample (NED world, forward-right-down body) and
/// back. ROS's convention (REP 103) is ENU with a forward-left-up body; marine stacks publishing NED
/// say so in the frame's name (REP 105's suffix, "_ned"). See ros_bag_navigation.hpp.

#include <string>

#include <Eigen/Geometry>

#include "ros_message.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap::detail {

/// Whether a frame's name says NED: it contains "ned", in any case ("odom_ned", "map_NED").
bool namesNedFrame(const std::string& frame_id);

/// A message's time: its std_msgs/Header stamp (seconds since the epoch), or `record_time_s` (the
/// log's) when it has no header or the stamp is zero. @throws Error for a stamp that is no number.
double headerTime(const RosValue& message, double record_time_s);

/// A frame's name as tf2 compares it: without a leading '/' (tf1's "/base_link" is "base_link").
std::string tfFrame(const std::string& frame_id);

/// The header's frame_id of `message` (tfFrame), or empty.
std::string headerFrame(const RosValue& message);

/// Whether a message's std_msgs/Header frame_id names a NED frame (namesNedFrame).
bool headerNamesNed(const RosValue& message);

/// The fix at `time_s` of a pose given as a position (metres) and a body-to-world quaternion in
/// NED/FRD (`ned`) or ENU/FLU (REP 103). Roll, pitch, yaw are the Z-Y-X angles of navigation.hpp.
/// @throws Error when the quaternion's norm is not within 1 ± 0.1 (a pose left at zero, a NaN).
NavSample rosPoseToNed(double time_s, const Eigen::Vector3d& position_m, const Eigen::Quaterniond& body_to_world, bool ned);

/// A beam's bearing as the Tritech drivers publish it: degrees in [0, 360), clockwise seen from
/// above (beam.hpp's bearing_rad counts the same way, from the same zero).
double clockwiseDegrees(double bearing_rad);

/// Checks what a ROS log writer writes: every beam's time finite and >= 0 s (a stamp) and bin length
/// > 0, every fix's time likewise and its values finite.
/// @throws ValueError naming `writer` and what is wrong.
void checkWritable(const char* writer, const SonarLog& log, const NavTrack& nav);

/// The inverse for ENU/FLU: the fix's position in ENU (metres) and its body-to-ENU rotation.
void nedToRosEnu(const NavSample& fix, Eigen::Vector3d& position_enu_m, Eigen::Quaterniond& flu_to_enu);

}  // namespace sonarmap::detail
