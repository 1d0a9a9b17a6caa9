#pragma once
/// @file v4log_fixture.hpp
/// Test helper: builds synthetic Tritech SeaNet `.V4LOG` bytes (layout as parseSeaNetV4Log reads
/// it, verified on the sample log): an 80-byte file header, then records.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sonarmap::test {

// Byte offsets inside the file header and inside an mtHeadData record.
constexpr std::size_t kV4DataOffsetAt = 40;
constexpr std::size_t kV4RecordCountAt = 44;
constexpr std::size_t kV4DateAt = 2;
constexpr std::size_t kV4AdIntervalAt = 35;
constexpr std::size_t kV4BearingAt = 42;
constexpr std::size_t kV4DataBytesAt = 44;

constexpr double kV4FirstDate_days = 38494.620369097225;  // the sample's first record, 2005-05-22

inline void putU16(std::string& out, std::uint16_t v) {
  out.push_back(static_cast<char>(v & 0xFF));
  out.push_back(static_cast<char>(v >> 8));
}
inline void putU32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}
inline void putF64(std::string& out, double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xFF));
}
inline void setU16(std::string& bytes, std::size_t at, std::uint16_t v) {
  bytes[at] = static_cast<char>(v & 0xFF);
  bytes[at + 1] = static_cast<char>(v >> 8);
}
inline void setU32(std::string& bytes, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<char>((v >> (8 * i)) & 0xFF);
}

/// The mtHeadData fields of an imaging head from the packed size to the data bytes, then
/// `extra_bytes` bytes: what a V4LOG record and a wire packet both hold after their node byte
/// (src/formats/seanet_head_data.hpp). Defaults are the sample's settings.
struct HeadDataFields {
  std::uint16_t head_control = 0x230D;  // adc8on, scanright, invert, raw, hasmot, replyASL
  std::uint16_t ad_interval = 33;       // 640 ns units
  std::uint8_t ad_span = 149;
  std::uint16_t bearing = 3200;         // 1/16 gradian, clockwise
  std::vector<std::uint8_t> data = {10, 20, 30};
  std::optional<std::uint16_t> data_count;  // the data byte count field, when not data.size()
  std::size_t extra_bytes = 0;              // counted in the packed size (a wire packet's)
};

inline std::string headDataFields(const HeadDataFields& f) {
  std::string out;
  putU16(out, static_cast<std::uint16_t>(f.data.size() + f.extra_bytes + 31));  // packed size
  out += {'\x02', '\x10', '\x00'};  // device type, head status, sweep code
  putU16(out, f.head_control);
  putU16(out, 100);         // range scale: 10 m
  putU32(out, 0x02999999);  // TxN
  out += '\x58';            // gain
  putU16(out, 90);          // slope
  out += static_cast<char>(f.ad_span);
  out += '\x0E';   // AD low
  putU16(out, 0);  // heading offset
  putU16(out, f.ad_interval);
  putU16(out, 2400);  // left limit
  putU16(out, 4000);  // right limit
  out += '\x40';      // step 64
  putU16(out, f.bearing);
  putU16(out, f.data_count.value_or(static_cast<std::uint16_t>(f.data.size())));
  out.append(f.data.begin(), f.data.end());
  return out + std::string(f.extra_bytes, '\x55');
}

/// One record of a synthetic log; defaults are the sample's settings.
struct V4Record {
  double date_days = kV4FirstDate_days;
  std::uint8_t type = 2;                // mtHeadData
  std::uint16_t head_control = 0x230D;  // adc8on, scanright, invert, raw, hasmot, replyASL
  std::uint16_t ad_interval = 33;
  std::uint16_t bearing = 3200;
  std::vector<std::uint8_t> data = {10, 20, 30};
  std::size_t appended_bytes = 0;  // bytes after the data (an appended message)
};

inline std::string v4RecordBytes(const V4Record& r) {
  std::string out;
  putU16(out, 0);  // length, set below
  putF64(out, r.date_days);
  out += {'\x02', '\xFF', static_cast<char>(r.type), '\x80', '\x02'};  // tx, rx, type, sequence, node
  if (r.type != 2) {
    out += std::string(12, '\x07');  // some other message body
  } else {
    HeadDataFields fields;
    fields.head_control = r.head_control;
    fields.ad_interval = r.ad_interval;
    fields.bearing = r.bearing;
    fields.data = r.data;
    out += headDataFields(fields) + std::string(r.appended_bytes, '\x55');
  }
  setU16(out, 0, static_cast<std::uint16_t>(out.size()));
  return out;
}

/// An 80-byte header (data offset 80) and the records.
inline std::string v4log(const std::vector<V4Record>& records) {
  std::string out = "SeaNetV4 Log File V1";
  out += std::string(11, ' ') + '\x1A';
  for (const std::uint32_t v : {16U, 80U, 80U, static_cast<std::uint32_t>(records.size()), 0U, 0U, 0U, 0U}) {
    putU32(out, v);
  }
  putF64(out, kV4FirstDate_days);
  putF64(out, kV4FirstDate_days + 1e-3);
  for (const V4Record& r : records) out += v4RecordBytes(r);
  return out;
}

}  // namespace sonarmap::test
