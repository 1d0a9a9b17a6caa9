#pragma once
/// @file ros_bag_records.hpp
/// Private to formats: a ROS 1 bag's records read with every length checked against what holds
/// them, for the walk of ros_bag_scan.hpp. Layout: the ROS wiki's "Bags/Format/2.0" (a version
/// line "#ROSBAG V2.0", then records of a uint32 header length, the header's fields as a uint32
/// length and NAME=VALUE each, a uint32 data length and the data; a chunk's data holds connection
/// and message records, bz2- or lz4-compressed or not).

#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <string_view>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {

inline constexpr std::string_view kBagVersionLine = "#ROSBAG V2.0\n";
inline constexpr std::uint8_t kBagMessage = 0x02, kBagHeader = 0x03, kBagIndex = 0x04, kBagChunk = 0x05,
                              kBagChunkInfo = 0x06, kBagConnection = 0x07;
/// Largest uncompressed chunk accepted, bytes: rosbag writes chunks of 768 KiB by default
/// (`rosbag record --chunksize`), and a chunk is held in memory whole.
inline constexpr std::uint64_t kMaxBagChunk = 256ull << 20;

/// What does not fit where: a FileError "'PATH': ROS bag: REASON", its REASON ("byte N: ...") kept
/// apart for a reader that reads around it.
class BagRecordError : public FileError {
 public:
  BagRecordError(const std::string& path, const std::string& reason)
      : FileError("'" + path + "': ROS bag: " + reason), reason_(reason) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

/// Bytes that records are read from: the bag's file, or a chunk's records.
class BagBytes {
 public:
  virtual ~BagBytes() = default;
  virtual std::uint64_t size() const = 0;
  /// `count` bytes from `at`. @throws BagRecordError when they run past the end.
  virtual std::string read(std::uint64_t at, std::uint64_t count) = 0;
  /// @throws BagRecordError naming `at` (and, in a chunk, the chunk) and `what`.
  [[noreturn]] virtual void fail(std::uint64_t at, const std::string& what) const = 0;
};

/// The bag's file, read piece by piece at the offsets the records give.
class BagFile final : public BagBytes {
 public:
  /// @throws FileError when the file cannot be opened.
  explicit BagFile(const std::string& path);
  std::uint64_t size() const override { return size_; }
  std::string read(std::uint64_t at, std::uint64_t count) override;
  [[noreturn]] void fail(std::uint64_t at, const std::string& what) const override;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

/// A chunk's records in memory, uncompressed; failures name the chunk's place in the file.
class ChunkBytes final : public BagBytes {
 public:
  ChunkBytes(const BagFile& bag, std::uint64_t chunk, std::string bytes) : bag_(bag), chunk_(chunk), bytes_(std::move(bytes)) {}
  std::uint64_t size() const override { return bytes_.size(); }
  std::string read(std::uint64_t at, std::uint64_t count) override;
  [[noreturn]] void fail(std::uint64_t at, const std::string& what) const override;
  const std::string& bytes() const { return bytes_; }

 private:
  const BagFile& bag_;
  std::uint64_t chunk_;
  std::string bytes_;
};

/// One record: where it starts, its header's fields, where its data starts and how long it is.
struct BagRecord {
  std::uint64_t at = 0, data = 0, data_length = 0;
  std::map<std::string, std::string> fields;
  std::uint8_t op() const { return static_cast<std::uint8_t>(fields.at("op")[0]); }
  std::uint64_t end() const { return data + data_length; }
};

/// The little-endian number of `bytes`' first 8 bytes (or fewer).
std::uint64_t littleEndian(const std::string& bytes);

/// The NAME=VALUE fields of `header`, each field's length checked against it; `at` names the
/// record in failures.
std::map<std::string, std::string> bagFields(const BagBytes& source, std::uint64_t at, const std::string& header);

/// The record at `at` in `source`: its header's fields (each inside its header, one a one-byte
/// 'op'), its data length, and, unless `data_may_run_past` (a chunk the file ends in), its data
/// inside `source`. A connection record's data, itself a header of fields (the topic, the type,
/// the message definition), is checked as one.
/// @throws BagRecordError for what does not fit.
BagRecord readBagRecord(BagBytes& source, std::uint64_t at, bool data_may_run_past = false);

/// The field `name` of `record`. @throws BagRecordError when it lacks it.
const std::string& bagField(const BagBytes& source, const BagRecord& record, const char* name);
/// The 4- or 8-byte number of field `name`. @throws BagRecordError when it lacks it or another size.
std::uint64_t bagNumber(const BagBytes& source, const BagRecord& record, const char* name);

/// The uncompressed size a chunk declares. @throws BagRecordError above kMaxBagChunk.
std::uint64_t bagChunkSize(const BagBytes& source, const BagRecord& chunk);

/// The records of the whole chunk `chunk` (compression none, bz2 or lz4), uncompressed into its
/// declared size (≤ kMaxBagChunk), as rosbag_storage will read them.
/// @throws BagRecordError for a size beyond the limit, an unknown compression or data that does
///         not decompress into its size.
std::string uncompressedChunk(BagFile& bag, const BagRecord& chunk);

/// What decompresses from the first bytes of a chunk's data, `data` (a chunk the file ends in, or
/// one left unterminated), at most `limit` bytes; `ended` tells whether the compressed stream
/// ended in them. Compression "none" is `data` itself (up to `limit`), ended.
/// @throws BagRecordError for an unknown compression.
std::string decompressAvailable(const BagFile& bag, const BagRecord& chunk, const std::string& data, std::uint64_t limit,
                                bool& ended);

}  // namespace sonarmap::detail
