#pragma once
/// @file ros_bag_writer.hpp
/// Writes a sonar log as a ROS 1 bag (format 2.0, through Debian's rosbag_storage), its beams as
/// messages of the micron_driver_ros driver's `micron_driver_ros/ScanLine` (a std_msgs/Header, the
/// bearing `angle` in degrees clockwise seen from above as the Tritech head counts it,
/// `bin_distance_step` in metres, and `IntensityBin[] bins`, each a `distance` in metres and an
/// `intensity`), with the message's definition in its connection, as the driver records them
/// (docs/formats.md, "ROS 1 bags"). readRosBag reads it back.

#include <string>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// The message definition written with each ScanLine connection (as the shared
/// micron_pool_ros1.bag stores it, without its comments).
extern const char* const kScanLineDefinition;

/// How the bag's chunks are stored: as they are, or compressed as `rosbag record --bz2` or `--lz4`
/// does (the ROS wiki's "Bags/Format/2.0", chunk `compression` field).
enum class BagCompression { kNone, kBz2, kLz4 };

/// Writes the beams of `log` to `path` as ScanLine messages on `topic`, in log order, each stamped
/// (header and record) with its time_s in seconds since the epoch (the record's time at least
/// 1 ns: a bag records no time 0), its chunks stored with `compression`. Written to a temporary
/// file and renamed (atomic_file.hpp).
/// @throws FileError when the file cannot be written; ValueError for a beam whose time is negative or
///         not finite, or whose bin length is not > 0.
void writeScanLineBag(const std::string& path, const SonarLog& log, const std::string& topic = "/sonar/scan_line",
                      BagCompression compression = BagCompression::kNone);

}  // namespace sonarmap
