/// @file mcap_writer.cpp
/// A sonar log and its navigation as a ROS 2 MCAP file (see mcap_writer.hpp).

#include "sonarmap/formats/mcap_writer.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <sstream>

#include "mcap_records.hpp"
#include "ros2_definitions.hpp"
#include "ros_frames.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"

namespace sonarmap {
namespace {

using detail::Cdr;

/// The ros2msg schema of micron_driver_ros/ScanLine: its fields, the header's types, IntensityBin.
const std::string kScanLine2 = detail::ros2SchemaWithHeader(
                                   "std_msgs/Header header\nfloat32 angle\nfloat32 bin_distance_step\n"
                                   "micron_driver_ros/IntensityBin[] bins\n") +
                               "================================================================================\n"
                               "MSG: micron_driver_ros/IntensityBin\nfloat32 distance\nuint8 intensity\n";

std::vector<unsigned char> scanLine(const Beam& beam) {
  Cdr out;
  out.header(beam.time_s, "sonar");
  out.put<float>(static_cast<float>(detail::clockwiseDegrees(beam.bearing_rad)));
  out.put<float>(static_cast<float>(beam.bin_length_m));
  out.put<std::uint32_t>(static_cast<std::uint32_t>(beam.intensities.size()));
  for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
    out.put<float>(static_cast<float>((static_cast<double>(i) + 0.5) * beam.bin_length_m));
    out.put<std::uint8_t>(beam.intensities[i]);
  }
  return out.bytes();
}

std::vector<unsigned char> odometry(const NavSample& fix) {
  Cdr out;
  out.header(fix.time_s, "odom");
  out.text("base_link");
  Eigen::Vector3d position;
  Eigen::Quaterniond orientation;
  detail::nedToRosEnu(fix, position, orientation);
  for (const double value : {position.x(), position.y(), position.z(), orientation.x(), orientation.y(), orientation.z(),
                             orientation.w()}) {
    out.put<double>(value);
  }
  for (int i = 0; i < 36 + 6 + 36; ++i) out.put<double>(0.0);  // pose covariance, twist, twist covariance
  return out.bytes();
}

std::uint64_t nanoseconds(double time_s) { return static_cast<std::uint64_t>(std::llround(time_s * 1e9)); }

}  // namespace

std::vector<unsigned char> mcapBytes(const SonarLog& log, const NavTrack& nav, const McapWriteOptions& options) {
  detail::checkWritable("mcapBytes", log, nav);
  std::ostringstream bytes;
  detail::McapRecordWriter file(bytes, options.compression, 1u << 20);
  const std::uint16_t sonar = file.channel(file.schema("micron_driver_ros/msg/ScanLine", kScanLine2), options.sonar_topic);
  std::uint16_t navigation = 0;
  if (!nav.empty()) {
    navigation = file.channel(
        file.schema("nav_msgs/msg/Odometry", detail::builtinRos2Definition("nav_msgs/msg/Odometry")), options.nav_topic);
  }
  // Messages in time order, in chunks of about 1 MiB.
  std::size_t b = 0, f = 0;
  while (b < log.beams.size() || f < nav.size()) {
    const bool beam = f == nav.size() || (b < log.beams.size() && log.beams[b].time_s <= nav[f].time_s);
    const double time_s = beam ? log.beams[b].time_s : nav[f].time_s;
    file.message(beam ? sonar : navigation, nanoseconds(time_s), beam ? scanLine(log.beams[b++]) : odometry(nav[f++]));
  }
  file.finish();
  const std::string text = std::move(bytes).str();
  return {text.begin(), text.end()};
}

void writeMcap(const std::string& path, const SonarLog& log, const NavTrack& nav, const McapWriteOptions& options) {
  writeBytesAtomically(path, mcapBytes(log, nav, options));
}

}  // namespace sonarmap
