/// @file mcap_file.cpp
/// An MCAP file's schemas, channels and messages (see mcap_file.hpp).

#include "mcap_file.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

constexpr unsigned char kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr std::uint8_t kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06, kDataEnd = 0x0F;
/// Largest record read into memory, bytes: a chunk (compressed) or a message outside chunks.
constexpr std::uint64_t kMaxRecord = 2 * kMaxMcapChunk;

[[noreturn]] void fail(const std::string& path, std::uint64_t at, const std::string& what) {
  throw FileError("'" + path + "': MCAP: byte " + std::to_string(at) + ": " + what);
}

/// Little-endian fields of one record's content, each checked against it.
class Fields {
 public:
  Fields(const std::string& path, std::uint64_t at, const std::vector<std::uint8_t>& bytes) : path_(path), at_(at), bytes_(bytes) {}
  template <class T>
  T number() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + offset_, sizeof(T));  // MCAP and this machine: little-endian
    offset_ += sizeof(T);
    return value;
  }
  /// A String or Bytes field: a uint32 (or, for a chunk's records, uint64) length and the bytes.
  template <class Length = std::uint32_t>
  std::vector<std::uint8_t> prefixed() {
    const std::uint64_t length = number<Length>();
    need(length);
    std::vector<std::uint8_t> out(bytes_.begin() + static_cast<std::ptrdiff_t>(offset_),
                                  bytes_.begin() + static_cast<std::ptrdiff_t>(offset_ + length));
    offset_ += length;
    return out;
  }
  std::string text() {
    const std::vector<std::uint8_t> bytes = prefixed();
    return std::string(bytes.begin(), bytes.end());
  }
  std::vector<std::uint8_t> rest() {
    std::vector<std::uint8_t> out(bytes_.begin() + static_cast<std::ptrdiff_t>(offset_), bytes_.end());
    offset_ = bytes_.size();
    return out;
  }

 private:
  void need(std::uint64_t count) const {
    if (count > bytes_.size() - offset_) fail(path_, at_, "a record's field of " + std::to_string(count) + " bytes runs past the record");
  }
  const std::string& path_;
  std::uint64_t at_;
  const std::vector<std::uint8_t>& bytes_;
  std::uint64_t offset_ = 0;
};

std::vector<std::uint8_t> decompressed(const std::string& path, std::uint64_t at, const std::string& compression,
                                       const std::vector<std::uint8_t>& data, std::uint64_t size) {
  if (size > kMaxMcapChunk) fail(path, at, "a chunk declares " + std::to_string(size) + " bytes uncompressed");
  if (compression.empty()) {
    if (data.size() != size) fail(path, at, "an uncompressed chunk's size differs from its records");
    return data;
  }
  if (compression != "zstd" && compression != "lz4") {
    fail(path, at, "unknown chunk compression '" + compression + "' (none, zstd and lz4 are known)");
  }
  // Before allocating what the chunk declares: a zstd frame that states its size must state this one;
  // an lz4 frame cannot expand more than 255 times (a literal run of 255-byte length codes).
  if (compression == "zstd") {
    const unsigned long long stated = ZSTD_getFrameContentSize(data.data(), data.size());
    if (stated == ZSTD_CONTENTSIZE_ERROR || (stated != ZSTD_CONTENTSIZE_UNKNOWN && stated != size)) {
      fail(path, at, "a zstd chunk's frame does not hold its declared size");
    }
  } else if (compression == "lz4" && size > 255 * static_cast<std::uint64_t>(data.size()) + 64) {
    fail(path, at, "an lz4 chunk of " + std::to_string(data.size()) + " bytes cannot hold " + std::to_string(size));
  }
  std::vector<std::uint8_t> out(size);
  if (compression == "zstd") {
    const std::size_t written = ZSTD_decompress(out.data(), out.size(), data.data(), data.size());
    if (ZSTD_isError(written) || written != size) fail(path, at, "a zstd chunk does not decompress into its declared size");
    return out;
  }
  // lz4 frames
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) fail(path, at, "cannot start lz4");
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(raw, LZ4F_freeDecompressionContext);
  std::size_t in_at = 0, out_at = 0;
  while (in_at < data.size()) {
    std::size_t in_size = data.size() - in_at, out_size = out.size() - out_at;
    const std::size_t hint = LZ4F_decompress(context.get(), out.data() + out_at, &out_size, data.data() + in_at, &in_size, nullptr);
    if (LZ4F_isError(hint)) fail(path, at, std::string("an lz4 chunk does not decompress: ") + LZ4F_getErrorName(hint));
    in_at += in_size;
    out_at += out_size;
    if (hint == 0) break;  // the frame ended
    if (in_size == 0 && out_size == 0) fail(path, at, "an lz4 chunk does not decompress into its declared size");
  }
  if (out_at != size) fail(path, at, "an lz4 chunk does not decompress into its declared size");
  return out;
}

}  // namespace

bool startsLikeMcap(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[5] = {};
  return in.read(magic, 5) && std::memcmp(magic, kMagic, 5) == 0;
}

McapFile::McapFile(const std::string& path) : path_(path) {
  Visitor visit;
  visit.schema = [&](std::uint16_t id, Schema schema) { schemas_[id] = std::move(schema); };
  visit.channel = [&](std::uint16_t id, Channel channel) { channels_.emplace(id, std::move(channel)); };
  visit.message = [&](std::uint16_t channel, std::uint64_t log_time_ns, std::vector<std::uint8_t>) {
    const auto found = channels_.find(channel);
    if (found == channels_.end()) return;  // a message before its channel: skipped, as readers do
    Channel& c = found->second;
    const double time_s = 1e-9 * static_cast<double>(log_time_ns);
    if (c.messages == 0 || time_s < c.first_s) c.first_s = time_s;
    if (c.messages == 0 || time_s > c.last_s) c.last_s = time_s;
    ++c.messages;
  };
  walkRecords(visit);
}

