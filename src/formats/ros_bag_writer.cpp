/// @file ros_bag_writer.cpp
/// A sonar log as a ROS 1 bag of micron_driver_ros/ScanLine messages (see ros_bag_writer.hpp).

#include "sonarmap/formats/ros_bag_writer.hpp"

#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <vector>

#include <unistd.h>

#include <rosbag/bag.h>
#include <ros/message_traits.h>
#include <ros/serialization.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"

namespace sonarmap {

const char* const kScanLineDefinition =
    "Header header\n"
    "float32 angle\n"
    "float32 bin_distance_step\n"
    "micron_driver_ros/IntensityBin[] bins\n"
    "\n"
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "uint32 seq\n"
    "time stamp\n"
    "string frame_id\n"
    "\n"
    "================================================================================\n"
    "MSG: micron_driver_ros/IntensityBin\n"
    "float32 distance\n"
    "uint8 intensity\n";

namespace {

/// A message already serialized, with what its connection records (as topic_tools' ShapeShifter
/// hands a message it does not know to rosbag).
struct SerializedMessage {
  std::vector<std::uint8_t> bytes;
};

/// The ScanLine type's MD5 sum as the driver's bags record it (micron_pool_ros1.bag).
constexpr const char* kScanLineMd5 = "6798122952303f12e50da3a7e7eed1f0";

template <class T>
void append(std::vector<std::uint8_t>& out, T value) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(&value);  // ROS 1 and this machine: little-endian
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

/// One beam as a serialized ScanLine (ros_message.hpp's layout).
SerializedMessage scanLine(const Beam& beam, std::uint32_t seq, const ros::Time& stamp) {
  SerializedMessage message;
  std::vector<std::uint8_t>& out = message.bytes;
  append<std::uint32_t>(out, seq);
  append<std::uint32_t>(out, stamp.sec);
  append<std::uint32_t>(out, stamp.nsec);
  append<std::uint32_t>(out, 0);  // frame_id: empty
  double clockwise_deg = std::fmod(360.0 - beam.bearing_rad * 180.0 / std::numbers::pi, 360.0);
  if (clockwise_deg >= 360.0) clockwise_deg -= 360.0;
  append<float>(out, static_cast<float>(clockwise_deg));
  append<float>(out, static_cast<float>(beam.bin_length_m));
  append<std::uint32_t>(out, static_cast<std::uint32_t>(beam.intensities.size()));
  for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
    append<float>(out, static_cast<float>((static_cast<double>(i) + 0.5) * beam.bin_length_m));
    append<std::uint8_t>(out, beam.intensities[i]);
  }
  return message;
}

}  // namespace
}  // namespace sonarmap

namespace ros::message_traits {
template <>
struct MD5Sum<sonarmap::SerializedMessage> {
  static const char* value() { return sonarmap::kScanLineMd5; }
  static const char* value(const sonarmap::SerializedMessage&) { return value(); }
};
template <>
struct DataType<sonarmap::SerializedMessage> {
  static const char* value() { return "micron_driver_ros/ScanLine"; }
  static const char* value(const sonarmap::SerializedMessage&) { return value(); }
};
template <>
struct Definition<sonarmap::SerializedMessage> {
  static const char* value() { return sonarmap::kScanLineDefinition; }
  static const char* value(const sonarmap::SerializedMessage&) { return value(); }
};
}  // namespace ros::message_traits

namespace ros::serialization {
template <>
struct Serializer<sonarmap::SerializedMessage> {
  template <typename Stream>
  static void write(Stream& stream, const sonarmap::SerializedMessage& message) {
    std::memcpy(stream.advance(static_cast<std::uint32_t>(message.bytes.size())), message.bytes.data(), message.bytes.size());
  }
  static std::uint32_t serializedLength(const sonarmap::SerializedMessage& message) {
    return static_cast<std::uint32_t>(message.bytes.size());
  }
};
}  // namespace ros::serialization

namespace sonarmap {

void writeScanLineBag(const std::string& path, const SonarLog& log, const std::string& topic, BagCompression compression) {
  for (const Beam& beam : log.beams) {
    if (!(std::isfinite(beam.time_s) && beam.time_s >= 0.0)) throw ValueError("writeScanLineBag: a beam's time must be finite and >= 0 s");
    if (!(beam.bin_length_m > 0.0) || !std::isfinite(beam.bin_length_m)) throw ValueError("writeScanLineBag: a beam's bin length must be > 0 m");
  }
  // rosbag writes to a path: a scratch file first, its bytes then put in place atomically.
  static std::atomic<unsigned> written{0};
  const std::filesystem::path scratch = std::filesystem::temp_directory_path() /
                                        ("sonarmap-" + std::to_string(::getpid()) + "-" + std::to_string(written++) + ".bag");
  std::vector<unsigned char> bytes;
  try {
    {
      rosbag::Bag bag(scratch.string(), rosbag::bagmode::Write);
      bag.setCompression(compression == BagCompression::kBz2   ? rosbag::compression::BZ2
                         : compression == BagCompression::kLz4 ? rosbag::compression::LZ4
                                                               : rosbag::compression::Uncompressed);
      std::uint32_t seq = 0;
      for (const Beam& beam : log.beams) {
        const ros::Time stamp(beam.time_s);
        bag.write(topic, std::max(stamp, ros::TIME_MIN), scanLine(beam, seq++, stamp));
      }
    }
    std::ifstream in(scratch, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::exception& error) {
    std::filesystem::remove(scratch);
    throw FileError("'" + path + "': cannot write the ROS bag: " + error.what());
  }
  std::filesystem::remove(scratch);
  writeBytesAtomically(path, bytes);
}

}  // namespace sonarmap
