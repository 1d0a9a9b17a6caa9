#pragma once
/// @file mcap_writer.hpp
/// Writes a sonar log and its navigation as a ROS 2 log in an MCAP file (mcap.dev/spec, version 0;
/// profile "ros2"), each message CDR-serialized with its ros2msg schema: the beams as
/// `micron_driver_ros/msg/ScanLine` (the ROS 1 driver's message, ros_bag_writer.hpp, with ROS 2's
/// std_msgs/Header: a builtin_interfaces/Time stamp and a frame_id), the fixes as
/// `nav_msgs/msg/Odometry` in ROS's ENU world `odom` and FLU body `base_link` (REP 103). The
/// messages sit in chunks, uncompressed or compressed with zstd or lz4 frames; no summary section
/// (readers that need one, such as `ros2 bag info`, rebuild it: `mcap recover`). readRosBag and
/// readRosBagNavigation read the file back (docs/formats.md, "ROS 2 logs (MCAP)").

#include <string>
#include <vector>

#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// How an MCAP file's chunks are stored (the Chunk record's `compression`).
enum class McapCompression { kNone, kZstd, kLz4 };

/// Options of writeMcap().
struct McapWriteOptions {
  std::string sonar_topic = "/sonar/scan_line";
  std::string nav_topic = "/odometry";
  McapCompression compression = McapCompression::kZstd;
};

/// The bytes of the MCAP file holding `log` and `nav` (may be empty), the two in time order, stamps
/// and log times the beams' and fixes' time_s (seconds since the epoch).
/// @throws ValueError for a beam or fix whose time is negative or not finite, a beam whose bin
///         length is not > 0, a fix with a non-finite value.
std::vector<unsigned char> mcapBytes(const SonarLog& log, const NavTrack& nav = {}, const McapWriteOptions& options = {});

/// Writes mcapBytes to `path` atomically (a temporary file renamed, atomic_file.hpp).
/// @throws as mcapBytes; FileError when the file cannot be written.
void writeMcap(const std::string& path, const SonarLog& log, const NavTrack& nav = {}, const McapWriteOptions& options = {});

}  // namespace sonarmap
