#pragma once
/// @file mcap_file.hpp
/// Private to formats: an MCAP file (ROS 2's default bag storage since Iron, and rosbag2's
/// `--storage mcap`) read record by record from its published specification (mcap.dev/spec,
/// version 0): the magic, then records of a uint8 opcode, a uint64 length and their content; the
/// Schema, Channel and Message records, and Chunks holding them, uncompressed or compressed with
/// zstd (Debian's libzstd) or lz4 frames (Debian's liblz4). Every length is checked against what
/// holds it before anything is read or allocated. The summary section after DataEnd repeats what
/// the data section holds and is not read.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace sonarmap::detail {

/// Largest uncompressed chunk accepted, bytes (rosbag2 writes chunks of 768 KiB by default).
inline constexpr std::uint64_t kMaxMcapChunk = 256ull << 20;

/// The MCAP magic that opens (and closes) every file: 0x89 "MCAP0\r\n".
bool startsLikeMcap(const std::string& path);

class McapFile {
 public:
  struct Schema {
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t schema_id = 0;
    std::string topic, message_encoding;
    std::size_t messages = 0;
    double first_s = 0.0, last_s = 0.0;  ///< log times of its first and last message, seconds
  };

  /// Reads the file's schemas and channels and counts each channel's messages.
  /// @throws FileError naming the file and the byte for anything that does not fit, an unknown
  ///         compression, a chunk that does not decompress to its declared size.
  explicit McapFile(const std::string& path);

  const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }

  /// Calls `use(data, log_time_s)` for every message of the channels in `ids`, in log-time order
  /// (stable: file order at equal times).
  void forEachMessage(const std::vector<std::uint16_t>& ids,
                      const std::function<void(const std::vector<std::uint8_t>&, double)>& use) const;

 private:
  /// What walkRecords hands on: each Schema, Channel and Message record's fields.
  struct Visitor {
    std::function<void(std::uint16_t, Schema)> schema;
    std::function<void(std::uint16_t, Channel)> channel;
    std::function<void(std::uint16_t, std::uint64_t, std::vector<std::uint8_t>)> message;  ///< channel, log time (ns), data
  };
  /// Walks every record of the data section, and those inside each chunk.
  void walkRecords(const Visitor& visit) const;

  std::string path_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
};

}  // namespace sonarmap::detail
