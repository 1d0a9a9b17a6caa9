/// @file seanet_capture.cpp
/// readSeaNetCapture / parseSeaNetCapture: raw Tritech SeaNet packets → SonarLog (see
/// seanet_capture.hpp).

#include "sonarmap/formats/seanet_capture.hpp"

#include <cstdint>
#include <utility>

#include "frame_scanner.hpp"
#include "reader_support.hpp"
#include "seanet_framing.hpp"
#include "seanet_head_data.hpp"
#include "sonarmap/formats/wire_stream.hpp"
#include "wire_protocols.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kMessageTypeAt = 10;
constexpr std::size_t kBodyAt = 11;  // the mtHeadData body: from the sequence byte
/// Bytes of an mtHeadData packet before its data bytes.
constexpr std::size_t kHeadDataHeaderBytes = kBodyAt + detail::kSeaNetHeadDataFieldBytes;

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
  scan.probe = detail::probeSeaNetPacket;
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
