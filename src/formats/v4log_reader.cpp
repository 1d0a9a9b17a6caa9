/// @file v4log_reader.cpp
/// readSeaNetV4Log / parseSeaNetV4Log: Tritech SeaNet `.V4LOG` → SonarLog (see v4log_reader.hpp).

#include "sonarmap/formats/v4log_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../io/byte_io.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// SeaNet's AD span and low level count 1/255 of 80 dB (rock-drivers SeaNetTypes; tritech_micron).
constexpr double kAdScale_db = 80.0;

using detail::ByteCursor;

constexpr std::string_view kMagic = "SeaNetV4 Log File V1";
constexpr std::size_t kMagicBytes = 32;
/// Record length, OLE date, tx node, rx node, message type: the least a record can hold.
constexpr std::size_t kMinRecordBytes = 2 + 8 + 3;
constexpr std::uint8_t kMtHeadData = 2;
constexpr std::size_t kRecordDateAt = 2;  // offset of the OLE date in a record
constexpr std::uint32_t kBearingUnitsPerTurn = 6400;  // 1/16 gradian
constexpr double kAdIntervalUnit_s = 640e-9;
constexpr double kSecondsPerDay = 86400.0;
// HdCtrl bits (Tritech mtHeadCommand/mtHeadData).
constexpr std::uint16_t kHdCtrlAdc8On = 1U << 0;

std::uint16_t u16(ByteCursor& in, std::string_view what) {
  in.require(2, what);
  const std::uint16_t low = in.u8(what);
  return static_cast<std::uint16_t>(low | (in.u8(what) << 8));
}

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
  const std::size_t count_at = in.offset();
  header.record_count = in.u32("record count");
  if (header.data_offset < kV4LogFileHeaderBytes || header.data_offset > bytes.size()) {
    in.failAt(data_offset_at, "data offset is " + std::to_string(header.data_offset) + ", expected " +
                                  std::to_string(kV4LogFileHeaderBytes) + "…" + std::to_string(bytes.size()) +
                                  " (within the file)");
  }
  const std::size_t left = bytes.size() - header.data_offset;
  if (header.record_count > left / kMinRecordBytes) {
    in.failAt(count_at, "record count is " + std::to_string(header.record_count) + " but the " + std::to_string(left) +
                            " bytes after the data offset hold at most " + std::to_string(left / kMinRecordBytes) +
                            " records of " + std::to_string(kMinRecordBytes) + " bytes");
  }
  return header;
}

/// Unpacks the data bytes of one beam: copied (8-bit) or two 4-bit bins per byte, high nibble
/// first, scaled ×17 onto 0…255.
std::vector<std::uint8_t> unpackBins(std::span<const unsigned char> data, bool eight_bit) {
  if (eight_bit) return {data.begin(), data.end()};
  std::vector<std::uint8_t> bins;
  bins.reserve(2 * data.size());
  for (const unsigned char byte : data) {
    bins.push_back(static_cast<std::uint8_t>((byte >> 4) * 17));
    bins.push_back(static_cast<std::uint8_t>((byte & 0x0F) * 17));
  }
  return bins;
}

/// SeaNet bearing (1/16 gradian, clockwise) → beam.hpp's radians in [0, 2π), counter-clockwise.
double bearingRad(std::uint16_t bearing) {
  const std::uint32_t ccw = (kBearingUnitsPerTurn - bearing) % kBearingUnitsPerTurn;
  return 2.0 * std::numbers::pi * static_cast<double>(ccw) / kBearingUnitsPerTurn;
}

