/// @file ros_bag_check.cpp
/// A ROS 1 bag's records checked against its file (see ros_bag_check.hpp).

#include "ros_bag_check.hpp"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string_view>
#include <vector>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

constexpr std::string_view kVersionLine = "#ROSBAG V2.0\n";
constexpr std::uint8_t kBagHeader = 0x03, kIndexData = 0x04, kChunk = 0x05, kChunkInfo = 0x06, kConnection = 0x07;
/// Largest record header or connection header read to check it, bytes (real ones hold a few
/// fields and a message definition: kilobytes).
constexpr std::uint32_t kMaxHeader = 16u << 20;
/// Bytes of one index entry (format 2.0, index version 1: a uint64 time and a uint32 offset).
constexpr std::uint64_t kIndexEntry = 12;

/// The bag's file, read piece by piece at the offsets the records give.
class BagFile {
 public:
  explicit BagFile(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    std::error_code error;
    size_ = std::filesystem::file_size(path, error);
    if (!in_ || error) throw FileError("'" + path + "': cannot open the ROS bag");
  }
  [[noreturn]] void fail(std::uint64_t at, const std::string& what) const {
    throw FileError("'" + path_ + "': ROS bag: byte " + std::to_string(at) + ": " + what);
  }
  std::uint64_t size() const { return size_; }
  std::string read(std::uint64_t at, std::uint64_t count) {
    if (count > size_ || at > size_ - count) fail(at, std::to_string(count) + " bytes run past the file");
    std::string bytes(count, '\0');
    in_.seekg(static_cast<std::streamoff>(at));
    if (!in_.read(bytes.data(), static_cast<std::streamsize>(count))) fail(at, "cannot read the file");
    return bytes;
  }

 private:
  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

/// A chunk's uncompressed records in memory; failures name the chunk's place in the file.
class ChunkBytes {
 public:
  ChunkBytes(const BagFile& bag, std::uint64_t chunk, std::string bytes)
      : bag_(bag), chunk_(chunk), bytes_(std::move(bytes)) {}
  [[noreturn]] void fail(std::uint64_t at, const std::string& what) const {
    bag_.fail(chunk_, "byte " + std::to_string(at) + " of the chunk's records: " + what);
  }
  std::uint64_t size() const { return bytes_.size(); }
  std::string read(std::uint64_t at, std::uint64_t count) const {
    if (count > bytes_.size() || at > bytes_.size() - count) fail(at, std::to_string(count) + " bytes run past the chunk");
    return bytes_.substr(at, count);
  }

