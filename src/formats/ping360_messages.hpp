#pragma once
/// @file ping360_messages.hpp
/// Private to src/formats: Blue Robotics ping-protocol messages of a Ping360 in a byte stream →
/// beams, shared by the raw stream reader and the Ping Viewer log reader (ping360_reader.hpp). The
/// framing, payloads and the beam of a ping are ping_protocol.hpp's (its sources: ping-protocol's
/// json, ping-python, Ping Viewer).

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap::detail {

/// The beams of a stream and where each one's message ends.
struct Ping360Messages {
  SonarLog log;                        ///< beams without times, skipped items
  std::vector<std::size_t> beam_ends;  ///< per beam: offset one past its message in the stream
  /// The last device_information message's device and firmware ("Ping360 (firmware 3.1.1)"), when
  /// there is one.
  std::string device;
};

/// Frames the ping-protocol messages of `stream` (ping_protocol::frameAt through
/// frame_scanner.hpp: garbage runs, a message cut by the end, bad checksums, messages of 10,240
/// bytes or more (beyond Ping Viewer's parser) are skipped and counted) and decodes device_data
/// and auto_device_data into beams (ping_protocol::ping360Beam: bearing 2π · angle / 400, bin
/// length from the sample period, intensities, gain setting, pulse length).
/// device_information (common message 4) names the device (Ping360Messages::device). Skipped and
/// counted: other message ids (a device_information whose payload is not 6 bytes among them);
/// device data whose data length does not fill the payload, whose angle is ≥ 400, whose sample
/// period is 0 or that has no samples.
/// @param where  names an offset of `stream` in skip lines ("byte 120").
/// Never throws for any bytes (only std::bad_alloc).
Ping360Messages readPing360Messages(std::span<const unsigned char> stream, const std::string& source,
                                    double sound_speed_m_s, const std::function<std::string(std::size_t)>& where);

}  // namespace sonarmap::detail
