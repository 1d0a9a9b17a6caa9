#pragma once
/// @file ping360_messages.hpp
/// Private to src/formats: Blue Robotics ping-protocol messages of a Ping360 in a byte stream →
/// beams, shared by the raw stream reader and the Ping Viewer log reader (ping360_reader.hpp).
///
/// Source: Blue Robotics `ping-protocol` (README "Format"; `src/definitions/ping360.json`:
/// device_data 2300, auto_device_data 2301) and `ping-python` (`brping/pingmessage.py`: header
/// "<BBHHBB", checksum = sum of the bytes before it & 0xFFFF). Written from them, not copied.
///
/// Message (little-endian): 'B' 'R'; uint16 payload length; uint16 message id; uint8 source
/// device id; uint8 destination device id; the payload; uint16 checksum. Payloads:
///   device_data (2300): u8 mode, u8 gain_setting, u16 angle (gradians 0–399), u16
///     transmit_duration (µs), u16 sample_period (25 ns), u16 transmit_frequency (kHz), u16
///     number_of_samples, u16 data length, u8 data[length].
///   auto_device_data (2301): as device_data up to transmit_frequency, then u16 start_angle,
///     u16 stop_angle, u8 num_steps, u8 delay (ms), u16 number_of_samples, u16 data length, data.

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

/// Frames the ping-protocol messages of `stream` (frame_scanner.hpp: garbage runs, a message cut
/// by the end, bad checksums, messages of 10,240 bytes or more (beyond Ping Viewer's parser) are
/// skipped and counted) and decodes device_data and
/// auto_device_data into beams: `bearing_rad` = 2π · angle / 400 (the Ping360 counts gradians
/// clockwise seen from above from its zero, ahead; beam.hpp the same),
/// `bin_length_m` = sample_period × 25 ns × sound_speed_m_s / 2, `intensities` = the data array
/// (bin 0 nearest), `gain_setting` = gain_setting (0 low, 1 normal, 2 high), no
/// `intensity_span_db` (the protocol gives none). device_information (common message 4) names the
/// device (Ping360Messages::device). Skipped and counted: other message ids; device data whose data length does not fill the payload, whose angle is ≥ 400, whose
/// sample period is 0 or that has no samples.
/// @param where  names an offset of `stream` in skip lines ("byte 120").
/// Never throws for any bytes (only std::bad_alloc).
Ping360Messages readPing360Messages(std::span<const unsigned char> stream, const std::string& source,
                                    double sound_speed_m_s, const std::function<std::string(std::size_t)>& where);

}  // namespace sonarmap::detail