 private:
  const BagFile& bag_;
  std::uint64_t chunk_;
  std::string bytes_;
};

std::uint64_t littleEndian(const std::string& bytes) {
  std::uint64_t value = 0;
  std::memcpy(&value, bytes.data(), std::min<std::size_t>(bytes.size(), 8));  // little-endian, as the bag
  return value;
}

/// One record: where it starts, its header's fields, where its data starts and how long it is.
struct Record {
  std::uint64_t at = 0, data = 0, data_length = 0;
  std::map<std::string, std::string> fields;
};

/// The NAME=VALUE fields of `header`, each field's length checked against it; `at` names the
/// record in failures.
template <class Source>
std::map<std::string, std::string> fieldsOf(const Source& source, std::uint64_t at, const std::string& header) {
  std::map<std::string, std::string> fields;
  for (std::size_t offset = 0; offset < header.size();) {
    if (header.size() - offset < 4) source.fail(at, "a header field's length runs past its header");
    const std::uint64_t length = littleEndian(header.substr(offset, 4));
    if (length > header.size() - offset - 4) source.fail(at, "a header field of " + std::to_string(length) + " bytes runs past its header");
    const std::string_view field(header.data() + offset + 4, length);
    const auto equals = field.find('=');
    if (equals == std::string_view::npos) source.fail(at, "a header field has no '='");
    fields.emplace(field.substr(0, equals), field.substr(equals + 1));
    offset += 4 + length;
  }
  return fields;
}

/// The record starting at `at` in `source` (a BagFile or a ChunkBytes), every length checked
/// against `source`. A connection record's data is itself a header of fields (the topic, the
/// type, the message definition): checked as one.
template <class Source>
Record readRecord(Source& source, std::uint64_t at) {
  Record record;
  record.at = at;
  const std::uint64_t header_length = littleEndian(source.read(at, 4));
  if (header_length > kMaxHeader || header_length > source.size() - at - 4) {
    source.fail(at, "a record header of " + std::to_string(header_length) + " bytes does not fit");
  }
  record.fields = fieldsOf(source, at, source.read(at + 4, header_length));
  const std::uint64_t length_at = at + 4 + header_length;
  record.data_length = littleEndian(source.read(length_at, 4));
  record.data = length_at + 4;
  if (record.data_length > source.size() - record.data) {
    source.fail(at, "record data of " + std::to_string(record.data_length) + " bytes runs past its end");
  }
  const auto op = record.fields.find("op");
  if (op == record.fields.end() || op->second.size() != 1) source.fail(at, "a record has no one-byte 'op' field");
  if (static_cast<std::uint8_t>(op->second[0]) == kConnection) {
    if (record.data_length > kMaxHeader) source.fail(at, "a connection header of " + std::to_string(record.data_length) + " bytes");
    fieldsOf(source, at, source.read(record.data, record.data_length));
  }
  return record;
}

template <class Source>
const std::string& field(const Source& source, const Record& record, const char* name) {
  const auto found = record.fields.find(name);
  if (found == record.fields.end()) source.fail(record.at, std::string("a record lacks its '") + name + "' field");
  return found->second;
}

template <class Source>
std::uint64_t number(const Source& source, const Record& record, const char* name) {
  const std::string& value = field(source, record, name);
  if (value.size() != 4 && value.size() != 8) source.fail(record.at, std::string("its '") + name + "' field is not a number");
  return littleEndian(value);
}

std::uint8_t opOf(const Record& record) { return static_cast<std::uint8_t>(record.fields.at("op")[0]); }

/// A chunk's records, uncompressed (rosbag_storage decompresses them into a buffer of the
/// declared size and reads a message at each index entry's offset into it).
std::string uncompressedChunk(BagFile& bag, const Record& record) {
  const std::uint64_t size = number(bag, record, "size");
  if (size > kMaxBagChunk) bag.fail(record.at, "a chunk declares " + std::to_string(size) + " bytes uncompressed");
  const std::string& compression = field(bag, record, "compression");
  std::string data = bag.read(record.data, record.data_length);
  if (compression == "none") {
    if (size != record.data_length) bag.fail(record.at, "an uncompressed chunk's size differs from its data");
    return data;
  }
  std::string out(size, '\0');
  unsigned int out_size = static_cast<unsigned int>(size);
  if (compression == "bz2") {
    if (BZ2_bzBuffToBuffDecompress(out.data(), &out_size, data.data(), static_cast<unsigned int>(data.size()), 0, 0) != BZ_OK) {
      bag.fail(record.at, "a bz2 chunk does not decompress into its declared size");
    }
  } else if (compression == "lz4") {
    if (roslz4_buffToBuffDecompress(data.data(), static_cast<unsigned int>(data.size()), out.data(), &out_size) != ROSLZ4_OK) {
      bag.fail(record.at, "an lz4 chunk does not decompress into its declared size");
    }
  } else {
    bag.fail(record.at, "unknown chunk compression '" + compression + "' (none, bz2 and lz4 are known)");
  }
  out.resize(out_size);
  return out;
}

/// The start of every record inside the chunk `record`, in order.
std::vector<std::uint64_t> chunkRecords(BagFile& bag, const Record& record, std::set<std::uint64_t>& connections) {
  const ChunkBytes chunk(bag, record.at, uncompressedChunk(bag, record));
  std::vector<std::uint64_t> starts;
  for (std::uint64_t at = 0; at < chunk.size();) {
    const Record inner = readRecord(chunk, at);
    if (opOf(inner) == kConnection) connections.insert(number(chunk, inner, "conn"));
    starts.push_back(at);
    at = inner.data + inner.data_length;
  }
  return starts;
}

}  // namespace

