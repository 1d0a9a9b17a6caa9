/// @file ros_bag_records.cpp
/// A ROS 1 bag's records read with every length checked (see ros_bag_records.hpp).

#include "ros_bag_records.hpp"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

namespace sonarmap::detail {
namespace {

/// Largest record header or connection header read to check it, bytes (real ones hold a few
/// fields and a message definition: kilobytes).
constexpr std::uint64_t kMaxHeader = 16u << 20;
/// Output grown by this much at a time when decompressing a chunk of unknown size.
constexpr std::uint64_t kOutputStep = 1u << 20;

/// Decompresses `data` with one of the streaming decoders: `step(in, in_left, out, out_left)` runs
/// the decoder once and gives 1 at the stream's end, 0 to go on, -1 on an error. The output grows
/// up to `limit` bytes; `ended` tells whether the stream ended within them.
template <class Step>
std::string stream(const std::string& data, std::uint64_t limit, bool& ended, Step&& step) {
  std::string out;
  const char* in = data.data();
  std::uint64_t in_left = data.size();
  ended = false;
  for (;;) {
    const std::uint64_t done = out.size();
    if (done > limit) break;  // one byte beyond it: room the decoder needs to tell a stream that ends at it
    out.resize(std::min(limit + 1, done + kOutputStep));
    std::uint64_t out_left = out.size() - done;
    const int status = step(in, in_left, out.data() + done, out_left);
    out.resize(out.size() - out_left);
    if (status != 0) {
      ended = status > 0;
      break;
    }
    if (in_left == 0 && out_left > 0) break;  // the input ran out before the stream's end
  }
  if (out.size() > limit) {  // more than the limit
    out.resize(limit);
    ended = false;
  }
  return out;
}

std::string bz2Stream(const std::string& data, std::uint64_t limit, bool& ended) {
  bz_stream bz{};
  if (BZ2_bzDecompressInit(&bz, 0, 0) != BZ_OK) {
    ended = false;
    return {};
  }
  std::string out = stream(data, limit, ended, [&](const char*& in, std::uint64_t& in_left, char* out_at, std::uint64_t& out_left) {
    bz.next_in = const_cast<char*>(in);  // bzlib's API is not const
    bz.avail_in = static_cast<unsigned int>(std::min<std::uint64_t>(in_left, 1u << 30));
    bz.next_out = out_at;
    bz.avail_out = static_cast<unsigned int>(out_left);
    const unsigned int given = bz.avail_in;
    const int status = BZ2_bzDecompress(&bz);
    in += given - bz.avail_in;
    in_left -= given - bz.avail_in;
    out_left = bz.avail_out;
    return status == BZ_STREAM_END ? 1 : status == BZ_OK ? 0 : -1;
  });
  BZ2_bzDecompressEnd(&bz);
  return out;
}

std::string lz4Stream(const std::string& data, std::uint64_t limit, bool& ended) {
  roslz4_stream lz{};
  if (roslz4_decompressStart(&lz) != ROSLZ4_OK) {
    ended = false;
    return {};
  }
  std::string out = stream(data, limit, ended, [&](const char*& in, std::uint64_t& in_left, char* out_at, std::uint64_t& out_left) {
    lz.input_next = const_cast<char*>(in);  // roslz4's API is not const
    lz.input_left = static_cast<int>(std::min<std::uint64_t>(in_left, 1u << 30));
    lz.output_next = out_at;
    lz.output_left = static_cast<int>(out_left);
    const int given = lz.input_left;
    const int status = roslz4_decompress(&lz);
    in += given - lz.input_left;
    in_left -= static_cast<std::uint64_t>(given - lz.input_left);
    out_left = static_cast<std::uint64_t>(lz.output_left);
    return status == ROSLZ4_STREAM_END ? 1 : status == ROSLZ4_OK ? 0 : -1;
  });
  roslz4_decompressEnd(&lz);
  return out;
}

}  // namespace

BagFile::BagFile(const std::string& path) : path_(path), in_(path, std::ios::binary) {
  std::error_code error;
  size_ = std::filesystem::file_size(path, error);
  if (!in_ || error) throw FileError("'" + path + "': cannot open the ROS bag");
}

void BagFile::fail(std::uint64_t at, const std::string& what) const {
  throw BagRecordError(path_, "byte " + std::to_string(at) + ": " + what);
}

std::string BagFile::read(std::uint64_t at, std::uint64_t count) {
  if (count > size_ || at > size_ - count) fail(at, std::to_string(count) + " bytes run past the file");
  std::string bytes(count, '\0');
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(at));
  if (!in_.read(bytes.data(), static_cast<std::streamsize>(count))) fail(at, "cannot read the file");
  return bytes;
}

