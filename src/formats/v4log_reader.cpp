/// @file v4log_reader.cpp
/// readSeaNetV4Log / parseSeaNetV4Log: Tritech SeaNet `.V4LOG` → SonarLog (see v4log_reader.hpp).

#include "sonarmap/formats/v4log_reader.hpp"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../io/byte_io.hpp"
#include "reader_support.hpp"
#include "seanet_head_data.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

using detail::ByteCursor;

constexpr std::string_view kMagic = "SeaNetV4 Log File V1";
constexpr std::size_t kMagicBytes = 32;
/// Record length, OLE date, tx node, rx node, message type: the least a record can hold.
constexpr std::size_t kMinRecordBytes = 2 + 8 + 3;
constexpr std::size_t kRecordDateAt = 2;  // offset of the OLE date in a record
constexpr double kSecondsPerDay = 86400.0;

std::string recordName(std::uint32_t index) { return "record " + std::to_string(index); }

/// The fields of the file header the reader uses.
struct FileHeader {
  std::uint32_t data_offset = 0;
  std::uint32_t record_count = 0;
};

/// Printable form of the first bytes of a wrong magic, for the message.
std::string quoted(std::span<const unsigned char> bytes) {
  std::string text;
  for (const unsigned char c : bytes.first(std::min(bytes.size(), kMagic.size()))) {
    text += (c >= 0x20 && c < 0x7F) ? static_cast<char>(c) : '?';
  }
  return "'" + text + "'";
}

FileHeader readFileHeader(std::span<const unsigned char> bytes, const std::string& source) {
  ByteCursor in(bytes, source);
  // The magic first, so that a short file of another kind is named as such, not as truncated.
  const std::size_t compared = std::min(bytes.size(), kMagic.size());
  if (std::string_view(reinterpret_cast<const char*>(bytes.data()), compared) != kMagic.substr(0, compared)) {
    in.failAt(0, "magic is " + quoted(bytes) + ", expected '" + std::string(kMagic) + "' (not a SeaNet V4 log)");
  }
  in.require(kV4LogFileHeaderBytes, "the 80-byte SeaNet V4 file header");
  for (std::size_t i = 0; i < kMagicBytes; ++i) in.u8("magic");
  in.u32("version");
  in.u32("header offset");
  FileHeader header;
  const std::size_t data_offset_at = in.offset();
  header.data_offset = in.u32("data offset");
  header.record_count = in.u32("record count");
  if (header.data_offset < kV4LogFileHeaderBytes || header.data_offset > bytes.size()) {
    in.failAt(data_offset_at, "data offset is " + std::to_string(header.data_offset) + ", expected " +
                                  std::to_string(kV4LogFileHeaderBytes) + "…" + std::to_string(bytes.size()) +
                                  " (within the file)");
  }
  return header;
}

/// Decodes the mtHeadData message of one record (starting at byte `at`, at least
/// kV4LogHeadDataHeaderBytes long): a beam without a time, or a skip reason when it has no data
/// bytes. @throws FileError for a field the shared decoder rejects.
detail::SeaNetHeadData readHeadData(std::span<const unsigned char> record, std::size_t at, std::uint32_t index,
                                 const std::string& source, double sound_speed_m_s) {
  constexpr std::size_t kBodyAt = kV4LogHeadDataHeaderBytes - detail::kSeaNetHeadDataFieldBytes;
  detail::SeaNetHeadData decoded = detail::decodeSeaNetHeadData(
      record.subspan(kBodyAt), at + kBodyAt, {recordName(index), "record", kV4LogHeadDataHeaderBytes}, sound_speed_m_s);
  if (!decoded.defect.empty()) ByteCursor(record, source, at).failAt(decoded.defect_at, decoded.defect);
  return decoded;
}

/// The bytes of record `index`, which starts at byte `at`, or why its length cannot frame it: a
/// length field cut off by the end of the file, below the smallest record, or running past the end
/// (a log cut short: a full disk, a pulled cable).
struct Framed {
  std::span<const unsigned char> record;
  std::string defect;  ///< set when `record` is empty
};

Framed recordAt(std::span<const unsigned char> bytes, std::size_t at, std::uint32_t index) {
  const std::string where = "byte " + std::to_string(at) + ": ";
  if (bytes.size() - at < 2) {
    return {{}, where + "the file ends " + std::to_string(bytes.size() - at) + " byte(s) into the length of " +
                    recordName(index) + " (cut short)"};
  }
  const std::uint16_t length = detail::u16At(bytes, at);
  if (length < kMinRecordBytes) {
    return {{}, where + "length of " + recordName(index) + " is " + std::to_string(length) + ", expected at least " +
                    std::to_string(kMinRecordBytes)};
  }
  if (length > bytes.size() - at) {
    return {{}, where + "length of " + recordName(index) + " is " + std::to_string(length) + " but the file ends " +
                    std::to_string(bytes.size() - at) + " bytes after the record's start (cut short)"};
  }
  return {bytes.subspan(at, length), {}};
}

