/// @file dataflash_log.cpp
/// scanDataflash, DataflashRecord (see dataflash_log.hpp).

#include "dataflash_log.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <map>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

constexpr std::uint8_t kHead1 = 0xA3, kHead2 = 0x95;
constexpr std::uint8_t kFmtType = 128;
constexpr std::size_t kFmtLength = 89;
constexpr std::size_t kHeaderBytes = 3;

/// Bytes of a format character's field; 0 for an unknown character (LogStructure.h's list).
std::size_t fieldBytes(char c) {
  switch (c) {
    case 'b': case 'B': case 'M': return 1;
    case 'h': case 'H': case 'c': case 'C': return 2;
    case 'i': case 'I': case 'f': case 'e': case 'E': case 'L': case 'n': return 4;
    case 'd': case 'q': case 'Q': return 8;
    case 'N': return 16;
    case 'Z': return 64;
    case 'a': return 64;  // int16_t[32]
    default: return 0;
  }
}

template <typename T>
double as(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof value);  // little-endian, as every target of this project
  return static_cast<double>(value);
}

std::string text(const std::uint8_t* p, std::size_t size) {
  const auto* chars = reinterpret_cast<const char*>(p);
  return std::string(chars, std::find(chars, chars + size, '\0'));
}

std::vector<std::string> split(const std::string& columns) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= columns.size()) {
    const std::size_t comma = std::min(columns.find(',', start), columns.size());
    out.push_back(columns.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

/// The format an FMT record defines; nullopt when its characters are unknown, its columns do not
/// match them or its fields do not fill its length.
std::optional<DataflashFormat> defined(const std::uint8_t* record) {
  DataflashFormat f;
  f.type = record[3];
  f.length = record[4];
  f.name = text(record + 5, 4);
  f.format = text(record + 9, 16);
  f.columns = split(text(record + 25, 64));
  if (f.columns.size() != f.format.size()) return std::nullopt;
  std::size_t offset = kHeaderBytes;
  for (char c : f.format) {
    const std::size_t bytes = fieldBytes(c);
    if (bytes == 0) return std::nullopt;
    f.offsets.push_back(offset);
    offset += bytes;
  }
  if (offset != f.length || f.type == kFmtType) return std::nullopt;
  return f;
}

DataflashFormat fmtFormat() {
  DataflashFormat f;
  f.type = kFmtType;
  f.length = kFmtLength;
  f.name = "FMT";
  f.format = "BBnNZ";
  f.columns = {"Type", "Length", "Name", "Format", "Columns"};
  f.offsets = {3, 4, 5, 9, 25};
  return f;
}

}  // namespace

std::optional<double> DataflashRecord::value(std::string_view name) const {
  const auto it = std::find(format_.columns.begin(), format_.columns.end(), name);
  if (it == format_.columns.end()) return std::nullopt;
  const std::size_t i = static_cast<std::size_t>(it - format_.columns.begin());
  const std::uint8_t* p = record_ + format_.offsets[i];
  switch (format_.format[i]) {
    case 'b': return as<std::int8_t>(p);
    case 'B': case 'M': return as<std::uint8_t>(p);
    case 'h': return as<std::int16_t>(p);
    case 'H': return as<std::uint16_t>(p);
    case 'i': return as<std::int32_t>(p);
    case 'I': return as<std::uint32_t>(p);
    case 'f': return as<float>(p);
    case 'd': return as<double>(p);
    case 'q': return as<std::int64_t>(p);
    case 'Q': return as<std::uint64_t>(p);
    case 'c': return as<std::int16_t>(p) / 100.0;
    case 'C': return as<std::uint16_t>(p) / 100.0;
    case 'e': return as<std::int32_t>(p) / 100.0;
    case 'E': return as<std::uint32_t>(p) / 100.0;
    case 'L': return as<std::int32_t>(p) / 1e7;
    default: return std::nullopt;  // n, N, Z: text; a: an array
  }
}

DataflashScan scanDataflash(std::span<const std::uint8_t> bytes, const std::string& source,
                            const std::function<void(const DataflashRecord&)>& visit) {
  if (bytes.size() < kHeaderBytes || bytes[0] != kHead1 || bytes[1] != kHead2 || bytes[2] != kFmtType) {
    throw FileError("'" + source + "': not an ArduPilot dataflash log (it starts with a FMT record: 0xA3 0x95 0x80)");
  }
  std::map<std::uint8_t, DataflashFormat> formats{{kFmtType, fmtFormat()}};
  DataflashScan scan;
  std::size_t offset = 0;
  while (offset + kHeaderBytes <= bytes.size()) {
    const std::uint8_t* p = bytes.data() + offset;
    const auto format = formats.find(p[2]);
    if (p[0] != kHead1 || p[1] != kHead2 || format == formats.end()) {
      ++scan.skipped_bytes;
      ++offset;
      continue;
    }
    const DataflashFormat& f = format->second;
    if (offset + f.length > bytes.size()) {
      scan.stop_note = "'" + source + "': record " + std::to_string(scan.records + 1) + " at byte " +
                       std::to_string(offset) + ": a record cut short (" + f.name + ", " +
                       std::to_string(bytes.size() - offset) + " of its " + std::to_string(f.length) +
                       " bytes); the " + std::to_string(scan.records) + " records before it are kept";
      return scan;
    }
    ++scan.records;
    if (f.type == kFmtType) {
      if (std::optional<DataflashFormat> defined_format = defined(p)) {
        formats[defined_format->type] = std::move(*defined_format);
      } else {
        ++scan.refused_formats;
      }
    } else {
      visit(DataflashRecord(f, p));
    }
    offset += f.length;
  }
  scan.skipped_bytes += bytes.size() - offset;
  return scan;
}

}  // namespace sonarmap::detail