void ChunkBytes::fail(std::uint64_t at, const std::string& what) const {
  bag_.fail(chunk_, "byte " + std::to_string(at) + " of the chunk's records: " + what);
}

std::string ChunkBytes::read(std::uint64_t at, std::uint64_t count) {
  if (count > bytes_.size() || at > bytes_.size() - count) fail(at, std::to_string(count) + " bytes run past the chunk");
  return bytes_.substr(at, count);
}

std::uint64_t littleEndian(const std::string& bytes) {
  std::uint64_t value = 0;
  std::memcpy(&value, bytes.data(), std::min<std::size_t>(bytes.size(), 8));  // little-endian, as the bag
  return value;
}

std::map<std::string, std::string> bagFields(const BagBytes& source, std::uint64_t at, const std::string& header) {
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

BagRecord readBagRecord(BagBytes& source, std::uint64_t at, bool data_may_run_past) {
  BagRecord record;
  record.at = at;
  const std::uint64_t header_length = littleEndian(source.read(at, 4));
  if (header_length > kMaxHeader || header_length > source.size() - at - 4) {
    source.fail(at, "a record header of " + std::to_string(header_length) + " bytes does not fit");
  }
  record.fields = bagFields(source, at, source.read(at + 4, header_length));
  const std::uint64_t length_at = at + 4 + header_length;
  record.data_length = littleEndian(source.read(length_at, 4));
  record.data = length_at + 4;
  const auto op = record.fields.find("op");
  if (op == record.fields.end() || op->second.size() != 1) source.fail(at, "a record has no one-byte 'op' field");
  if (!data_may_run_past && record.data_length > source.size() - record.data) {
    source.fail(at, "record data of " + std::to_string(record.data_length) + " bytes runs past its end");
  }
  if (record.op() == kBagConnection && record.data_length <= source.size() - record.data) {
    if (record.data_length > kMaxHeader) source.fail(at, "a connection header of " + std::to_string(record.data_length) + " bytes");
    bagFields(source, at, source.read(record.data, record.data_length));
  }
  return record;
}

const std::string& bagField(const BagBytes& source, const BagRecord& record, const char* name) {
  const auto found = record.fields.find(name);
  if (found == record.fields.end()) source.fail(record.at, std::string("a record lacks its '") + name + "' field");
  return found->second;
}

std::uint64_t bagNumber(const BagBytes& source, const BagRecord& record, const char* name) {
  const std::string& value = bagField(source, record, name);
  if (value.size() != 4 && value.size() != 8) source.fail(record.at, std::string("its '") + name + "' field is not a number");
  return littleEndian(value);
}

std::uint64_t bagChunkSize(const BagBytes& source, const BagRecord& chunk) {
  const std::uint64_t size = bagNumber(source, chunk, "size");
  if (size > kMaxBagChunk) source.fail(chunk.at, "a chunk declares " + std::to_string(size) + " bytes uncompressed");
  return size;
}

std::string uncompressedChunk(BagFile& bag, const BagRecord& chunk) {
  const std::uint64_t size = bagChunkSize(bag, chunk);
  const std::string& compression = bagField(bag, chunk, "compression");
  std::string data = bag.read(chunk.data, chunk.data_length);
  if (compression == "none") {
    if (size != chunk.data_length) bag.fail(chunk.at, "an uncompressed chunk's size differs from its data");
    return data;
  }
  bool ended = false;
  std::string out = decompressAvailable(bag, chunk, data, size, ended);
  // rosbag_storage decompresses into a buffer of the declared size: the stream must end in it
  if (!ended) bag.fail(chunk.at, "a " + compression + " chunk does not decompress into its declared size");
  return out;
}

std::string decompressAvailable(const BagFile& bag, const BagRecord& chunk, const std::string& data, std::uint64_t limit,
                                bool& ended) {
  const std::string& compression = bagField(bag, chunk, "compression");
  if (compression == "none") {
    ended = true;
    return data.substr(0, limit);
  }
  if (compression == "bz2") return bz2Stream(data, limit, ended);
  if (compression == "lz4") return lz4Stream(data, limit, ended);
  bag.fail(chunk.at, "unknown chunk compression '" + compression + "' (none, bz2 and lz4 are known)");
}

}  // namespace sonarmap::detail