/// What one record holds: its date and a beam, or why it has none.
struct ParsedRecord {
  double date_days = 0.0;    ///< OLE date: days since 1899-12-30
  std::optional<Beam> beam;  ///< without its time yet
  std::string skip_reason;   ///< set when `beam` is empty
};

ParsedRecord readRecord(std::span<const unsigned char> record, std::size_t at, std::uint32_t index,
                        const std::string& source, double sound_speed_m_s) {
  ByteCursor in(record, source, at);
  in.u16("record length");
  ParsedRecord parsed;
  parsed.date_days = in.finiteF64("record date");
  in.u8("tx node");
  in.u8("rx node");
  const std::uint8_t type = in.u8("message type");
  if (type != detail::kSeaNetMtHeadData) {
    parsed.skip_reason = "message type " + std::to_string(type) + ", not mtHeadData (2)";
    return parsed;
  }
  if (record.size() < kV4LogHeadDataHeaderBytes) {
    in.failAt(at, "length of " + recordName(index) + " is " + std::to_string(record.size()) + ", expected at least " +
                      std::to_string(kV4LogHeadDataHeaderBytes) + " for mtHeadData");
  }
  detail::SeaNetHeadData decoded = readHeadData(record, at, index, source, sound_speed_m_s);
  parsed.beam = std::move(decoded.beam);
  parsed.skip_reason = std::move(decoded.skip_reason);
  return parsed;
}

/// Throws unless the beam of record `index` (at byte `at`), at `time_s`, is not before the
/// previous beam's `previous_s` (seconds since the first record).
void checkTimeOrder(double time_s, double previous_s, std::size_t at, std::uint32_t index, const std::string& source) {
  if (time_s >= previous_s) return;
  throw FileError(source + ": byte " + std::to_string(at + kRecordDateAt) + ": date of " + recordName(index) + " is " +
                  std::to_string(time_s) + " s after the first record, before the previous beam's " +
                  std::to_string(previous_s) + " s; times must not go backwards");
}

}  // namespace

SonarLog parseSeaNetV4Log(std::span<const unsigned char> bytes, const std::string& source, const V4LogOptions& options) {
  detail::checkSoundSpeed(options.sound_speed_m_s);
  const FileHeader header = readFileHeader(bytes, source);
  SonarLog log;
  // Reserved for the records the bytes can hold: a cut file's header declares more.
  log.beams.reserve(std::min<std::size_t>(header.record_count, (bytes.size() - header.data_offset) / kMinRecordBytes));
  std::size_t at = header.data_offset;
  std::optional<double> first_date_days;
  std::string first_skip;  // why the first record without a beam has none
  const auto skip = [&](const std::string& reason) {
    if (first_skip.empty()) first_skip = reason;
    ++log.skipped_beams;
    log.skip_reasons.push_back(source + ": " + reason);
  };
  for (std::uint32_t index = 0; index < header.record_count; ++index) {
    const Framed framed = recordAt(bytes, at, index);
    if (!framed.defect.empty()) {  // the records before are whole: read up to the damage
      skip(framed.defect + "; the last " + std::to_string(bytes.size() - at) + " bytes and the " +
           std::to_string(header.record_count - index) + " record(s) the header declares from there skipped");
      break;
    }
    const std::span<const unsigned char> record = framed.record;
    ParsedRecord parsed = readRecord(record, at, index, source, options.sound_speed_m_s);
    if (!first_date_days) first_date_days = parsed.date_days;
    if (parsed.beam) {
      parsed.beam->time_s = (parsed.date_days - *first_date_days) * kSecondsPerDay;
      if (!log.beams.empty()) checkTimeOrder(parsed.beam->time_s, log.beams.back().time_s, at, index, source);
      log.beams.push_back(std::move(*parsed.beam));
    } else {
      skip(recordName(index) + " at byte " + std::to_string(at) + ": " + parsed.skip_reason);
    }
    at += record.size();  // past any bytes appended after the data
  }
  if (log.beams.empty()) {
    throw FileError(source + ": no beam in the " + std::to_string(header.record_count) +
                    " record(s) the header declares, expected mtHeadData records with data bytes" +
                    (first_skip.empty() ? "" : " (" + first_skip + ")"));
  }
  return log;
}

SonarLog readSeaNetV4Log(const std::string& path, const V4LogOptions& options) {
  return parseSeaNetV4Log(detail::readFileBytes(path), path, options);
}

}  // namespace sonarmap
