#pragma once
/// @file ros_bag_navigation.hpp
/// A ROS 1 bag's topics, and the vehicle's navigation it records, as the NavTrack the mapper and
/// the localizer take (nav/navigation.hpp), so that a bag maps with the navigation recorded beside
/// its sonar (docs/formats.md, "ROS 1 bags").
///
/// A navigation topic is found by its fields' roles: a std_msgs/Header and a pose, either
/// `pose.position` and `pose.orientation` (geometry_msgs/PoseStamped) or `pose.pose.position` and
/// `pose.pose.orientation` (nav_msgs/Odometry, geometry_msgs/PoseWithCovarianceStamped, and any
/// vendor message laid out the same way): a position x, y, z in metres and an orientation
/// quaternion x, y, z, w; or a fix in NED with Euler angles, `north_m`, `east_m`, `down_m`,
/// `roll_rad`, `pitch_rad`, `yaw_rad` (the NavFix of a recorded dive, dive_recorder.hpp), taken as
/// it is. Among several, nav_msgs/Odometry comes first, then the one with most messages.
///
/// Frames. ROS's convention (REP 103) is a world frame x east, y north, z up (ENU) and a body
/// frame x forward, y left, z up (FLU); marine stacks that publish in NED say so in the frame's
/// name (`odom_ned`, `map_ned`: REP 105's suffix convention, as MAVROS and the UUV simulator use
/// it). A pose whose header frame_id contains "ned" is read as NED with a forward-right-down body;
/// any other as ENU with FLU, turned into NED and FRD: north = y, east = x, down = −z, and the body
/// rotation R_ned_frd = A · R_enu_flu · B with A the ENU → NED axis swap and B = diag(1, −1, −1).
/// Times are each message's header stamp (seconds since the epoch), the bag's record time when the
/// stamp is zero.
///
/// A bag without a pose topic is dead-reckoned from the raw sensors it records: an IMU's attitude
/// (sensor_msgs/Imu), a pressure sensor's depth (sensor_msgs/FluidPressure) and a DVL's velocity
/// (TwistStamped, TwistWithCovarianceStamped, or a vendor message with a `velocity` vector); see
/// src/formats/ros_inertial_navigation.hpp.
///
/// Positions on the Earth: a topic of sensor_msgs/NavSatFix (found by its fields: a
/// std_msgs/Header, `status.status`, `latitude`, `longitude`, `altitude`; the one with most
/// messages) gives the fixes' latitudes and longitudes (degrees, WGS84) and altitudes (metres above
/// the ellipsoid, as REP 145 and the message's comments state); a message whose status is
/// STATUS_NO_FIX (−1) is left out, one with a NaN or out-of-range latitude or longitude is skipped
/// and counted with a reason naming the topic and the field.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "sonarmap/nav/geodetic.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// One topic of a bag: its name, message type, message count and the record times of its first and
/// last message (seconds since the epoch; 0 when it has none).
struct RosBagTopic {
  std::string topic;
  std::string type;
  std::size_t messages = 0;
  double first_s = 0.0;
  double last_s = 0.0;
};

/// Every topic of the ROS 1 bag at `path`, in the bag's connection order.
/// @throws FileError naming the file when it is no readable ROS 1 bag (format 2.0).
/// `msg_path`: as RosBagOptions::msg_path.
std::vector<RosBagTopic> listRosBagTopics(const std::string& path, const std::string& msg_path = {});

/// Options of readRosBagNavigation().
struct RosBagNavOptions {
  /// The navigation topic (one holding poses); empty: chosen by its fields' roles (see the file's
  /// comment).
  std::string nav_topic{};
  /// Sea water's density, kg/m³, turning a pressure into a depth (UNESCO's equation of state gives
  /// 1020–1030 at the surface; fresh water: 1000).
  double water_density_kg_m3 = 1025.0;
  /// The pressure at the surface, Pa, a pressure sensor's reading at depth 0 (the standard
  /// atmosphere, 101,325 Pa; a sensor that reads gauge pressure: 0).
  double surface_pressure_pa = 101325.0;
  /// As RosBagOptions::msg_path.
  std::string msg_path{};
};

/// A bag's navigation: the fixes, which topic they came from and how it was read.
struct RosBagNavigation {
  NavTrack track;
  std::string topic;
  std::string type;
  std::string frame;       ///< "NED" or "ENU (REP 103), turned into NED"
  /// The vehicle's body frame the poses are of: the first message's child_frame_id (Odometry),
  /// else "base_link" (REP 105's name), "base_link_frd" for a NED pose.
  std::string body_frame;
  std::size_t skipped = 0;  ///< messages that did not decode or whose time did not increase
  std::vector<std::string> skip_reasons;
  /// The NavSatFix topic's fixes with a fix (see the file's comment), header stamps; empty without one.
  std::vector<GeodeticFix> geodetic_fixes;
  std::string geodetic_topic;  ///< its name; empty without one
  std::size_t geodetic_skipped = 0;  ///< its messages skipped (not decoded, not finite, out of range)
};

/// Reads the navigation of the ROS 1 bag at `path` (see the file's comment), in time order; a
/// message whose time is not after the previous fix's, or that does not decode, is skipped and
/// counted.
/// @return nullopt when `options.nav_topic` is empty and no topic holds a pose or an attitude.
/// @throws FileError naming the file when it is no readable bag, when `options.nav_topic` is not in
///         it or holds no pose, or when no message of the topic gives a fix (a NaN or non-unit
///         quaternion, a non-finite position).
std::optional<RosBagNavigation> readRosBagNavigation(const std::string& path, const RosBagNavOptions& options = {});

}  // namespace sonarmap
