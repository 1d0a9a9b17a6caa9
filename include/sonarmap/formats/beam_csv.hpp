#pragma once
/// @file beam_csv.hpp
/// Beam CSV: a plain-text sonar log, one beam per row (docs/formats.md, "Beam CSV"), for logs
/// from other tools (a spreadsheet, a script) and for exchanging beams without MATLAB.
///
///     time_s,bearing_deg,bin_length_m,b0,b1,...,b<K-1>
///     10.28,0,0.0125313,12,40,7
///
///  - time_s: seconds, the log's own clock (the navigation's clock when there is one); finite;
///    rows in time order (equal times allowed, going backwards is an error).
///  - bearing_deg: degrees in the sonar frame of beam.hpp, 0 along the sonar's +x (ahead),
///    clockwise positive seen from above (90° is +y, starboard); any finite value, wrapped to [0°, 360°).
///  - bin_length_m: metres, finite and > 0.
///  - intensity_span_db (optional column, right after bin_length_m): the dB span of the
///    intensities 0…255 (Beam::intensity_span_db, e.g. a SeaNet head's AD span), finite and > 0;
///    an empty field leaves it unknown (the detector then assumes 45 dB). Written only when some
///    beam has one, so that a converted log maps as its source does.
///  - gain_setting (optional column, after intensity_span_db or, without it, after bin_length_m):
///    the head's receiver gain setting in its own units (Beam::gain_setting, an integer); empty:
///    unknown. Written only when some beam has one (a range or gain change splits sweeps, sweeps.hpp).
///  - pulse_length_m (optional column, after the optional columns before it): the transmitted
///    pulse's length in range, metres, finite and > 0 (Beam::pulse_length_m: a Ping360's transmit
///    duration, a simulated head's pulse); empty: unknown. Written only when some beam has one.
///  - b0…b<K-1>: echo intensity per bin, integers 0…255, b0 nearest. The header has as many
///    b-columns as the longest beam (K ≥ 0); a row may hold fewer bins than the header (trailing
///    empty fields, as spreadsheets pad short rows, count as absent bins), never more.
/// Spaces and tabs around fields, CRLF line ends, blank lines and a UTF-8 byte-order mark are
/// accepted. Numbers as std::from_chars reads them (no leading '+').

#include <iosfwd>
#include <memory>
#include <string>

#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/beam_source.hpp"

namespace sonarmap {

/// Reads a beam CSV. Bearings are converted to Beam::bearing_rad = radians(bearing_deg wrapped
/// to [0°, 360°)), computed as deg · π / 180 like readCrasMat. Nothing is skipped: the returned
/// log has skipped_beams = 0. The file may be gzip-compressed (`beams.csv.gz`: io/text_input.hpp).
/// @return the beams in file order.
/// @throws FileError naming the file, the 1-based line and the field (column name and number)
///         when the file cannot be opened, is empty, or its gzip data is truncated or corrupt; the header is not
///         `time_s,bearing_deg,bin_length_m[,intensity_span_db][,gain_setting][,pulse_length_m],b0,b1,…`
///         with consecutive b-columns; a row has fewer than 3 fields or more bins than the header
///         declares; a number is malformed or not finite (a NaN bearing); a bin length, a span or a
///         pulse length is ≤ 0; an intensity is not an integer in 0…255; a gain setting is not an integer;
///         a time is before the previous row's ("times go backwards"); or there is no beam row.
SonarLog readBeamCsv(const std::string& path);

/// The same CSV read from a stream; `name` stands for the file in messages.
/// @throws FileError as readBeamCsv(path) for anything malformed.
SonarLog readBeamCsv(std::istream& in, const std::string& name);

/// readBeamCsv's beams one row at a time (beam_source.hpp): the same beams and errors, read as
/// they are asked for, so a CSV of any length (gzip-compressed or not) is read in the memory of one row; each pass reads
/// the file again. Opening reads the header and the first row.
/// @throws FileError as readBeamCsv: on opening for the file, its header or first row (or none),
///         from next() for a later row.
std::unique_ptr<BeamSource> openBeamCsv(const std::string& path);

/// Writes the beams of `log` as a beam CSV (atomically: temporary file + rename). Beams may have
/// different bin counts; the header has as many b-columns as the longest beam. Times and bin
/// lengths are written in their shortest exact decimal form, so they read back identically.
/// Bearings are written in degrees chosen so that readBeamCsv gives back the identical
/// bearing_rad: the nearest degree value, or its neighbour one ulp away when only that one reads
/// back exactly (11 of the CRAS log's 200 bearings). This is exact for every bearing that some
/// double degree value maps to, which includes every bearing readCrasMat and readBeamCsv produce
/// (degrees → radians). About a fifth of arbitrary radians values in [0, 2π) are the image of no
/// double degree value; those read back within 1 ulp (< 9e-16 rad). A bearing outside [0, 2π)
/// reads back wrapped into it. skipped_beams and skip_reasons are not written.
/// @throws ValueError (before writing anything) when the log has no beam, or a beam has a
///         non-finite time or bearing, a bin length or intensity span that is not finite and > 0,
///         or a time before
///         the previous beam's: readBeamCsv would reject the file. The message names the beam's
///         index. @throws FileError when the file cannot be written.
void writeBeamCsv(const std::string& path, const SonarLog& log);

/// The same CSV written to a stream (e.g. to stage it with other outputs, io/atomic_file.hpp).
/// @throws ValueError as writeBeamCsv(path, log), before writing anything.
void writeBeamCsv(std::ostream& out, const SonarLog& log);

}  // namespace sonarmap
