#pragma once
/// @file wire_encoder.hpp
/// Beams as a sonar head sends them on the wire: a log (any format) turned into a raw capture that
/// `sonarmap map --format seanet|ping360` and `sonarmap live` read, e.g. to replay a log to a live
/// mapper over a serial line or UDP, or to measure its latency (`sonarmap convert LOG -o X.seanet`).
///
/// Layouts as the readers decode them (seanet_capture.hpp, ping360_reader.hpp), from the same
/// sources: Tritech SeaNet (rock-drivers `SeaNetTypesInternal.cpp`, tritech_micron `replies.py`),
/// Blue Robotics ping-protocol (`ping360.json`, ping-python `pingmessage.py`). All little-endian.
///
/// What the wire cannot carry is lost or rounded (the reader gives it back so):
///  - time: neither mtHeadData nor device_data has a clock (the reader numbers the beams instead);
///  - bearing: 1/16 gradian (SeaNet, ahead at 3200) or 1 gradian (Ping360, ahead at 0), clockwise
///    seen from above, as the readers take them (beam.hpp's bearing 0 is ahead);
///  - bin length: the sample interval, 640 ns (SeaNet ADInterval) or 25 ns (Ping360 sample period)
///    of two-way travel at CaptureOptions::sound_speed_m_s: 0.48 mm and 0.019 mm at 1500 m/s;
///  - the intensity span: SeaNet ADspan (dB × 255 / 80, rounded; 0 when unknown), none on Ping360.
#include <cstdint>
#include <vector>

#include "sonarmap/formats/capture_options.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// One mtHeadData packet per beam ('@', length in 4 hex digits and as uint16, source node 2,
/// destination 255, byte count 0, type 2, sequence 0x80, node 2, the head-data fields with 8-bit
/// bins (HdCtrl adc8on), LF), in beam order.
/// @throws ValueError for a beam with more than 65,000 bins, a bin length that is not finite and > 0
///         or whose sample interval is not 1…65535 × 640 ns, or an invalid sound speed.
std::vector<std::uint8_t> encodeSeaNetCapture(const std::vector<Beam>& beams, const CaptureOptions& options = {});

/// One ping-protocol device_data message (id 2300, source device 2, destination 0) per beam: mode
/// 1, gain 0, angle, transmit duration 32 µs, sample period, transmit frequency 750 kHz, number of
/// samples, the samples; a checksum (sum of the bytes before it, mod 65536) after each.
/// @throws ValueError for a beam with more than 65,000 bins, a bin length whose sample period is
///         not 1…65535 × 25 ns, or an invalid sound speed.
std::vector<std::uint8_t> encodePing360Stream(const std::vector<Beam>& beams, const CaptureOptions& options = {});

}  // namespace sonarmap
