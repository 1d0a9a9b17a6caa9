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

/// The top-level Schema, Channel, Message and Chunk records of the data section, one at a time,
/// each checked against the file before it is read.
class McapFile::Records {
 public:
  explicit Records(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    std::error_code error;
    size_ = std::filesystem::file_size(path_, error);
    if (!in_ || error) throw FileError("'" + path_ + "': cannot open the MCAP file");
    unsigned char magic[8] = {};
    if (size_ < 8 || !in_.read(reinterpret_cast<char*>(magic), 8) || std::memcmp(magic, kMagic, 8) != 0) {
      fail(path_, 0, "the file does not start with the MCAP magic");
    }
  }
  /// The next record's opcode, content and offset; false at DataEnd or the file's end.
  bool next(std::uint8_t& opcode, std::vector<std::uint8_t>& content, std::uint64_t& at) {
    while (at_ < size_) {
      if (size_ - at_ < 9) fail(path_, at_, "a record header runs past the file");
      unsigned char head[9];
      in_.seekg(static_cast<std::streamoff>(at_));
      if (!in_.read(reinterpret_cast<char*>(head), 9)) fail(path_, at_, "cannot read the file");
      std::uint64_t length = 0;
      std::memcpy(&length, head + 1, 8);
      if (length > size_ - at_ - 9) fail(path_, at_, "a record of " + std::to_string(length) + " bytes runs past the file");
      opcode = head[0];
      if (opcode == kDataEnd) {  // the summary after it repeats the data section
        at_ = size_;
        return false;
      }
      at = at_;
      at_ += 9 + length;
      if (opcode == kSchema || opcode == kChannel || opcode == kMessage || opcode == kChunk) {
        if (length > kMaxRecord) fail(path_, at, "a record of " + std::to_string(length) + " bytes");
        content.resize(length);
        if (!in_.read(reinterpret_cast<char*>(content.data()), static_cast<std::streamsize>(length))) {
          fail(path_, at, "cannot read the file");
        }
        return true;
      }
      // header, footer, indexes, attachments, metadata, statistics: not needed to read messages
    }
    return false;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::uint64_t at_ = 8;
};

namespace {

/// A Message record's channel, log time (ns) and data.
struct MessageRecord {
  std::uint16_t channel = 0;
  std::uint64_t log_time_ns = 0;
  std::vector<std::uint8_t> data;
};

MessageRecord messageOf(const std::string& path, std::uint64_t at, const std::vector<std::uint8_t>& content) {
  Fields fields(path, at, content);
  MessageRecord message;
  message.channel = fields.number<std::uint16_t>();
  fields.number<std::uint32_t>();  // sequence
  message.log_time_ns = fields.number<std::uint64_t>();
  fields.number<std::uint64_t>();  // publish time
  message.data = fields.rest();
  return message;
}

/// Calls `record(opcode, content)` for each record inside the Chunk record `content` at `at`.
template <class Record>
void forEachChunkRecord(const std::string& path, std::uint64_t at, const std::vector<std::uint8_t>& content, Record&& record) {
  Fields fields(path, at, content);
  fields.number<std::uint64_t>();  // message start time
  fields.number<std::uint64_t>();  // message end time
  const auto uncompressed_size = fields.number<std::uint64_t>();
  fields.number<std::uint32_t>();  // uncompressed CRC (0: not computed)
  const std::string compression = fields.text();
  const std::vector<std::uint8_t> records = decompressed(path, at, compression, fields.prefixed<std::uint64_t>(), uncompressed_size);
  for (std::uint64_t offset = 0; offset < records.size();) {
    if (records.size() - offset < 9) fail(path, at, "a chunk's record header runs past the chunk");
    const std::uint8_t opcode = records[offset];
    std::uint64_t length = 0;
    std::memcpy(&length, records.data() + offset + 1, 8);
    if (length > records.size() - offset - 9) fail(path, at, "a chunk's record of " + std::to_string(length) + " bytes runs past the chunk");
    if (opcode == kChunk) fail(path, at, "a chunk inside a chunk");
    const std::vector<std::uint8_t> inner(records.begin() + static_cast<std::ptrdiff_t>(offset + 9),
                                          records.begin() + static_cast<std::ptrdiff_t>(offset + 9 + length));
    record(opcode, inner);
    offset += 9 + length;
  }
}

}  // namespace

McapFile::McapFile(const std::string& path) : path_(path) {
  std::vector<std::uint64_t> unit_min_ns;  // each unit's earliest message, in file order
  bool in_run = false;                     // the last unit is a run of messages outside chunks
  std::uint64_t run_last_ns = 0;
  auto record = [&](std::uint8_t opcode, const std::vector<std::uint8_t>& content, std::uint64_t at, bool inner) {
    Fields fields(path_, at, content);
    if (opcode == kSchema) {
      const auto id = fields.number<std::uint16_t>();
      Schema schema;
      schema.name = fields.text();
      schema.encoding = fields.text();
      const std::vector<std::uint8_t> data = fields.prefixed();
      schema.data.assign(data.begin(), data.end());
      schemas_[id] = std::move(schema);
    } else if (opcode == kChannel) {
      const auto id = fields.number<std::uint16_t>();
      Channel channel;
      channel.schema_id = fields.number<std::uint16_t>();
      channel.topic = fields.text();
      channel.message_encoding = fields.text();
      channels_.emplace(id, std::move(channel));
    } else if (opcode == kMessage) {
      const MessageRecord message = messageOf(path_, at, content);
      if (inner) {
        unit_min_ns.back() = std::min(unit_min_ns.back(), message.log_time_ns);
      } else if (in_run && message.log_time_ns >= run_last_ns) {
        run_last_ns = message.log_time_ns;
      } else {
        unit_min_ns.push_back(message.log_time_ns);
        in_run = true;
        run_last_ns = message.log_time_ns;
      }
      const auto found = channels_.find(message.channel);
      if (found == channels_.end()) return;  // a message before its channel: skipped, as readers do
      Channel& c = found->second;
      const double time_s = 1e-9 * static_cast<double>(message.log_time_ns);
      if (c.messages == 0 || time_s < c.first_s) c.first_s = time_s;
      if (c.messages == 0 || time_s > c.last_s) c.last_s = time_s;
      ++c.messages;
    }
  };
  Records records(path_);
  std::uint8_t opcode = 0;
  std::vector<std::uint8_t> content;
  std::uint64_t at = 0;
  while (records.next(opcode, content, at)) {
    if (opcode == kChunk) {
      in_run = false;
      unit_min_ns.push_back(UINT64_MAX);
      forEachChunkRecord(path_, at, content, [&](std::uint8_t inner, const std::vector<std::uint8_t>& bytes) { record(inner, bytes, at, true); });
    } else {
      if (opcode != kMessage) in_run = false;
      record(opcode, content, at, false);
    }
  }
  later_min_ns_.assign(unit_min_ns.size() + 1, UINT64_MAX);
  for (std::size_t i = unit_min_ns.size(); i-- > 0;) later_min_ns_[i] = std::min(unit_min_ns[i], later_min_ns_[i + 1]);
}

McapFile::Cursor::Cursor(const McapFile& file, std::vector<std::uint16_t> ids)
    : file_(&file), ids_(std::move(ids)), records_(std::make_unique<Records>(file.path_)), bound_ns_(file.later_min_ns_.front()) {}
McapFile::Cursor::~Cursor() = default;
McapFile::Cursor::Cursor(Cursor&&) noexcept = default;
McapFile::Cursor& McapFile::Cursor::operator=(Cursor&&) noexcept = default;

void McapFile::Cursor::take(std::uint16_t channel, std::uint64_t log_time_ns, std::vector<std::uint8_t> data) {
  if (std::find(ids_.begin(), ids_.end(), channel) == ids_.end()) return;
  pending_.push_back(Pending{log_time_ns, order_++, std::move(data)});
  std::push_heap(pending_.begin(), pending_.end(), std::greater<>());  // a min-heap: the earliest at the front
}

bool McapFile::Cursor::readMore() {
  std::uint8_t opcode = 0;
  std::vector<std::uint8_t> content;
  std::uint64_t at = 0;
  const std::string& path = records_->path();
  // Units as the constructor counts them: a chunk, or a run of messages outside chunks in time
  // order (ended by any other record). After unit k, later_min_ns_[k + 1] bounds what is unread.
  while (records_->next(opcode, content, at)) {
    if (opcode == kChunk) {
      run_open_ = false;
      forEachChunkRecord(path, at, content, [&](std::uint8_t inner, const std::vector<std::uint8_t>& bytes) {
        if (inner != kMessage) return;
        MessageRecord message = messageOf(path, at, bytes);
        take(message.channel, message.log_time_ns, std::move(message.data));
      });
      ++units_;
      bound_ns_ = file_->later_min_ns_[std::min(units_, file_->later_min_ns_.size() - 1)];
      return true;
    }
    if (opcode != kMessage) {  // a schema or a channel: read by the constructor
      run_open_ = false;
      continue;
    }
    MessageRecord message = messageOf(path, at, content);
    const std::uint64_t time_ns = message.log_time_ns;
    if (!run_open_ || time_ns < run_last_ns_) ++units_;  // a new run
    run_open_ = true;
    run_last_ns_ = time_ns;
    take(message.channel, time_ns, std::move(message.data));
    // the rest of this run is no earlier than this message
    bound_ns_ = std::min(time_ns, file_->later_min_ns_[std::min(units_, file_->later_min_ns_.size() - 1)]);
    return true;
  }
  return false;
}

bool McapFile::Cursor::next(std::vector<std::uint8_t>& data, double& log_time_s) {
  for (;;) {
    if (!pending_.empty() && (ended_ || pending_.front().log_time_ns <= bound_ns_)) {
      std::pop_heap(pending_.begin(), pending_.end(), std::greater<>());  // the earliest to the back
      data = std::move(pending_.back().data);
      log_time_s = 1e-9 * static_cast<double>(pending_.back().log_time_ns);
      pending_.pop_back();
      return true;
    }
    if (ended_) return false;
    if (!readMore()) ended_ = true;
  }
}

void McapFile::forEachMessage(const std::vector<std::uint16_t>& ids,
                              const std::function<void(const std::vector<std::uint8_t>&, double)>& use) const {
  Cursor cursor(*this, ids);
  std::vector<std::uint8_t> data;
  double log_time_s = 0.0;
  while (cursor.next(data, log_time_s)) use(data, log_time_s);
}

}  // namespace sonarmap::detail
