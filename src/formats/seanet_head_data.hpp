#pragma once
/// @file seanet_head_data.hpp
/// Private to src/formats: the one decoder of Tritech SeaNet's mtHeadData message (imaging head),
/// shared by the `.V4LOG` reader (v4log_reader.cpp: records of a SeaNet log) and the raw wire
/// capture reader (seanet_capture.cpp: packets as they come off the head's serial port).
///
/// Source: Tritech's SeaNet protocol as open drivers decode it: rock-drivers
/// `drivers-sonar_tritech` (`SeaNetTypesInternal.cpp`, SeaNetPacket::decodeHeadData and
/// isValidPacket), mcgill-robotics `tritech_micron` (`sonar.py`, `replies.py`), orjan1992/pySonar
/// (`readLogFile.py`); ../shared/docs/formats.md. Checked on `seanet_sector_target.V4LOG`.
///
/// The body decoded here starts at the byte after the message type (offsets from there,
/// little-endian): 0 sequence, 1 node, 2–3 packed size, 4 device type, 5 head status, 6 sweep code,
/// 7–8 HdCtrl, 9–10 range scale (dm), 11–14 TxN, 15 gain, 16–17 slope, 18 ADspan, 19 ADlow,
/// 20–21 heading offset, 22–23 ADInterval (640 ns), 24–25 left limit, 26–27 right limit (1/16
/// gradian), 28 step, 29–30 bearing (1/16 gradian, clockwise seen from above), 31–32 data byte
/// count, then the data bytes. In a wire packet the body starts at byte 11, in a V4LOG record at 13.
/// A profiling head (SeaKing DFP) lays its fields out differently after the slope: not decoded.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap::detail {

/// Bytes of the mtHeadData fields before the data bytes, from the sequence byte on.
inline constexpr std::size_t kSeaNetHeadDataFieldBytes = 33;
/// Message type of mtHeadData.
inline constexpr std::uint8_t kSeaNetMtHeadData = 2;

/// How messages name the message being decoded, e.g. {"record 3", "record", 46}.
struct SeaNetMessageName {
  std::string name;              ///< "record 3", "packet at byte 120"
  std::string_view container;    ///< "record", "packet"
  std::size_t header_bytes = 0;  ///< bytes of the container before the data bytes
};

/// What one mtHeadData body gives: a beam, a message without data bytes, or a field out of range.
struct SeaNetHeadData {
  std::optional<Beam> beam;        ///< without its time; set when neither reason below is
  std::string skip_reason;         ///< a well-formed message without data bytes
  std::string defect;              ///< a field out of range or a count past the body's end
  std::size_t defect_at = 0;       ///< offset of that field, as reported (body_at based)
  std::size_t trailing_bytes = 0;  ///< bytes of `body` after the data bytes (beam only)
};

/// Decodes one mtHeadData body (layout in the file comment) into a beam:
///   - `bearing_rad` = 2π · ((bearing − 3200) mod 6400) / 6400: SeaNet counts 1/16 gradian
///     clockwise seen from above with "ahead" at 3200, beam.hpp clockwise from ahead (see
///     v4log_reader.hpp for the evidence). HdCtrl bit 3 `invert` (head mounted upside down) set:
///     2π · ((3200 − bearing) mod 6400) / 6400, the count reversed about ahead. The heading offset
///     is not applied.
///   - `bin_length_m` = ADInterval × 640 ns × sound_speed_m_s / 2.
///   - `intensities`: 8-bit bins (HdCtrl bit 0 `adc8on`) copied; else two 4-bit bins per byte,
///     high nibble first, ×17 onto 0…255.
///   - `intensity_span_db` = ADspan × 80 / 255 dB, unset when ADspan is 0.
///   - `gain_setting` = the gain byte.
/// Checks, in this order (the first failing one is the result's `defect`): the body holds the
/// 33 field bytes; ADInterval > 0; bearing < 6400; the data byte count fits in the body. A
/// message with no data bytes gives `skip_reason` "mtHeadData with no data bytes".
/// @param body     the bytes from the sequence byte to the end of the message.
/// @param body_at  offset of body[0] as reported in messages (a file offset).
/// @param sound_speed_m_s  checked by the caller (positive, finite).
/// Never throws for any bytes (only std::bad_alloc).
SeaNetHeadData decodeSeaNetHeadData(std::span<const unsigned char> body, std::size_t body_at,
                                    const SeaNetMessageName& name, double sound_speed_m_s);

}  // namespace sonarmap::detail
