#pragma once
/// @file seanet_capture.hpp
/// Reader for raw Tritech SeaNet wire captures: the bytes a Micron or SeaKing imaging head sends
/// on its serial (RS-232/RS-485) or Ethernet port, logged as they come (`cat /dev/ttyUSB0 > f`).
/// Default extension `.seanet` (log_reader.hpp).
///
/// Source: Tritech's SeaNet protocol as open drivers decode it: rock-drivers
/// `drivers-sonar_tritech` (`SeaNetTypesInternal.cpp`: SeaNetPacket::isValidPacket,
/// decodeHeadData), mcgill-robotics `tritech_micron` (`replies.py`: Reply.parse; `sonar.py`);
/// ../shared/docs/formats.md, "Tritech SeaNet wire protocol". Written from those descriptions,
/// not copied.
///
/// Packet (little-endian): byte 0 '@' (0x40); bytes 1–4 the packet length as 4 ASCII hex digits;
/// bytes 5–6 the same length as uint16 (it counts from byte 5 to the byte before the final LF:
/// the packet is length + 6 bytes); 7 source node; 8 destination node; 9 byte count (0 in
/// mtHeadData); 10 message type (1 mtVersionData, 2 mtHeadData, 4 mtAlive, …); 11 sequence;
/// 12 node; the message; the last byte LF (0x0A). An imaging head's mtHeadData holds its head
/// settings from byte 13 and the bins from byte 44, data bytes + 45 bytes in all (the fields:
/// src/formats/seanet_head_data.hpp).

#include <span>
#include <string>

#include "sonarmap/formats/capture_options.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Reads a raw SeaNet capture (see parseSeaNetCapture).
/// @throws FileError when the file cannot be opened or read, or parseSeaNetCapture rejects it.
/// @throws ValueError for options out of range (see parseSeaNetCapture).
SonarLog readSeaNetCapture(const std::string& path, const CaptureOptions& options = {});

/// Parses the bytes of a raw SeaNet capture. Every mtHeadData packet of an imaging head becomes
/// one Beam, converted exactly as the `.V4LOG` reader converts its records (v4log_reader.hpp):
/// `bearing_rad` = 2π · ((bearing − 3200) mod 6400) / 6400 (SeaNet's 1/16 gradian clockwise,
/// ahead at 3200; reversed about ahead when HdCtrl `invert` is set), `bin_length_m` = ADInterval × 640 ns × sound speed / 2,
/// 8-bit bins copied or 4-bit bins unpacked high nibble first ×17, `intensity_span_db` =
/// ADspan × 80 / 255 dB. `time_s` = beam index × options.beam_interval_s (the protocol has no
/// clock).
///
/// A packet is recognised by its '@', equal hex and binary lengths (≥ 8: 14 bytes at least) and
/// the LF where the length says the packet ends. Skipped and counted (`skipped_beams`, one line
/// each in `skip_reasons` naming the byte offset and why): packets of other message types
/// (mtAlive, mtVersionData, …); mtHeadData packets whose fields are out of range (ADInterval 0,
/// bearing ≥ 6400), without data bytes, or whose size is not data bytes + 45 (a profiling head's
/// layout, a multi-packet reply); each run of bytes outside any packet (line noise, a packet
/// broken by a bad byte); a final packet cut short by the end of the capture (a pulled cable).
/// Bearings are taken as the head reports them: HdCtrl `invert` and the heading offset are not
/// applied.
///
/// @param bytes   the whole capture.
/// @param source  name used in messages (the path).
/// @return        beams in capture order.
/// @throws FileError  naming `source` when the capture holds no beam at all (empty, no packet,
///   or no usable mtHeadData packet), with the first reason a packet or byte run was skipped.
/// @throws ValueError when `options.sound_speed_m_s` is not positive and finite, or
///   `options.beam_interval_s` is negative or not finite.
SonarLog parseSeaNetCapture(std::span<const unsigned char> bytes, const std::string& source,
                            const CaptureOptions& options = {});

}  // namespace sonarmap
