/// @file seanet_capture.cpp
/// readSeaNetCapture / parseSeaNetCapture: raw Tritech SeaNet packets → SonarLog (see
/// seanet_capture.hpp).

#include "sonarmap/formats/seanet_capture.hpp"

#include <cctype>
#include <cstdint>
#include <utility>

#include "frame_scanner.hpp"
#include "reader_support.hpp"
#include "seanet_head_data.hpp"
#include "sonarmap/formats/wire_stream.hpp"
#include "wire_protocols.hpp"

namespace sonarmap {
namespace {

using detail::FrameProbe;

constexpr unsigned char kPacketEnd = 0x0A;  // LF
/// '@', the 4 hex digits and the final LF are outside the packet length.
constexpr std::size_t kUncountedBytes = 6;
/// The smallest packet: header up to the node byte (13 bytes) and the LF (rock: at least 14).
constexpr std::size_t kMinPacketBytes = 14;
constexpr std::size_t kHexLengthAt = 1;
constexpr std::size_t kBinaryLengthAt = 5;
constexpr std::size_t kMessageTypeAt = 10;
constexpr std::size_t kBodyAt = 11;  // the mtHeadData body: from the sequence byte
/// Bytes of an mtHeadData packet before its data bytes.
constexpr std::size_t kHeadDataHeaderBytes = kBodyAt + detail::kSeaNetHeadDataFieldBytes;

FrameProbe cutShort(std::size_t available, const std::string& what) {
  return {FrameProbe::Kind::kCutShort, 0,
          what + ", the capture ends " + std::to_string(available) + " bytes after its start"};
}

/// SeaNet framing of `bytes` (from an '@' at stream offset `at` to the last byte received): hex
/// and binary lengths equal, at least the smallest packet, LF at the end.
FrameProbe probePacket(std::span<const unsigned char> bytes, std::size_t at) {
  const std::size_t available = bytes.size();
  std::size_t hex_length = 0;
  for (std::size_t i = kHexLengthAt; i < kHexLengthAt + 4; ++i) {
    if (i >= available) return cutShort(available, "header");
    const unsigned char digit = bytes[i];
    if (!std::isxdigit(digit)) return {FrameProbe::Kind::kNotAFrame, 0, "length is not 4 ASCII hex digits"};
    hex_length = 16 * hex_length + static_cast<std::size_t>(std::isdigit(digit) ? digit - '0' : std::tolower(digit) - 'a' + 10);
  }
  if (available < kBinaryLengthAt + 2) return cutShort(available, "header");
  const std::size_t length = bytes[kBinaryLengthAt] | (bytes[kBinaryLengthAt + 1] << 8);
  if (length != hex_length) {
    return {FrameProbe::Kind::kNotAFrame, 0,
            "hex length " + std::to_string(hex_length) + " and binary length " + std::to_string(length) + " differ"};
  }
  const std::size_t size = length + kUncountedBytes;
  if (size < kMinPacketBytes) {
    return {FrameProbe::Kind::kNotAFrame, 0,
            "length " + std::to_string(length) + ", expected at least " + std::to_string(kMinPacketBytes - kUncountedBytes)};
  }
  if (size > available) return cutShort(available, "declares " + std::to_string(size) + " bytes");
  if (bytes[size - 1] != kPacketEnd) {
    return {FrameProbe::Kind::kNotAFrame, 0, "no LF at its end (byte " + std::to_string(at + size - 1) + ")"};
  }
  return {FrameProbe::Kind::kFrame, size, {}};
}

/// One whole packet: a beam, or a skipped item saying why not.
void readPacket(std::span<const unsigned char> packet, std::size_t at, const std::string& source,
                double sound_speed_m_s, SonarLog& log) {
  const std::string name = "packet at byte " + std::to_string(at);
  const std::uint8_t type = packet[kMessageTypeAt];
  if (type != detail::kSeaNetMtHeadData) {
    detail::addSkip(log, source, name + ": message type " + std::to_string(type) + ", not mtHeadData (2)");
    return;
  }
  const std::span<const unsigned char> body = packet.subspan(kBodyAt, packet.size() - kBodyAt - 1);  // before the LF
  detail::SeaNetHeadData decoded =
      detail::decodeSeaNetHeadData(body, at + kBodyAt, {name, "packet", kHeadDataHeaderBytes}, sound_speed_m_s);
  if (!decoded.defect.empty()) {
    detail::addSkip(log, source, "byte " + std::to_string(decoded.defect_at) + ": " + decoded.defect);
  } else if (!decoded.beam) {
    detail::addSkip(log, source, name + ": " + decoded.skip_reason);
  } else if (decoded.trailing_bytes != 0) {
    detail::addSkip(log, source, name + ": " + std::to_string(decoded.trailing_bytes) +
                                     " bytes between its data bytes and the LF, expected none (an imaging head's "
                                     "packet is data bytes + 45 bytes)");
  } else {
    log.beams.push_back(std::move(*decoded.beam));
  }
}

}  // namespace

namespace detail {

FrameScan seaNetFrameScan(const std::string& source, double sound_speed_m_s, SonarLog& log) {
  FrameScan scan;
  scan.start = "@";
  scan.noun = "packet";
  scan.probe = probePacket;
  scan.on_frame = [source, sound_speed_m_s, &log](std::span<const unsigned char> packet, std::size_t at) {
    readPacket(packet, at, source, sound_speed_m_s, log);
  };
  return scan;
}

}  // namespace detail

SonarLog parseSeaNetCapture(std::span<const unsigned char> bytes, const std::string& source,
                            const CaptureOptions& options) {
  return detail::parseClocklessCapture(LogFormat::kSeaNet, bytes, source, options,
                                       "SeaNet mtHeadData packets ('@', hex length, ..., LF)");
}

SonarLog readSeaNetCapture(const std::string& path, const CaptureOptions& options) {
  return parseSeaNetCapture(detail::readFileBytes(path), path, options);
}

}  // namespace sonarmap
