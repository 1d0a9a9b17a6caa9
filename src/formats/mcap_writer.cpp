/// @file mcap_writer.cpp
/// A sonar log and its navigation as a ROS 2 MCAP file (see mcap_writer.hpp).

#include "sonarmap/formats/mcap_writer.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>

#include "ros2_definitions.hpp"
#include "ros_frames.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"

namespace sonarmap {
namespace {

constexpr unsigned char kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr const char* kRule = "================================================================================\n";
constexpr const char* kHeader2 = "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n";
constexpr const char* kTime2 = "MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n";

/// The ros2msg schemas written: the type's own fields, then each type it uses after a rule.
const std::string kScanLine2 = std::string("std_msgs/Header header\nfloat32 angle\nfloat32 bin_distance_step\n"
                                           "micron_driver_ros/IntensityBin[] bins\n") +
                               kRule + kHeader2 + kRule + kTime2 + kRule +
                               "MSG: micron_driver_ros/IntensityBin\nfloat32 distance\nuint8 intensity\n";
/// Little-endian bytes, MCAP's fields.
class Out {
 public:
  template <class T>
  void put(T value) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);  // MCAP, CDR here and this machine: little-endian
    bytes_.insert(bytes_.end(), bytes, bytes + sizeof(T));
  }
  void text(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  void raw(const std::vector<unsigned char>& b) { bytes_.insert(bytes_.end(), b.begin(), b.end()); }
  /// A record: opcode, uint64 length, content.
  void record(std::uint8_t opcode, const std::vector<unsigned char>& content) {
    put<std::uint8_t>(opcode);
    put<std::uint64_t>(content.size());
    raw(content);
  }
  std::vector<unsigned char>& bytes() { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
};

/// A CDR message (little-endian plain CDR: the encapsulation header 0x00 0x01, each number aligned
/// to its size from the byte after it).
class Cdr {
 public:
  Cdr() : bytes_{0x00, 0x01, 0x00, 0x00} {}
  template <class T>
  void put(T value) {
    while ((bytes_.size() - 4) % sizeof(T) != 0) bytes_.push_back(0);
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    bytes_.insert(bytes_.end(), bytes, bytes + sizeof(T));
  }
  void text(const std::string& s) {  // the length counts the terminating NUL
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
  }
  void header(double time_s, const std::string& frame_id) {
    const double seconds = std::floor(time_s);
    put<std::int32_t>(static_cast<std::int32_t>(seconds));
    put<std::uint32_t>(static_cast<std::uint32_t>(std::min(999999999.0, std::round((time_s - seconds) * 1e9))));
    text(frame_id);
  }
  const std::vector<unsigned char>& bytes() const { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
};

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

std::vector<unsigned char> compressed(McapCompression compression, const std::vector<unsigned char>& records) {
  if (compression == McapCompression::kZstd) {
    std::vector<unsigned char> out(ZSTD_compressBound(records.size()));
    const std::size_t size = ZSTD_compress(out.data(), out.size(), records.data(), records.size(), 3);
    if (ZSTD_isError(size)) throw FileError("cannot compress an MCAP chunk with zstd");
    out.resize(size);
    return out;
  }
  if (compression == McapCompression::kLz4) {
    std::vector<unsigned char> out(LZ4F_compressFrameBound(records.size(), nullptr));
    const std::size_t size = LZ4F_compressFrame(out.data(), out.size(), records.data(), records.size(), nullptr);
    if (LZ4F_isError(size)) throw FileError("cannot compress an MCAP chunk with lz4");
    out.resize(size);
    return out;
  }
  return records;
}

std::uint64_t nanoseconds(double time_s) { return static_cast<std::uint64_t>(std::llround(time_s * 1e9)); }

}  // namespace

std::vector<unsigned char> mcapBytes(const SonarLog& log, const NavTrack& nav, const McapWriteOptions& options) {
  detail::checkWritable("mcapBytes", log, nav);
  Out file;
  for (const unsigned char c : kMagic) file.put<unsigned char>(c);
  Out header;
  header.text("ros2");
  header.text("sonarmap");
  file.record(0x01, header.bytes());
  // Schemas 1 and 2, channels 1 (sonar) and 2 (navigation), before the chunks that use them.
  auto schema = [&](std::uint16_t id, const std::string& name, const std::string& data) {
    Out s;
    s.put<std::uint16_t>(id);
    s.text(name);
    s.text("ros2msg");
    s.text(data);
    file.record(0x03, s.bytes());
  };
  auto channel = [&](std::uint16_t id, std::uint16_t schema_id, const std::string& topic) {
    Out c;
    c.put<std::uint16_t>(id);
    c.put<std::uint16_t>(schema_id);
    c.text(topic);
    c.text("cdr");
    c.put<std::uint32_t>(0);  // metadata: an empty map
    file.record(0x04, c.bytes());
  };
  schema(1, "micron_driver_ros/msg/ScanLine", kScanLine2);
  channel(1, 1, options.sonar_topic);
  if (!nav.empty()) {
    schema(2, "nav_msgs/msg/Odometry", detail::builtinRos2Definition("nav_msgs/msg/Odometry"));
    channel(2, 2, options.nav_topic);
  }
  // Messages in time order, in chunks of about 1 MiB.
  Out chunk;
  std::uint64_t start_ns = 0, end_ns = 0;
  auto flush = [&] {
    if (chunk.bytes().empty()) return;
    Out c;
    c.put<std::uint64_t>(start_ns);
    c.put<std::uint64_t>(end_ns);
    c.put<std::uint64_t>(chunk.bytes().size());
    c.put<std::uint32_t>(0);  // no CRC
    c.text(options.compression == McapCompression::kZstd ? "zstd" : options.compression == McapCompression::kLz4 ? "lz4" : "");
    const std::vector<unsigned char> packed = compressed(options.compression, chunk.bytes());
    c.put<std::uint64_t>(packed.size());
    c.raw(packed);
    file.record(0x06, c.bytes());
    chunk.bytes().clear();
  };
  std::size_t b = 0, f = 0;
  std::uint32_t sequence = 0;
  while (b < log.beams.size() || f < nav.size()) {
    const bool beam = f == nav.size() || (b < log.beams.size() && log.beams[b].time_s <= nav[f].time_s);
    const double time_s = beam ? log.beams[b].time_s : nav[f].time_s;
    Out m;
    m.put<std::uint16_t>(beam ? 1 : 2);
    m.put<std::uint32_t>(sequence++);
    m.put<std::uint64_t>(nanoseconds(time_s));
    m.put<std::uint64_t>(nanoseconds(time_s));
    m.raw(beam ? scanLine(log.beams[b++]) : odometry(nav[f++]));
    if (chunk.bytes().empty()) start_ns = nanoseconds(time_s);
    end_ns = nanoseconds(time_s);
    chunk.record(0x05, m.bytes());
    if (chunk.bytes().size() > (1u << 20)) flush();
  }
  flush();
  Out data_end;
  data_end.put<std::uint32_t>(0);  // no data section CRC
  file.record(0x0F, data_end.bytes());
  Out footer;
  footer.put<std::uint64_t>(0);  // no summary section
  footer.put<std::uint64_t>(0);
  footer.put<std::uint32_t>(0);
  file.record(0x02, footer.bytes());
  for (const unsigned char c : kMagic) file.put<unsigned char>(c);
  return std::move(file.bytes());
}

void writeMcap(const std::string& path, const SonarLog& log, const NavTrack& nav, const McapWriteOptions& options) {
  writeBytesAtomically(path, mcapBytes(log, nav, options));
}

}  // namespace sonarmap