void McapFile::forEachMessage(const std::vector<std::uint16_t>& ids,
                              const std::function<void(const std::vector<std::uint8_t>&, double)>& use) const {
  std::vector<std::pair<std::uint64_t, std::vector<std::uint8_t>>> messages;
  Visitor visit;
  visit.schema = [](std::uint16_t, Schema) {};
  visit.channel = [](std::uint16_t, Channel) {};
  visit.message = [&](std::uint16_t channel, std::uint64_t log_time_ns, std::vector<std::uint8_t> data) {
    if (std::find(ids.begin(), ids.end(), channel) != ids.end()) messages.emplace_back(log_time_ns, std::move(data));
  };
  walkRecords(visit);
  std::stable_sort(messages.begin(), messages.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [log_time_ns, data] : messages) use(data, 1e-9 * static_cast<double>(log_time_ns));
}

void McapFile::walkRecords(const Visitor& visit) const {
  std::ifstream in(path_, std::ios::binary);
  std::error_code error;
  const std::uint64_t size = std::filesystem::file_size(path_, error);
  if (!in || error) throw FileError("'" + path_ + "': cannot open the MCAP file");
  unsigned char magic[8] = {};
  if (size < 8 || !in.read(reinterpret_cast<char*>(magic), 8) || std::memcmp(magic, kMagic, 8) != 0) {
    fail(path_, 0, "the file does not start with the MCAP magic");
  }
  // One record (opcode, content); inside a chunk `inner` is set and nothing nests further.
  auto handle = [&](std::uint8_t opcode, const std::vector<std::uint8_t>& content, std::uint64_t at, bool inner, auto& self) -> void {
    Fields fields(path_, at, content);
    switch (opcode) {
      case kSchema: {
        const auto id = fields.number<std::uint16_t>();
        Schema schema;
        schema.name = fields.text();
        schema.encoding = fields.text();
        const std::vector<std::uint8_t> data = fields.prefixed();
        schema.data.assign(data.begin(), data.end());
        visit.schema(id, std::move(schema));
        break;
      }
      case kChannel: {
        const auto id = fields.number<std::uint16_t>();
        Channel channel;
        channel.schema_id = fields.number<std::uint16_t>();
        channel.topic = fields.text();
        channel.message_encoding = fields.text();
        visit.channel(id, std::move(channel));
        break;
      }
      case kMessage: {
        const auto channel = fields.number<std::uint16_t>();
        fields.number<std::uint32_t>();  // sequence
        const auto log_time_ns = fields.number<std::uint64_t>();
        fields.number<std::uint64_t>();  // publish time
        visit.message(channel, log_time_ns, fields.rest());
        break;
      }
      case kChunk: {
        if (inner) fail(path_, at, "a chunk inside a chunk");
        fields.number<std::uint64_t>();  // message start time
        fields.number<std::uint64_t>();  // message end time
        const auto uncompressed_size = fields.number<std::uint64_t>();
        fields.number<std::uint32_t>();  // uncompressed CRC (0: not computed)
        const std::string compression = fields.text();
        const std::vector<std::uint8_t> records =
            decompressed(path_, at, compression, fields.prefixed<std::uint64_t>(), uncompressed_size);
        for (std::uint64_t offset = 0; offset < records.size();) {
          if (records.size() - offset < 9) fail(path_, at, "a chunk's record header runs past the chunk");
          const std::uint8_t inner_opcode = records[offset];
          std::uint64_t length = 0;
          std::memcpy(&length, records.data() + offset + 1, 8);
          if (length > records.size() - offset - 9) fail(path_, at, "a chunk's record of " + std::to_string(length) + " bytes runs past the chunk");
          const std::vector<std::uint8_t> inner_content(records.begin() + static_cast<std::ptrdiff_t>(offset + 9),
                                                        records.begin() + static_cast<std::ptrdiff_t>(offset + 9 + length));
          self(inner_opcode, inner_content, at, true, self);
          offset += 9 + length;
        }
        break;
      }
      default:
        break;  // header, footer, indexes, attachments, metadata, statistics: not needed to read messages
    }
  };
  for (std::uint64_t at = 8; at < size;) {
    if (size - at < 9) fail(path_, at, "a record header runs past the file");
    unsigned char head[9];
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(reinterpret_cast<char*>(head), 9)) fail(path_, at, "cannot read the file");
    std::uint64_t length = 0;
    std::memcpy(&length, head + 1, 8);
    if (length > size - at - 9) fail(path_, at, "a record of " + std::to_string(length) + " bytes runs past the file");
    const std::uint8_t opcode = head[0];
    if (opcode == kDataEnd) break;  // the summary after it repeats the data section
    if (opcode == kSchema || opcode == kChannel || opcode == kMessage || opcode == kChunk) {
      if (length > kMaxRecord) fail(path_, at, "a record of " + std::to_string(length) + " bytes");
      std::vector<std::uint8_t> content(length);
      if (!in.read(reinterpret_cast<char*>(content.data()), static_cast<std::streamsize>(length))) fail(path_, at, "cannot read the file");
      handle(opcode, content, at, false, handle);
    }
    at += 9 + length;
  }
}

}  // namespace sonarmap::detail
