#pragma once
/// @file mcap_file.hpp
/// Private to formats: an MCAP file (ROS 2's default bag storage since Iron, and rosbag2's
/// `--storage mcap`) read record by record from its published specification (mcap.dev/spec,
/// version 0): the magic, then records of a uint8 opcode, a uint64 length and their content; the
/// Schema, Channel and Message records, and Chunks holding them, uncompressed or compressed with
/// zstd (Debian's libzstd) or lz4 frames (Debian's liblz4). Every length is checked against what
/// holds it before anything is read or allocated. The summary section after DataEnd repeats what
/// the data section holds and is not read. Messages are read as they are needed (Cursor), one
/// chunk at a time, so that a log of any length is read in the memory of a chunk.

#include <cstdint>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
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

 private:
  class Records;  ///< the data section's records, one at a time (mcap_file.cpp)

 public:
  /// The messages of some channels in log-time order (stable: file order at equal times), read
  /// from the file as they are asked for. It holds the chunk being read and the messages read
  /// ahead of their turn: those that a later part of the file could still precede (none when the
  /// file is in time order, as writers write it). The McapFile must outlive it.
  class Cursor {
   public:
    Cursor(const McapFile& file, std::vector<std::uint16_t> ids);
    ~Cursor();
    Cursor(Cursor&&) noexcept;
    Cursor& operator=(Cursor&&) noexcept;
    /// The next message's data and log time (seconds); false after the last.
    /// @throws FileError as the constructor of McapFile, should the file have changed since.
    bool next(std::vector<std::uint8_t>& data, double& log_time_s);

   private:
    struct Pending {
      std::uint64_t log_time_ns = 0;
      std::uint64_t order = 0;  ///< file order
      std::vector<std::uint8_t> data;
      bool operator>(const Pending& other) const {
        return log_time_ns != other.log_time_ns ? log_time_ns > other.log_time_ns : order > other.order;
      }
    };
    /// Reads the next top-level record (a chunk's messages, or a message); false at the data's end.
    bool readMore();
    void take(std::uint16_t channel, std::uint64_t log_time_ns, std::vector<std::uint8_t> data);

    const McapFile* file_;
    std::vector<std::uint16_t> ids_;
    std::unique_ptr<Records> records_;
    std::vector<Pending> pending_;  ///< a heap, the earliest (time, then file order) at the front
    std::size_t units_ = 0;        ///< units (McapFile::later_min_ns_) begun so far
    std::uint64_t bound_ns_ = 0;   ///< no message not yet read is earlier than this
    std::uint64_t order_ = 0;      ///< messages taken so far
    bool run_open_ = false;        ///< the last record read was a message outside chunks
    std::uint64_t run_last_ns_ = 0;  ///< its log time
    bool ended_ = false;
  };

  /// Calls `use(data, log_time_s)` for every message of the channels in `ids`, in log-time order
  /// (stable: file order at equal times).
  void forEachMessage(const std::vector<std::uint16_t>& ids,
                      const std::function<void(const std::vector<std::uint8_t>&, double)>& use) const;

 private:
  std::string path_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  /// The data section as units in file order, each a chunk or a run of messages outside chunks in
  /// time order: the earliest log time (ns) of any message in unit i or after it, at i (the last:
  /// none, UINT64_MAX). What lets a Cursor hand a message on once nothing later in the file can
  /// come before it.
  std::vector<std::uint64_t> later_min_ns_;
};

}  // namespace sonarmap::detail
