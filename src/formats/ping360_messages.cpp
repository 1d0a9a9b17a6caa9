/// @file ping360_messages.cpp
/// readPing360Messages: ping-protocol messages → Ping360 beams (see ping360_messages.hpp), with the
/// framing, payloads and beams of ping_protocol.hpp.

#include "ping360_messages.hpp"

#include <optional>

#include "frame_scanner.hpp"
#include "sonarmap/formats/ping_protocol.hpp"
#include "wire_protocols.hpp"

namespace sonarmap::detail {
namespace {

namespace pp = ping_protocol;

/// ping_protocol::frameAt as the frame scanner takes it.
FrameProbe probeMessage(std::span<const unsigned char> stream, std::size_t /*at*/) {
  pp::Framing framing = pp::frameAt(stream);
  const FrameProbe::Kind kind = framing.kind == pp::Framing::Kind::kMessage    ? FrameProbe::Kind::kFrame
                                : framing.kind == pp::Framing::Kind::kCutShort ? FrameProbe::Kind::kCutShort
                                                                               : FrameProbe::Kind::kNotAFrame;
  return {kind, framing.size, std::move(framing.reason)};
}

/// The ping of a device_data / auto_device_data message, or why there is none.
std::optional<pp::DeviceData> pingOf(const pp::Message& message, std::string& why) {
  if (message.id == pp::kDeviceData) return pp::DeviceData::parse(message.payload, &why);
  std::optional<pp::AutoDeviceData> automatic = pp::AutoDeviceData::parse(message.payload, &why);
  if (!automatic) return std::nullopt;
  return automatic->deviceData();
}

}  // namespace

FrameScan ping360FrameScan(const std::string& source, double sound_speed_m_s,
                           const std::function<std::string(std::size_t)>& where, Ping360Messages& out) {
  FrameScan scan;
  scan.start = "BR";
  scan.noun = "message";
  scan.where = where;
  scan.probe = probeMessage;
  scan.on_frame = [source, sound_speed_m_s, &where, &out](std::span<const unsigned char> frame, std::size_t at) {
    const pp::Message message = pp::messageOf(frame);
    const std::string name = "message at " + where(at);
    if (message.id == pp::kDeviceInformation) {
      if (const std::optional<pp::DeviceInformation> info = pp::DeviceInformation::parse(message.payload)) {
        out.device = info->text();
        return;
      }
    }
    if (message.id != pp::kDeviceData && message.id != pp::kAutoDeviceData) {
      addSkip(out.log, source, name + ": id " + std::to_string(message.id) +
                                   ", not device_data (2300) or auto_device_data (2301)");
      return;
    }
    std::string why;
    std::optional<Beam> beam;
    if (const std::optional<pp::DeviceData> ping = pingOf(message, why)) beam = pp::ping360Beam(*ping, sound_speed_m_s, &why);
    if (!beam) {
      addSkip(out.log, source, name + " (" + (message.id == pp::kDeviceData ? "device_data" : "auto_device_data") + "): " + why);
      return;
    }
    out.log.beams.push_back(std::move(*beam));
    out.beam_ends.push_back(at + frame.size());
  };
  return scan;
}

Ping360Messages readPing360Messages(std::span<const unsigned char> stream, const std::string& source,
                                    double sound_speed_m_s, const std::function<std::string(std::size_t)>& where) {
  Ping360Messages result;
  scanFrames(stream, ping360FrameScan(source, sound_speed_m_s, where, result), source, result.log);
  return result;
}

}  // namespace sonarmap::detail
