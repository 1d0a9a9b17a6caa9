/// @file mcap_records.cpp
/// MCAP records and CDR messages written as they come (see mcap_records.hpp).

#include "mcap_records.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

constexpr unsigned char kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr std::uint8_t kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05,
                       kChunk = 0x06, kMetadata = 0x0C, kDataEnd = 0x0F;
constexpr const char* kRule = "================================================================================\n";

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

}  // namespace

void Cdr::text(const std::string& s) {
  put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
  bytes_.insert(bytes_.end(), s.begin(), s.end());
  bytes_.push_back(0);
}

void Cdr::header(std::int32_t sec, std::uint32_t nanosec, const std::string& frame_id) {
  put<std::int32_t>(sec);
  put<std::uint32_t>(nanosec);
  text(frame_id);
}

void Cdr::header(double time_s, const std::string& frame_id) {
  const double seconds = std::floor(time_s);
  header(static_cast<std::int32_t>(seconds),
         static_cast<std::uint32_t>(std::min(999999999.0, std::round((time_s - seconds) * 1e9))), frame_id);
}

void Cdr::bytes(const std::vector<std::uint8_t>& values) {
  put<std::uint32_t>(static_cast<std::uint32_t>(values.size()));
  bytes_.insert(bytes_.end(), values.begin(), values.end());
}

std::string ros2SchemaWithHeader(const std::string& fields) {
  return fields + kRule + "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n" + kRule +
         "MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n";
}

McapRecordWriter::McapRecordWriter(std::ostream& out, McapCompression compression, std::size_t chunk_bytes)
    : out_(out), compression_(compression), chunk_bytes_(chunk_bytes) {
  McapOut start;
  for (const unsigned char c : kMagic) start.put<unsigned char>(c);
  McapOut header;
  header.text("ros2");
  header.text("sonarmap");
  start.record(kHeader, header.bytes());
  write(start.bytes());
}

std::uint16_t McapRecordWriter::schema(const std::string& name, const std::string& data) {
  McapOut s;
  s.put<std::uint16_t>(++schemas_);
  s.text(name);
  s.text("ros2msg");
  s.text(data);
  McapOut record;
  record.record(kSchema, s.bytes());
  write(record.bytes());
  return schemas_;
}

std::uint16_t McapRecordWriter::channel(std::uint16_t schema_id, const std::string& topic) {
  McapOut c;
  c.put<std::uint16_t>(++channels_);
  c.put<std::uint16_t>(schema_id);
  c.text(topic);
  c.text("cdr");
  c.put<std::uint32_t>(0);  // metadata: an empty map
  McapOut record;
  record.record(kChannel, c.bytes());
  write(record.bytes());
  return channels_;
}

void McapRecordWriter::metadata(const std::string& name, const std::map<std::string, std::string>& values) {
  writeChunk();
  McapOut entries;
  for (const auto& [key, value] : values) {
    entries.text(key);
    entries.text(value);
  }
  McapOut m;
  m.text(name);
  m.put<std::uint32_t>(static_cast<std::uint32_t>(entries.bytes().size()));
  m.raw(entries.bytes());
  McapOut record;
  record.record(kMetadata, m.bytes());
  write(record.bytes());
}

void McapRecordWriter::message(std::uint16_t channel_id, std::uint64_t time_ns, const std::vector<unsigned char>& data) {
  McapOut m;
  m.put<std::uint16_t>(channel_id);
  m.put<std::uint32_t>(sequence_++);
  m.put<std::uint64_t>(time_ns);  // log time
  m.put<std::uint64_t>(time_ns);  // publish time
  m.raw(data);
  if (chunk_.bytes().empty()) {
    chunk_start_ns_ = chunk_end_ns_ = time_ns;
  } else {
    chunk_start_ns_ = std::min(chunk_start_ns_, time_ns);
    chunk_end_ns_ = std::max(chunk_end_ns_, time_ns);
  }
  chunk_.record(kMessage, m.bytes());
  if (chunk_.bytes().size() >= chunk_bytes_) writeChunk();
}

void McapRecordWriter::writeChunk() {
  if (chunk_.bytes().empty()) return;
  McapOut c;
  c.put<std::uint64_t>(chunk_start_ns_);
  c.put<std::uint64_t>(chunk_end_ns_);
  c.put<std::uint64_t>(chunk_.bytes().size());
  c.put<std::uint32_t>(0);  // no CRC
  c.text(compression_ == McapCompression::kZstd ? "zstd" : compression_ == McapCompression::kLz4 ? "lz4" : "");
  const std::vector<unsigned char> packed = compressed(compression_, chunk_.bytes());
  c.put<std::uint64_t>(packed.size());
  c.raw(packed);
  McapOut record;
  record.record(kChunk, c.bytes());
  chunk_.bytes().clear();
  write(record.bytes());
}

void McapRecordWriter::flush() {
  writeChunk();
  out_.flush();
  if (!out_) throw FileError("cannot write the MCAP file (is the disk full?)");
}

void McapRecordWriter::finish() {
  writeChunk();
  McapOut end;
  McapOut data_end;
  data_end.put<std::uint32_t>(0);  // no data section CRC
  end.record(kDataEnd, data_end.bytes());
  McapOut footer;
  footer.put<std::uint64_t>(0);  // no summary section
  footer.put<std::uint64_t>(0);
  footer.put<std::uint32_t>(0);
  end.record(kFooter, footer.bytes());
  for (const unsigned char c : kMagic) end.put<unsigned char>(c);
  write(end.bytes());
  flush();
}

void McapRecordWriter::write(const std::vector<unsigned char>& bytes) {
  out_.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out_) throw FileError("cannot write the MCAP file (is the disk full?)");
}

}  // namespace sonarmap::detail