/// Reads the mtHeadData message of one record (cursor just after the message type) into a beam
/// without a time; std::nullopt when it has no data bytes.
std::optional<Beam> readHeadData(ByteCursor& in, std::span<const unsigned char> record, std::uint32_t index,
                                 double sound_speed_m_s) {
  in.u8("sequence");
  in.u8("node");
  u16(in, "packed size");
  in.u8("device type");
  in.u8("head status");
  in.u8("sweep code");
  const std::uint16_t head_control = u16(in, "HdCtrl");
  u16(in, "range scale");
  in.u32("TxN");
  in.u8("gain");
  u16(in, "slope");
  const std::uint8_t ad_span = in.u8("AD span");
  in.u8("AD low");
  u16(in, "heading offset");
  const std::size_t interval_at = in.offset();
  const std::uint16_t ad_interval = u16(in, "ADInterval");
  u16(in, "left limit");
  u16(in, "right limit");
  in.u8("step");
  const std::size_t bearing_at = in.offset();
  const std::uint16_t bearing = u16(in, "bearing");
  const std::size_t count_at = in.offset();
  const std::uint16_t data_bytes = u16(in, "data byte count");
  auto name = [index] { return recordName(index); };  // built only for a message
  if (ad_interval == 0) {
    in.failAt(interval_at, "ADInterval of " + name() + " is 0, expected > 0 (units of 640 ns; bin length 0 m)");
  }
  if (bearing >= kBearingUnitsPerTurn) {
    in.failAt(bearing_at, "bearing of " + name() + " is " + std::to_string(bearing) + ", expected 0…6399 (1/16 gradian)");
  }
  if (data_bytes > in.remaining()) {
    in.failAt(count_at, "data byte count of " + name() + " is " + std::to_string(data_bytes) + " but the record holds " +
                            std::to_string(in.remaining()) + " bytes after its " +
                            std::to_string(kV4LogHeadDataHeaderBytes) + "-byte header");
  }
  if (data_bytes == 0) return std::nullopt;
  Beam beam;
  beam.bearing_rad = bearingRad(bearing);
  beam.bin_length_m = ad_interval * kAdIntervalUnit_s * sound_speed_m_s / 2.0;
  beam.intensities = unpackBins(record.subspan(kV4LogHeadDataHeaderBytes, data_bytes), (head_control & kHdCtrlAdc8On) != 0);
  // ADspan counts 80/255 dB (SeaNet's 0…80 dB scale); 0 would be no span at all: leave it unknown.
  if (ad_span > 0) beam.intensity_span_db = ad_span * kAdScale_db / 255.0;
  return beam;
}

/// The bytes of record `index`, which starts at byte `at`: its length field is checked against
/// the smallest record and against the end of the file.
std::span<const unsigned char> recordAt(std::span<const unsigned char> bytes, std::size_t at, std::uint32_t index,
                                        const std::string& source) {
  ByteCursor in(bytes.subspan(at), source, at);
  const std::uint16_t length = u16(in, "record length");
  if (length < kMinRecordBytes) {
    in.failAt(at, "length of " + recordName(index) + " is " + std::to_string(length) + ", expected at least " +
                      std::to_string(kMinRecordBytes));
  }
  if (length > bytes.size() - at) {
    in.failAt(at, "length of " + recordName(index) + " is " + std::to_string(length) + " but the file ends " +
                      std::to_string(bytes.size() - at) + " bytes after the record's start");
  }
  return bytes.subspan(at, length);
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
  u16(in, "record length");
  ParsedRecord parsed;
  parsed.date_days = in.finiteF64("record date");
  in.u8("tx node");
  in.u8("rx node");
  const std::uint8_t type = in.u8("message type");
  if (type != kMtHeadData) {
    parsed.skip_reason = "message type " + std::to_string(type) + ", not mtHeadData (2)";
    return parsed;
  }
  if (record.size() < kV4LogHeadDataHeaderBytes) {
    in.failAt(at, "length of " + recordName(index) + " is " + std::to_string(record.size()) + ", expected at least " +
                      std::to_string(kV4LogHeadDataHeaderBytes) + " for mtHeadData");
  }
  parsed.beam = readHeadData(in, record, index, sound_speed_m_s);
  if (!parsed.beam) parsed.skip_reason = "mtHeadData with no data bytes";
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
  if (!(std::isfinite(options.sound_speed_m_s) && options.sound_speed_m_s > 0.0)) {
    throw ValueError("parseSeaNetV4Log: sound speed is " + std::to_string(options.sound_speed_m_s) +
                     " m/s, expected a positive finite number");
  }
  const FileHeader header = readFileHeader(bytes, source);
  SonarLog log;
  log.beams.reserve(header.record_count);
  std::size_t at = header.data_offset;
  std::optional<double> first_date_days;
  std::string first_skip;  // why the first record without a beam has none
  for (std::uint32_t index = 0; index < header.record_count; ++index) {
    const std::span<const unsigned char> record = recordAt(bytes, at, index, source);
    ParsedRecord parsed = readRecord(record, at, index, source, options.sound_speed_m_s);
    if (!first_date_days) first_date_days = parsed.date_days;
    if (parsed.beam) {
      parsed.beam->time_s = (parsed.date_days - *first_date_days) * kSecondsPerDay;
      if (!log.beams.empty()) checkTimeOrder(parsed.beam->time_s, log.beams.back().time_s, at, index, source);
      log.beams.push_back(std::move(*parsed.beam));
    } else {
      const std::string reason = recordName(index) + " at byte " + std::to_string(at) + ": " + parsed.skip_reason;
      if (first_skip.empty()) first_skip = reason;
      ++log.skipped_beams;
      log.skip_reasons.push_back(source + ": " + reason);
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
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (error || !in) throw FileError("cannot open '" + path + "' for reading");
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (in.gcount() != static_cast<std::streamsize>(bytes.size())) throw FileError(path + ": reading failed");
  return parseSeaNetV4Log(bytes, path, options);
}

}  // namespace sonarmap
