#pragma once
/// @file mcap_records.hpp
/// Private to src/formats: writing MCAP (mcap.dev/spec, version 0) record by record to a stream,
/// and ROS 2 messages in plain CDR for them. Shared by the batch writer (mcap_writer.hpp) and the
/// recorder of live runs (dive_recorder.hpp), which writes as it goes.

#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "sonarmap/formats/mcap_writer.hpp"

namespace sonarmap::detail {

/// Little-endian bytes of MCAP's fields.
class McapOut {
 public:
  template <class T>
  void put(T value) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);  // MCAP, CDR and this machine: little-endian
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

/// A ROS 2 message in little-endian plain CDR: the encapsulation header 0x00 0x01 0x00 0x00, then
/// each number aligned to its size from the byte after the header.
class Cdr {
 public:
  Cdr() : bytes_{0x00, 0x01, 0x00, 0x00} {}
  template <class T>
  void put(T value) {
    while ((bytes_.size() - 4) % sizeof(T) != 0) bytes_.push_back(0);
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    bytes_.insert(bytes_.end(), bytes, bytes + sizeof(T));
  }
  /// A string: its length counting the terminating NUL, its bytes, the NUL.
  void text(const std::string& s);
  /// A std_msgs/Header: builtin_interfaces/Time (int32 sec, uint32 nanosec) and frame_id.
  void header(std::int32_t sec, std::uint32_t nanosec, const std::string& frame_id);
  /// header() of `time_s` (seconds since the epoch), rounded to the nanosecond.
  void header(double time_s, const std::string& frame_id);
  /// A uint8[] sequence: its length, then its bytes.
  void bytes(const std::vector<std::uint8_t>& values);
  const std::vector<unsigned char>& bytes() const { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
};

/// The ros2msg schema text of a ROS 2 message: its own fields, then the std_msgs/Header and
/// builtin_interfaces/Time it uses after the rules rosbag2 writes.
std::string ros2SchemaWithHeader(const std::string& fields);

/// MCAP records written to `out` in order: the magic and Header, Schemas, Channels, Metadata and
/// Messages (gathered into Chunks of about `chunk_bytes`, compressed with `compression`), then
/// DataEnd, an empty summary and the Footer. Channels and schemas are numbered from 1.
class McapRecordWriter {
 public:
  /// Writes the magic and the Header record (profile "ros2", library "sonarmap").
  /// @throws FileError when `out` fails.
  McapRecordWriter(std::ostream& out, McapCompression compression, std::size_t chunk_bytes);
  /// A Schema record ("ros2msg"), written at once; its id.
  std::uint16_t schema(const std::string& name, const std::string& data);
  /// A Channel record ("cdr"), written at once; its id.
  std::uint16_t channel(std::uint16_t schema_id, const std::string& topic);
  /// A Metadata record (a name and a map of strings), written at once after the current chunk.
  void metadata(const std::string& name, const std::map<std::string, std::string>& values);
  /// A Message record (log and publish time in nanoseconds since the epoch) into the current chunk,
  /// which is written once it reaches chunk_bytes.
  void message(std::uint16_t channel_id, std::uint64_t time_ns, const std::vector<unsigned char>& data);
  /// Writes the current chunk (if any) and flushes `out`.
  /// @throws FileError when `out` fails (a full disk).
  void flush();
  /// Writes the current chunk, DataEnd, the Footer and the closing magic, and flushes.
  void finish();

 private:
  void write(const std::vector<unsigned char>& bytes);
  void writeChunk();

  std::ostream& out_;
  McapCompression compression_;
  std::size_t chunk_bytes_;
  McapOut chunk_;
  std::uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  std::uint32_t sequence_ = 0;
  std::uint16_t schemas_ = 0, channels_ = 0;
};

}  // namespace sonarmap::detail
