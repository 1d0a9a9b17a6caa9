#pragma once
/// @file vehicle_log_fixture.hpp
/// Test helper: BlueROV2 logs built byte by byte from their specifications (not with the readers'
/// code): MAVLink 1 and 2 frames (mavlink.io/en/guide/serialization.html: header, payload with
/// MAVLink 2's trailing zeros truncated, CRC-16/MCRF4XX over the bytes after the magic plus the
/// message's CRC_EXTRA, optional 13-byte signature), telemetry logs (a big-endian uint64 of
/// microseconds since 1970 before each frame, pymavlink's mavlogfile), and ArduPilot dataflash
/// records (0xA3 0x95, type, packed little-endian fields; FMT = type 128 defining the others:
/// ArduPilot's AP_Logger/LogStructure.h).

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace sonarmap::test {

template <typename T>
void putLittle(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // the test machines are little-endian, as MAVLink and dataflash
  out.append(bytes, sizeof(T));
}

/// CRC-16/MCRF4XX (poly 0x1021 reflected, init 0xFFFF, no final xor), bit by bit from its
/// definition (its catalogue check value: "123456789" → 0x6F91).
inline std::uint16_t mcrf4xx(std::string_view bytes, std::uint16_t crc = 0xFFFF) {
  for (unsigned char byte : bytes) {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1) ? static_cast<std::uint16_t>((crc >> 1) ^ 0x8408) : static_cast<std::uint16_t>(crc >> 1);
  }
  return crc;
}

struct MavlinkFrameOptions {
  bool v2 = true;
  std::uint8_t system = 1, component = 1, sequence = 0;
  bool sign = false;    ///< MAVLink 2: incompat flag 0x01 and 13 signature bytes (not checked by readers of logs)
  bool corrupt = false;  ///< flip the checksum
};

/// One MAVLink frame of message `id` with `payload` (its full length; MAVLink 2 drops trailing zeros).
inline std::string mavlinkFrame(std::uint32_t id, std::uint8_t crc_extra, std::string payload,
                                const MavlinkFrameOptions& o = {}) {
  if (o.v2) {
    while (payload.size() > 1 && payload.back() == '\0') payload.pop_back();
  }
  std::string body;  // from the length byte to the payload's end: what the CRC covers
  body.push_back(static_cast<char>(payload.size()));
  if (o.v2) {
    body.push_back(static_cast<char>(o.sign ? 0x01 : 0x00));
    body.push_back('\0');
  }
  body.push_back(static_cast<char>(o.sequence));
  body.push_back(static_cast<char>(o.system));
  body.push_back(static_cast<char>(o.component));
  body.push_back(static_cast<char>(id & 0xFF));
  if (o.v2) {
    body.push_back(static_cast<char>((id >> 8) & 0xFF));
    body.push_back(static_cast<char>((id >> 16) & 0xFF));
  }
  body += payload;
  std::uint16_t crc = mcrf4xx(std::string(1, static_cast<char>(crc_extra)), mcrf4xx(body));
  if (o.corrupt) crc ^= 0x5A5A;
  std::string frame(1, static_cast<char>(o.v2 ? 0xFD : 0xFE));
  frame += body;
  putLittle(frame, crc);
  if (o.sign) frame += std::string(13, '\x42');
  return frame;
}

/// A telemetry log record: the reception time, big-endian µs since 1970, then the frame.
inline std::string tlogRecord(std::uint64_t received_us, const std::string& frame) {
  std::string out;
  for (int shift = 56; shift >= 0; shift -= 8) out.push_back(static_cast<char>((received_us >> shift) & 0xFF));
  return out + frame;
}

// common.xml messages (id, CRC_EXTRA; fields by size, largest first)
inline std::string attitudeFrame(std::uint32_t boot_ms, float roll, float pitch, float yaw, const MavlinkFrameOptions& o = {}) {
  std::string p;
  putLittle(p, boot_ms);
  for (float v : {roll, pitch, yaw, 0.0f, 0.0f, 0.0f}) putLittle(p, v);
  return mavlinkFrame(30, 39, p, o);
}
inline std::string localPositionNedFrame(std::uint32_t boot_ms, float x, float y, float z, const MavlinkFrameOptions& o = {}) {
  std::string p;
  putLittle(p, boot_ms);
  for (float v : {x, y, z, 0.0f, 0.0f, 0.0f}) putLittle(p, v);
  return mavlinkFrame(32, 185, p, o);
}
inline std::string globalPositionIntFrame(std::uint32_t boot_ms, std::int32_t relative_alt_mm, const MavlinkFrameOptions& o = {}) {
  std::string p;
  putLittle(p, boot_ms);
  for (std::int32_t v : {0, 0, relative_alt_mm, relative_alt_mm}) putLittle(p, v);  // lat, lon, alt, relative_alt
  for (int i = 0; i < 3; ++i) putLittle(p, std::int16_t{0});  // vx, vy, vz
  putLittle(p, std::uint16_t{0});  // hdg
  return mavlinkFrame(33, 104, p, o);
}
inline std::string scaledPressure2Frame(std::uint32_t boot_ms, float press_abs_hpa, const MavlinkFrameOptions& o = {}) {
  std::string p;
  putLittle(p, boot_ms);
  putLittle(p, press_abs_hpa);
  putLittle(p, 0.0f);               // press_diff
  putLittle(p, std::int16_t{1500});  // temperature, cdegC
  putLittle(p, std::int16_t{0});     // temperature_press_diff (extension)
  return mavlinkFrame(137, 195, p, o);
}
inline std::string heartbeatFrame(const MavlinkFrameOptions& o = {}) {
  std::string p;
  putLittle(p, std::uint32_t{0});  // custom_mode
  p += std::string("\x0C\x03\x51\x04\x03", 5);  // type (submarine), autopilot, base_mode, system_status, version
  return mavlinkFrame(0, 50, p, o);
}

// ---- ArduPilot dataflash ---------------------------------------------------------------------

inline std::size_t dataflashFieldBytes(char c) {
  switch (c) {
    case 'b': case 'B': case 'M': return 1;
    case 'h': case 'H': case 'c': case 'C': return 2;
    case 'i': case 'I': case 'f': case 'e': case 'E': case 'L': case 'n': return 4;
    case 'd': case 'q': case 'Q': return 8;
    case 'N': return 16;
    default: return 64;  // Z, a
  }
}

/// A FMT record (89 bytes) defining `type` as `name` with `format` and comma-separated `columns`.
inline std::string dataflashFmt(std::uint8_t type, std::string_view name, std::string_view format, std::string_view columns) {
  std::size_t length = 3;
  for (char c : format) length += dataflashFieldBytes(c);
  std::string out = "\xA3\x95\x80";
  out.push_back(static_cast<char>(type));
  out.push_back(static_cast<char>(length));
  const auto fixed = [&out](std::string_view text, std::size_t size) {
    std::string field(text.substr(0, size));
    field.resize(size, '\0');
    out += field;
  };
  fixed(name, 4);
  fixed(format, 16);
  fixed(columns, 64);
  return out;
}

/// A record of `type` whose packed fields are `fields`.
inline std::string dataflashRecord(std::uint8_t type, const std::string& fields) {
  std::string out = "\xA3\x95";
  out.push_back(static_cast<char>(type));
  return out + fields;
}

}  // namespace sonarmap::test