void checkBagRecords(const std::string& path) {
  BagFile bag(path);
  if (bag.read(0, std::min<std::uint64_t>(bag.size(), kVersionLine.size())) != kVersionLine) {
    bag.fail(0, "the first line is not '#ROSBAG V2.0' (format 2.0 is read)");
  }
  std::vector<std::uint64_t> record_starts, chunk_starts;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> chunk_infos;  // the info's place, its chunk's
  std::vector<std::pair<std::uint64_t, std::uint64_t>> indexed;      // an index's or info's place, a connection
  std::set<std::uint64_t> connections;
  std::vector<std::uint64_t> last_chunk;  // the record starts of the chunk the next indexes describe
  std::uint64_t index_pos = 0;
  for (std::uint64_t at = kVersionLine.size(); at < bag.size();) {
    const Record record = readRecord(bag, at);
    record_starts.push_back(at);
    switch (opOf(record)) {
      case kBagHeader:
        index_pos = number(bag, record, "index_pos");
        break;
      case kConnection:
        connections.insert(number(bag, record, "conn"));
        break;
      case kChunk:
        chunk_starts.push_back(at);
        last_chunk = chunkRecords(bag, record, connections);
        break;
      case kIndexData: {
        if (number(bag, record, "ver") != 1) bag.fail(at, "an index of a version other than 1");
        const std::uint64_t count = number(bag, record, "count");
        if (kIndexEntry * count > record.data_length) bag.fail(at, "an index holds fewer entries than it declares");
        indexed.emplace_back(at, number(bag, record, "conn"));
        const std::string entries = bag.read(record.data, kIndexEntry * count);
        for (std::uint64_t entry = 0; entry < count; ++entry) {
          const std::uint64_t offset = littleEndian(entries.substr(entry * kIndexEntry + 8, 4));
          if (!std::binary_search(last_chunk.begin(), last_chunk.end(), offset)) {
            bag.fail(at, "an index entry points at byte " + std::to_string(offset) + " of its chunk, where no record starts");
          }
        }
        break;
      }
      case kChunkInfo:
      {
        const std::uint64_t count = number(bag, record, "count");
        if (8 * count > record.data_length) bag.fail(at, "a chunk info holds fewer entries than it declares");
        chunk_infos.emplace_back(at, number(bag, record, "chunk_pos"));
        const std::string entries = bag.read(record.data, 8 * count);  // a uint32 connection, a uint32 count
        for (std::uint64_t entry = 0; entry < count; ++entry) indexed.emplace_back(at, littleEndian(entries.substr(entry * 8, 4)));
        break;
      }
      default:
        break;
    }
    at = record.data + record.data_length;
  }
  if (index_pos != 0 && !std::binary_search(record_starts.begin(), record_starts.end(), index_pos)) {
    bag.fail(0, "the index position " + std::to_string(index_pos) + " is not where a record starts");
  }
  for (const auto& [info, chunk] : chunk_infos) {
    if (!std::binary_search(chunk_starts.begin(), chunk_starts.end(), chunk)) {
      bag.fail(info, "a chunk info points at byte " + std::to_string(chunk) + ", where no chunk starts");
    }
  }
  for (const auto& [index, connection] : indexed) {
    if (connections.count(connection) == 0) bag.fail(index, "an index or chunk info names connection " + std::to_string(connection) + ", which the bag never defines");
  }
}

}  // namespace sonarmap::detail
