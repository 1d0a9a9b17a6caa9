#pragma once
/// @file ros_bag_writer.hpp
/// Writes a sonar log and its navigation as a ROS 1 bag (format 2.0, through Debian's
/// rosbag_storage), its beams as
/// messages of the micron_driver_ros driver's `micron_driver_ros/ScanLine` (a std_msgs/Header, the
/// bearing `angle` in degrees clockwise seen from above as the Tritech head counts it,
/// `bin_distance_step` in metres, and `IntensityBin[] bins`, each a `distance` in metres and an
/// `intensity`), with the message's definition in its connection, as the driver records them
/// (docs/formats.md, "ROS 1 bags"); its navigation as nav_msgs/Odometry in ROS's ENU world frame
/// `odom` with the FLU body `base_link` (REP 103, REP 105). readRosBag and readRosBagNavigation
/// read them back (or in NED, RosBagWriteOptions::nav_frame).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/nav/geodetic.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// The message definition written with each ScanLine connection (as the shared
/// micron_pool_ros1.bag stores it, without its comments).
extern const char* const kScanLineDefinition;

/// How the bag's chunks are stored: as they are, or compressed as `rosbag record --bz2` or `--lz4`
/// does (the ROS wiki's "Bags/Format/2.0", chunk `compression` field).
enum class BagCompression { kNone, kBz2, kLz4 };

/// The definition written with each nav_msgs/Odometry connection (ROS's, without its comments).
extern const char* const kOdometryDefinition;

/// Options of writeRosBag().
struct RosBagWriteOptions {
  std::string sonar_topic = "/sonar/scan_line";
  std::string nav_topic = "/odometry";
  /// The fixes' world frame: ROS's ENU (REP 103) unless the name contains "ned" (the fixes then
  /// written as they are, NED with a forward-right-down body).
  std::string nav_frame = "odom";
  /// Whether the fixes are written as nav_msgs/Odometry on nav_topic.
  bool odometry = true;
  /// Whether the fixes are also written as the raw sensors dead reckoning starts from, ENU and FLU
  /// (REP 103): sensor_msgs/Imu on /imu/data (the orientation), geometry_msgs/TwistStamped on
  /// /dvl/twist (the body velocity to the next fix), sensor_msgs/FluidPressure on /pressure (the
  /// depth's pressure with water_density_kg_m3 and surface_pressure_pa).
  bool raw_sensors = false;
  /// With raw_sensors: whether the DVL's /dvl/twist is written (false: a vehicle without a DVL,
  /// whose raw sensors give the attitude and the depth only).
  bool raw_dvl = true;
  double water_density_kg_m3 = 1025.0;
  double surface_pressure_pa = 101325.0;
  BagCompression compression = BagCompression::kNone;
  /// The sonar's mounting on the vehicle (navigation.hpp's sonar_to_body): written as one static
  /// transform on /tf_static (tf2_msgs/TFMessage) from the body frame ("base_link", FLU; with a
  /// NED nav_frame "base_link_frd") to the sonar messages' frame "sonar" (ros_bag_mounting.hpp).
  std::optional<Eigen::Isometry3d> sonar_to_body{};
  /// Where the fixes' NED zero lies on the Earth: when set, each fix is also written as a
  /// sensor_msgs/NavSatFix on /gps/fix (frame "gps", status STATUS_FIX, service GPS, covariance
  /// unknown), its latitude, longitude and altitude nedToGeodetic(geodetic_origin, position):
  /// a vehicle with a positioning fix at every navigation fix.
  std::optional<GeodeticPoint> geodetic_origin{};
  /// With raw_sensors: the DVL turned by this rotation in the IMU's frame (FLU, as tf records it):
  /// its velocities written in its own frame ("dvl_link") and the rotation on /tf_static
  /// (imu_link -> dvl_link), as a vehicle whose DVL is mounted turned records them.
  std::optional<Eigen::Quaterniond> dvl_rotation_flu{};
};

/// Writes the beams of `log` to `path` as ScanLine messages on `options.sonar_topic` and the fixes
/// of `nav` (may be empty) as Odometry on `options.nav_topic`, the two in time order, each stamped
/// (header and record) with its time in seconds since the epoch (the record's time at least 1 ns:
/// a bag records no time 0), chunks stored with `options.compression`. Written to a temporary file
/// and renamed (atomic_file.hpp).
/// @throws FileError when the file cannot be written; ValueError for a beam or fix whose time is
///         negative or not finite, a beam whose bin length is not > 0, a fix with a non-finite value.
void writeRosBag(const std::string& path, const SonarLog& log, const NavTrack& nav = {},
                 const RosBagWriteOptions& options = {});

/// The bytes writeRosBag writes (to stage them with other outputs, io/atomic_file.hpp).
/// @throws ValueError as writeRosBag; FileError when rosbag_storage cannot write its scratch file.
std::vector<unsigned char> rosBagBytes(const SonarLog& log, const NavTrack& nav = {}, const RosBagWriteOptions& options = {});

}  // namespace sonarmap
