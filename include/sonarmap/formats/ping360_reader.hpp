#pragma once
/// @file ping360_reader.hpp
/// Readers for Blue Robotics Ping360 scanning sonar data: a raw ping-protocol message stream (the
/// bytes of the sonar's serial or UDP link, logged as they come) and Ping Viewer's sensor logs
/// (`.bin`, in `Documents/PingViewer/Sensor_Log`). Default extension `.bin` (log_reader.hpp);
/// readPing360 tells the two apart by their first bytes.
///
/// Sources (read, not copied): Blue Robotics `ping-protocol` (README "Format",
/// `src/definitions/ping360.json`), `ping-python` (`brping/pingmessage.py`), Ping Viewer
/// (`src/link/logsensorstruct.cpp`, `src/link/filelink.cpp`, `src/link/abstractlink.cpp`,
/// `examples/decode_sensor_binary_log.py`); ../shared/docs/formats.md.
///
/// Message (little-endian): 'B' 'R', uint16 payload length, uint16 message id, uint8 source and
/// destination device ids, the payload, uint16 checksum (sum of all bytes before it, mod 65536).
/// device_data (2300): u8 mode, u8 gain_setting, u16 angle (gradians, 0–399), u16
/// transmit_duration (µs), u16 sample_period (25 ns), u16 transmit_frequency (kHz), u16
/// number_of_samples, u16 data length, the samples (u8 each, nearest first). auto_device_data
/// (2301) adds u16 start_angle, u16 stop_angle, u8 num_steps, u8 delay before number_of_samples.
///
/// Ping Viewer log (Qt QDataStream, big-endian): the header, then records to the end of the file.
/// Strings and byte arrays are a uint32 byte length (0xFFFFFFFF: null) and the bytes; strings
/// are UTF-8 in logs written on Linux/macOS and UTF-16BE in Windows ones (decode_sensor_binary_log.py).
///   header: string "PingViewer sensor log file", int32 version (1), strings git hash, build
///     date, tag, OS name, OS version, int32 sensor family, int32 sensor type;
///   record: string time "hh:mm:ss.zzz" (time since logging began, Ping Viewer's QElapsedTimer),
///     byte array: the bytes received from the sensor at that time (any part of the stream: a
///     message may span records).
/// Layout from Ping Viewer's source only: not checked against a log written by Ping Viewer.

#include <span>
#include <string>

#include "sonarmap/formats/capture_options.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Reads a Ping360 file (see parsePing360). A Ping Viewer log whose file name starts with its
/// start time (`yyyyMMdd-hhmmsszzz`, log_clock.hpp) gets `clock_utc_s` = that local time counted
/// as UTC (readSonarLog moves it by LogReadOptions::utc_offset_s).
/// @throws FileError when the file cannot be opened or read, or the parser rejects it.
/// @throws ValueError for options out of range (see parsePing360Stream).
SonarLog readPing360(const std::string& path, const CaptureOptions& options = {});

/// Parses Ping360 bytes: a Ping Viewer log when isPingViewerLog says so (parsePingViewerLog),
/// else a raw message stream (parsePing360Stream). Throws as they do.
SonarLog parsePing360(std::span<const unsigned char> bytes, const std::string& source, const CaptureOptions& options = {});

/// Parses a raw ping-protocol stream. Each device_data or auto_device_data message becomes one
/// Beam:
///   - `bearing_rad` = 2π · angle / 400: the Ping360 counts gradians clockwise seen from above
///     from its zero, which Ping Viewer draws ahead, at the top of its fan (it adds the vehicle's
///     yaw to the angle and draws it clockwise); beam.hpp's bearings are clockwise from ahead;
///   - `bin_length_m` = sample_period × 25 ns × sound speed / 2;
///   - `intensities`: the data array, sample 0 nearest (its length, not number_of_samples, gives
///     the bin count); `intensity_span_db` unset (the protocol does not give one);
///   - `time_s` = beam index × options.beam_interval_s (the messages carry no time).
/// Skipped and counted (`skipped_beams`, one line each in `skip_reasons` with the byte offset and
/// why): messages with other ids (ack, nack, ascii_text, device_information, …); device data whose
/// data length does not fill the payload, with an angle ≥ 400, a sample period of 0 or no samples;
/// each run of bytes outside any message (noise, a message with a bad checksum or of 10,240 bytes
/// or more, beyond Ping Viewer's parser: the run names its first rejected message and why); a
/// final message cut short by the end of the stream.
/// @param bytes   the whole stream.
/// @param source  name used in messages (the path).
/// @throws FileError  naming `source` when the stream holds no beam, with the first skip reason.
/// @throws ValueError when `options.sound_speed_m_s` is not positive and finite, or
///   `options.beam_interval_s` is negative or not finite.
SonarLog parsePing360Stream(std::span<const unsigned char> bytes, const std::string& source,
                            const CaptureOptions& options = {});

/// True when `bytes` begins with a Ping Viewer log header string (UTF-8 or UTF-16BE).
bool isPingViewerLog(std::span<const unsigned char> bytes);

/// True when `path` is a regular file that begins with a Ping Viewer log header (isPingViewerLog
/// on its first bytes); false for anything else (a device, a FIFO, a raw stream, a missing file).
/// Never throws.
bool isPingViewerLogFile(const std::string& path);

/// Parses a Ping Viewer sensor log (layout in the file comment). The data of every record, in
/// order, form one ping-protocol stream read as parsePing360Stream reads it; a beam's `time_s` is
/// the time of the record holding its message's last byte (seconds since logging began).
/// `options.beam_interval_s` is not used. Skipped and counted besides the stream's items: a record
/// whose time is not hh:mm:ss.zzz (with its data), a beam whose time is before the previous beam's,
/// and the end of the file from a record that is cut short or whose time is empty or longer than
/// 24 bytes (where Ping Viewer's own reader stops or loses its place). Offsets in skip lines name
/// the record and its byte in the file.
/// @throws FileError  naming `source` when the header is not a Ping Viewer header (string, then
///   version 1, the five build strings and the two sensor ints, within the file), or the log holds
///   no beam.
/// @throws ValueError when `options.sound_speed_m_s` is not positive and finite.
SonarLog parsePingViewerLog(std::span<const unsigned char> bytes, const std::string& source,
                            const CaptureOptions& options = {});

}  // namespace sonarmap
