#pragma once
/// @file v4log_reader.hpp
/// Reader for Tritech SeaNet V4 logs (`.V4LOG`) of mechanically scanned imaging sonars.
///
/// Layout (little-endian), as checked on `seanet_sector_target.V4LOG` (see
/// ../shared/docs/formats.md, "Tritech SeaNet V4 log"; field names from Tritech's mtHeadData
/// message as decoded by orjan1992/pySonar `readLogFile.py`, rock-drivers/drivers-sonar_tritech
/// `SeaNetTypesInternal.cpp` and mcgill-robotics tritech_micron `sonar.py`):
///   - file header, 80 bytes: 32-byte magic starting `SeaNetV4 Log File V1`, uint32 version,
///     header offset, data offset, record count, config/extra/index/check offsets, float64 open and
///     close dates (OLE: days since 1899-12-30).
///   - `record count` records from the data offset, each: uint16 record length (bytes, counting
///     this field), float64 OLE date of the record, then the message without its serial framing:
///     uint8 tx node, rx node, message type (2 = mtHeadData), sequence, node; uint16 packed size;
///     uint8 device type, head status, sweep code; uint16 HdCtrl, range scale; uint32 TxN; uint8
///     gain; uint16 slope; uint8 AD span, AD low; uint16 heading offset, ADInterval, left limit,
///     right limit; uint8 step; uint16 bearing, data byte count; then the data bytes. The mtHeadData
///     header is 46 bytes from the record start; bytes after the data (appended messages) are skipped.

#include <cstddef>
#include <span>
#include <string>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// How V4LOG head settings become beam geometry.
struct V4LogOptions {
  /// Speed of sound in m/s (> 0, finite): bin length = ADInterval × 640 ns × speed / 2.
  double sound_speed_m_s = 1500.0;
};

/// Size of the fixed part of a V4LOG mtHeadData record (length, date, message header), bytes.
inline constexpr std::size_t kV4LogHeadDataHeaderBytes = 46;
/// Size of the V4LOG file header, bytes.
inline constexpr std::size_t kV4LogFileHeaderBytes = 80;

/// Reads a SeaNet V4 log into beams (see parseSeaNetV4Log for the conversion and the errors).
/// @param path  the `.V4LOG` file.
/// @throws FileError  when the file cannot be opened or read, or parseSeaNetV4Log rejects it.
/// @throws ValueError when `options.sound_speed_m_s` is not a positive finite number.
SonarLog readSeaNetV4Log(const std::string& path, const V4LogOptions& options = {});

/// Parses the bytes of a SeaNet V4 log. Each mtHeadData record becomes one Beam:
///   - `time_s`: seconds since the first record of the data section (its OLE date × 86,400 s
///     subtracted), so the first record is at 0. The absolute date is the PC's local clock and is
///     not kept.
///   - `bearing_rad`: SeaNet bearings count 1/16 gradian (6,400 per turn) *clockwise* seen from
///     above: the head scans from its left limit to its right limit with bearings increasing;
///     HdCtrl bit 2 `scanright` ("scanning direction is clockwise", ros-tritech-micron `sonar.py`)
///     is set on both beams of every increasing step of the sample and clear on every decreasing
///     one; rock's `Micron.cpp` notes "sonars coordinate system is clock wise". Tritech's "ahead"
///     is 3,200, the centre of the default 2,400…4,000 sector (rock's driver places a beam at
///     π − bearing·2π/6400 counter-clockwise: 3,200 ahead). beam.hpp counts clockwise from ahead,
///     so `bearing_rad = 2π · ((bearing − 3200) mod 6400) / 6400`, in [0, 2π). The HdCtrl bit 3
///     `invert` flag (head mounted boot up, upside down) reverses the count seen from above:
///     `2π · ((3200 − bearing) mod 6400) / 6400`, so an inverted head is mapped with the same
///     mounting as an upright one. The heading offset is not applied.
///   - `bin_length_m` = ADInterval × 640 ns × sound_speed / 2 (two-way travel time of one sample).
///   - `intensities`: 8-bit bins (HdCtrl bit 0 `adc8on` set) are copied; 4-bit bins (bit clear)
///     come two per byte, high nibble first (pySonar, tritech_micron; rock's driver takes the low
///     nibble first), and are scaled ×17 so 0…15 maps onto 0…255. Bin count = data bytes (8-bit)
///     or 2 × data bytes (4-bit).
///   - `intensity_span_db`: the head's AD span, ADspan × 80 / 255 dB (SeaNet's 0…80 dB scale: the
///     log-compressed echo from ADlow to ADlow + span fills 0…255); unset when ADspan is 0. The
///     shared sample: 149 → 46.7 dB. The detector converts its dB thresholds with it.
/// Left/right limits, step and sweep code are not needed to place a beam: a sector scan shows as
/// bearing reversals, which splitSweeps uses.
///
/// Records that are not mtHeadData (message type ≠ 2) and mtHeadData records with no data bytes
/// are left out, counted in `skipped_beams` and described in `skip_reasons` (record index, byte
/// offset, why).
///
/// A log cut short (a full disk, a pulled cable: the header declares more records than follow) is
/// read up to the damage: the whole records before it are read, and the first record whose length
/// field is cut off, runs past the end of the file or is below 13 bytes (the records after it
/// cannot be framed) ends the reading with one skip reason naming its byte, why, and how many
/// bytes and declared records were left.
///
/// @param bytes   the whole file.
/// @param source  name used in messages (the path).
/// @return        beams in recording order.
/// @throws FileError  naming `source`, the byte offset and the field, when: the file is shorter
///   than its 80-byte header; the magic is not `SeaNetV4 Log File V1`; the data offset lies
///   outside the file; a whole record's length is below 46 for mtHeadData; a record date is not
///   finite; the data byte count exceeds the record; ADInterval is 0 (no positive bin length); a
///   bearing is ≥ 6,400; a beam's date is before the previous beam's (at the record's date: "times
///   must not go backwards"); or no beam is read at all (no record, none is mtHeadData with data,
///   or the damage comes first: the message then gives its reason).
/// @throws ValueError when `options.sound_speed_m_s` is not a positive finite number.
SonarLog parseSeaNetV4Log(std::span<const unsigned char> bytes, const std::string& source,
                          const V4LogOptions& options = {});

}  // namespace sonarmap
