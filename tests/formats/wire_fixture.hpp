#pragma once
/// @file wire_fixture.hpp
/// Test helper: builds raw sonar wire captures byte by byte from the protocols' specifications
/// (not with the readers' code): Tritech SeaNet packets (seanet_capture.hpp), Blue Robotics
/// ping-protocol messages of a Ping360 and Ping Viewer logs (ping360_reader.hpp).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "v4log_fixture.hpp"

namespace sonarmap::test {

// ---- Tritech SeaNet ------------------------------------------------------------------------------

/// '@', the length as 4 hex digits and as uint16, `message` (from the source node byte on), LF.
/// The length counts from its binary copy to the byte before the LF: message size + 2.
inline std::string seanetFrame(const std::string& message) {
  const std::size_t length = message.size() + 2;
  char hex[5];
  std::snprintf(hex, sizeof hex, "%04zX", length);
  std::string out = "@";
  out += hex;
  putU16(out, static_cast<std::uint16_t>(length));
  return out + message + '\n';
}

/// One mtHeadData packet of an imaging head; defaults are the shared V4LOG's settings.
using SeaNetHeadPacket = HeadDataFields;

/// Bytes 7… of an mtHeadData packet up to its LF: the wire layout of seanet_capture.hpp.
inline std::string seanetHeadDataMessage(const SeaNetHeadPacket& p) {
  const std::string header = {'\x02', '\xFF', '\x00', '\x02', '\x80', '\x02'};  // source, destination, count, type, sequence, node
  return header + headDataFields(p);
}

inline std::string seanetHeadData(const SeaNetHeadPacket& p) { return seanetFrame(seanetHeadDataMessage(p)); }

/// A packet of another message type (`type`: 4 mtAlive, 1 mtVersionData, …) with `body_bytes`
/// bytes after the node byte; its byte count is the length − 5 (tritech_micron `replies.py`).
inline std::string seanetOther(std::uint8_t type, std::size_t body_bytes) {
  std::string message = {'\x02', '\xFF', static_cast<char>(body_bytes + 3), static_cast<char>(type), '\x80', '\x02'};
  return seanetFrame(message + std::string(body_bytes, '\x07'));
}

/// The mtHeadData message of a V4LOG record (length, OLE date, tx, rx, type, sequence, node, …,
/// data; v4log_reader.hpp) re-framed as the wire packet the head sent: the byte count (0)
/// inserted after the two node bytes, bytes after the data dropped.
inline std::string seanetPacketOfV4Record(std::string_view record) {
  const std::size_t data_bytes = static_cast<unsigned char>(record[44]) | (static_cast<unsigned char>(record[45]) << 8);
  std::string message(record.substr(10, 2));
  message += '\x00';
  message += record.substr(12, 46 + data_bytes - 12);
  return seanetFrame(message);
}

// ---- Blue Robotics ping-protocol -----------------------------------------------------------------

/// 'B' 'R', payload length, message id, source and destination device ids, payload, checksum
/// (the sum of every byte before it, mod 65536), little-endian.
inline std::string pingMessage(std::uint16_t id, const std::string& payload) {
  std::string out = "BR";
  putU16(out, static_cast<std::uint16_t>(payload.size()));
  putU16(out, id);
  out += {'\x02', '\x00'};  // source device 2, destination 0
  out += payload;
  unsigned sum = 0;
  for (const char c : out) sum += static_cast<unsigned char>(c);
  putU16(out, static_cast<std::uint16_t>(sum & 0xFFFF));
  return out;
}

/// One device_data (2300) or auto_device_data (2301) message of a Ping360.
struct Ping360Data {
  bool auto_device_data = false;
  std::uint16_t angle = 0;            // gradians, clockwise
  std::uint16_t sample_period = 80;   // 25 ns units: 2 µs, 1.5 mm at 1500 m/s
  std::uint16_t transmit_frequency = 750;
  std::vector<std::uint8_t> data = {1, 2, 250};
  std::optional<std::uint16_t> data_length;  // the length field, when not data.size()
};

inline std::string ping360Payload(const Ping360Data& d) {
  std::string out = {'\x01', '\x00'};  // mode 1, gain setting 0
  putU16(out, d.angle);
  putU16(out, 32);  // transmit duration, µs
  putU16(out, d.sample_period);
  putU16(out, d.transmit_frequency);
  if (d.auto_device_data) {
    putU16(out, 0);    // start angle
    putU16(out, 399);  // stop angle
    out += {'\x01', '\x00'};  // num_steps, delay
  }
  putU16(out, static_cast<std::uint16_t>(d.data.size()));  // number of samples
  putU16(out, d.data_length.value_or(static_cast<std::uint16_t>(d.data.size())));
  out.append(d.data.begin(), d.data.end());
  return out;
}

inline std::string ping360Message(const Ping360Data& d) {
  return pingMessage(d.auto_device_data ? 2301 : 2300, ping360Payload(d));
}

// ---- Ping Viewer sensor log ----------------------------------------------------------------------

inline void putBigU32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((v >> shift) & 0xFF));
}

/// A QDataStream QString as Ping Viewer logs hold it: big-endian byte length, then UTF-8 or
/// UTF-16BE bytes (ASCII text here).
inline std::string qtString(std::string_view text, bool utf16) {
  std::string bytes;
  for (const char c : text) {
    if (utf16) bytes += '\0';
    bytes += c;
  }
  std::string out;
  putBigU32(out, static_cast<std::uint32_t>(bytes.size()));
  return out + bytes;
}

inline std::string qtByteArray(const std::string& data) {
  std::string out;
  putBigU32(out, static_cast<std::uint32_t>(data.size()));
  return out + data;
}

/// The log header (LogSensorStruct): header string, version, five build strings, sensor family
/// (1: ping) and type (2: Ping360).
inline std::string pingViewerHeader(bool utf16 = false, std::uint32_t version = 1) {
  std::string out = qtString("PingViewer sensor log file", utf16);
  putBigU32(out, version);
  for (const char* text : {"1ed4508", "2025-08-07", "v2.4.1", "Debian GNU/Linux 12", "12"}) out += qtString(text, utf16);
  putBigU32(out, 1);
  putBigU32(out, 2);
  return out;
}

/// A whole log: the header and one record per (time "hh:mm:ss.zzz", bytes received) pair.
inline std::string pingViewerLog(const std::vector<std::pair<std::string, std::string>>& records, bool utf16 = false) {
  std::string out = pingViewerHeader(utf16);
  for (const auto& [time, data] : records) out += qtString(time, utf16) + qtByteArray(data);
  return out;
}

}  // namespace sonarmap::test
