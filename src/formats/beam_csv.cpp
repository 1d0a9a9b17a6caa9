/// @file beam_csv.cpp
/// Beam CSV reader and writer (see beam_csv.hpp).

#include "sonarmap/formats/beam_csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <string_view>
#include <utility>

#include "../io/csv_fields.hpp"
#include "../io/message_text.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/text_input.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kFixedColumns = 3;  // time_s, bearing_deg, bin_length_m
constexpr std::string_view kFixedNames[kFixedColumns] = {"time_s", "bearing_deg", "bin_length_m"};
constexpr std::string_view kSpanName = "intensity_span_db";  // optional, after bin_length_m
constexpr std::string_view kGainName = "gain_setting";       // optional, after the span (or bin_length_m)
constexpr std::string_view kPulseName = "pulse_length_m";    // optional, after the gain (or the columns before)
constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Bearing in [0, 2π) from any finite angle in degrees (the same arithmetic as readCrasMat).
double bearingFromDegrees(double bearing_deg) {
  double deg = std::fmod(bearing_deg, 360.0);
  if (deg < 0.0) deg += 360.0;
  const double rad = deg * std::numbers::pi / 180.0;
  return rad < kTwoPi ? rad : 0.0;
}

/// The degree value that bearingFromDegrees maps back to exactly `bearing_rad`: the nearest
/// degree value or one of its neighbours a few ulps away; the nearest one when none does.
double degreesFromBearing(double bearing_rad) {
  const double nearest_deg = bearing_rad * 180.0 / std::numbers::pi;
  double below = nearest_deg, above = nearest_deg;
  for (int step = 0; step <= 4; ++step) {
    if (bearingFromDegrees(below) == bearing_rad) return below;
    if (bearingFromDegrees(above) == bearing_rad) return above;
    below = std::nextafter(below, -HUGE_VAL);
    above = std::nextafter(above, HUGE_VAL);
  }
  return nearest_deg;
}

/// The header name of bin `bin`'s column: "b0", "b1", …
std::string binColumnName(std::size_t bin) {
  std::string name = "b";  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on "b" + string
  name += std::to_string(bin);
  return name;
}

/// The columns a header declares.
struct Header {
  bool has_span = false;      ///< an intensity_span_db column after bin_length_m
  std::optional<std::size_t> gain_column;  ///< the gain_setting column, when there is one
  std::optional<std::size_t> pulse_column;  ///< the pulse_length_m column, when there is one
  std::size_t first_bin = 0;  ///< column of b0
  std::size_t bins = 0;       ///< b-columns
};

Header readHeader(csv::LineReader& reader) {
  if (!reader.next()) reader.failFile("empty, expected the header row time_s,bearing_deg,bin_length_m,b0,b1,...");
  for (std::size_t c = 0; c < kFixedColumns; ++c) reader.expectName(c, kFixedNames[c]);
  Header header;
  const auto named = [&](std::size_t column, std::string_view name) {
    return reader.fields().size() > column && reader.fields()[column] == name;
  };
  header.has_span = named(kFixedColumns, kSpanName);
  header.first_bin = kFixedColumns + (header.has_span ? 1 : 0);
  if (named(header.first_bin, kGainName)) header.gain_column = header.first_bin++;
  if (named(header.first_bin, kPulseName)) header.pulse_column = header.first_bin++;
  header.bins = reader.fields().size() - header.first_bin;
  for (std::size_t i = 0; i < header.bins; ++i) reader.expectName(header.first_bin + i, binColumnName(i));
  return header;
}

std::uint8_t readIntensity(const csv::LineReader& reader, std::size_t column, std::size_t bin) {
  const std::string_view token = reader.fields()[column];
  const char* end = token.data() + token.size();
  long value = 0;
  const auto [stop, error] = std::from_chars(token.data(), end, value);
  const bool integer = (error == std::errc() || error == std::errc::result_out_of_range) && stop == end;
  if (integer && error == std::errc() && value >= 0 && value <= 255) return static_cast<std::uint8_t>(value);
  std::string what = detail::quotedForMessage(token);
  what += token.empty() ? " (empty; only trailing bins may be empty)"
                        : (integer ? " is out of range" : " is not an integer");
  reader.failField(column, binColumnName(bin), what + ", expected an intensity 0...255");
}

Beam readBeam(const csv::LineReader& reader, const Header& header) {
  const std::vector<std::string_view>& fields = reader.fields();
  if (fields.size() < kFixedColumns) {
    reader.fail(std::to_string(fields.size()) + " field(s), expected at least 3: time_s,bearing_deg,bin_length_m");
  }
  std::size_t bins = fields.size() > header.first_bin ? fields.size() - header.first_bin : 0;
  while (bins > 0 && fields[header.first_bin + bins - 1].empty()) --bins;  // spreadsheet padding
  if (bins > header.bins) {
    reader.fail(std::to_string(bins) + " bins, more than the " + std::to_string(header.bins) +
                " b-columns the header declares");
  }
  Beam beam;
  beam.time_s = reader.finiteNumber(0, kFixedNames[0], "seconds");
  beam.bearing_rad = bearingFromDegrees(reader.finiteNumber(1, kFixedNames[1], "degrees"));
  beam.bin_length_m = reader.finiteNumber(2, kFixedNames[2], "metres > 0");
  if (!(beam.bin_length_m > 0.0)) {
    reader.failField(2, kFixedNames[2], csv::formatNumber(beam.bin_length_m) + " m, expected metres > 0");
  }
  if (header.has_span && fields.size() > kFixedColumns && !fields[kFixedColumns].empty()) {  // empty: unknown
    const double span_db = reader.finiteNumber(kFixedColumns, kSpanName, "dB > 0");
    if (!(span_db > 0.0)) reader.failField(kFixedColumns, kSpanName, csv::formatNumber(span_db) + " dB, expected dB > 0");
    beam.intensity_span_db = span_db;
  }
  if (header.gain_column && fields.size() > *header.gain_column && !fields[*header.gain_column].empty()) {
    const std::string_view token = fields[*header.gain_column];
    int gain = 0;
    const auto [stop, error] = std::from_chars(token.data(), token.data() + token.size(), gain);
    if (error != std::errc() || stop != token.data() + token.size()) {
      reader.failField(*header.gain_column, kGainName, detail::quotedForMessage(token) + " is not an integer, expected the head's gain setting");
    }
    beam.gain_setting = gain;
  }
  if (header.pulse_column && fields.size() > *header.pulse_column && !fields[*header.pulse_column].empty()) {
    const double pulse_m = reader.finiteNumber(*header.pulse_column, kPulseName, "metres > 0");
    if (!(pulse_m > 0.0)) {
      reader.failField(*header.pulse_column, kPulseName, csv::formatNumber(pulse_m) + " m, expected metres > 0");
    }
    beam.pulse_length_m = pulse_m;
  }
  beam.intensities.resize(bins);
  for (std::size_t i = 0; i < bins; ++i) beam.intensities[i] = readIntensity(reader, header.first_bin + i, i);
  return beam;
}

/// @throws ValueError when writing `log` would give a file readBeamCsv rejects.
void checkWritable(const SonarLog& log) {
  if (log.beams.empty()) throw ValueError("a beam CSV cannot be written: the log has no beam");
  for (std::size_t i = 0; i < log.beams.size(); ++i) {
    const Beam& beam = log.beams[i];
    const std::string where = "a beam CSV cannot be written: beam " + std::to_string(i) + ": ";
    if (!std::isfinite(beam.time_s) || !std::isfinite(beam.bearing_rad)) {
      throw ValueError(where + "time or bearing is not finite");
    }
    if (!(beam.bin_length_m > 0.0 && std::isfinite(beam.bin_length_m))) {
      throw ValueError(where + "bin length " + csv::formatNumber(beam.bin_length_m) + " m, expected finite and > 0");
    }
    if (beam.intensity_span_db && !(*beam.intensity_span_db > 0.0 && std::isfinite(*beam.intensity_span_db))) {
      throw ValueError(where + "intensity span " + csv::formatNumber(*beam.intensity_span_db) +
                       " dB, expected finite and > 0");
    }
    if (beam.pulse_length_m && !(*beam.pulse_length_m > 0.0 && std::isfinite(*beam.pulse_length_m))) {
      throw ValueError(where + "pulse length " + csv::formatNumber(*beam.pulse_length_m) + " m, expected finite and > 0");
    }
    if (i > 0 && beam.time_s < log.beams[i - 1].time_s) {
      throw ValueError(where + "time " + csv::formatNumber(beam.time_s) + " s is before the previous beam's " +
                       csv::formatNumber(log.beams[i - 1].time_s) + " s");
    }
  }
}

}  // namespace

SonarLog readBeamCsv(const std::string& path) {
  const std::unique_ptr<std::istream> in = openTextInput(path);
  return readBeamCsv(*in, path);
}

namespace {

/// The rows of a beam CSV as beams, one at a time, each checked as readBeamCsv checks it.
class BeamCsvRows {
 public:
  /// Reads the header row. @throws FileError as readBeamCsv for an empty file or a bad header.
  BeamCsvRows(std::istream& in, const std::string& name) : reader_(in, name), header_(readHeader(reader_)) {}

  /// The next row's beam, nullopt after the last.
  /// @throws FileError as readBeamCsv for a malformed row or a time before the previous row's, and
  ///         at the end for a file without a beam row.
  std::optional<Beam> next() {
    if (!reader_.next()) {
      if (!previous_time_s_) reader_.failFile("no beams: only the header row");
      return std::nullopt;
    }
    Beam beam = readBeam(reader_, header_);
    if (previous_time_s_ && beam.time_s < *previous_time_s_) {
      reader_.failField(0, kFixedNames[0], "times go backwards: " + csv::formatNumber(beam.time_s) +
                                               " s is before the previous beam's " + csv::formatNumber(*previous_time_s_) +
                                               " s (line " + std::to_string(previous_line_) + ")");
    }
    previous_time_s_ = beam.time_s;
    previous_line_ = reader_.lineNumber();
    return beam;
  }

 private:
  csv::LineReader reader_;
  Header header_;
  std::optional<double> previous_time_s_;  ///< the last row's
  std::size_t previous_line_ = 0;
};

/// A beam CSV file (gzip-compressed or not) read row by row (openBeamCsv), opened again for each pass.
class BeamCsvSource final : public BeamSource {
 public:
  explicit BeamCsvSource(const std::string& path) : path_(path) {
    rewind();
    first_ = rows_->next();  // the header and the first row: their errors are the opening's
  }
  std::optional<Beam> next() override {
    if (first_) return std::exchange(first_, std::nullopt);
    if (!rows_) return std::nullopt;
    std::optional<Beam> beam = rows_->next();
    if (!beam) rows_.reset();
    return beam;
  }
  void rewind() override {
    rows_.reset();
    first_.reset();
    in_ = openTextInput(path_);  // gzip-compressed or not
    rows_.emplace(*in_, path_);
  }
  const SonarLog& header() const override { return header_; }

 private:
  std::string path_;
  std::unique_ptr<std::istream> in_;
  std::optional<BeamCsvRows> rows_;  ///< unset at the end of a pass
  std::optional<Beam> first_;        ///< read ahead by the opening
  SonarLog header_;                  ///< a beam CSV says nothing besides its beams
};

}  // namespace

SonarLog readBeamCsv(std::istream& in, const std::string& name) {
  BeamCsvRows rows(in, name);
  SonarLog log;
  while (std::optional<Beam> beam = rows.next()) log.beams.push_back(std::move(*beam));
  return log;
}

std::unique_ptr<BeamSource> openBeamCsv(const std::string& path) { return std::make_unique<BeamCsvSource>(path); }

void writeBeamCsv(std::ostream& out, const SonarLog& log) {
  checkWritable(log);
  std::size_t header_bins = 0;
  bool has_span = false, has_gain = false, has_pulse = false;
  for (const Beam& beam : log.beams) {
    header_bins = std::max(header_bins, beam.intensities.size());
    has_span = has_span || beam.intensity_span_db.has_value();
    has_gain = has_gain || beam.gain_setting.has_value();
    has_pulse = has_pulse || beam.pulse_length_m.has_value();
  }
  std::string line = "time_s,bearing_deg,bin_length_m";
  if (has_span) (line += ',') += kSpanName;
  if (has_gain) (line += ',') += kGainName;
  if (has_pulse) (line += ',') += kPulseName;
  for (std::size_t i = 0; i < header_bins; ++i) line += ',' + binColumnName(i);
  out << line << '\n';
  for (const Beam& beam : log.beams) {
    line.clear();
    csv::appendNumber(line, beam.time_s);
    line += ',';
    csv::appendNumber(line, degreesFromBearing(beam.bearing_rad));
    line += ',';
    csv::appendNumber(line, beam.bin_length_m);
    if (has_span) {
      line += ',';
      if (beam.intensity_span_db) csv::appendNumber(line, *beam.intensity_span_db);
    }
    if (has_gain) {
      line += ',';
      if (beam.gain_setting) line += std::to_string(*beam.gain_setting);
    }
    if (has_pulse) {
      line += ',';
      if (beam.pulse_length_m) csv::appendNumber(line, *beam.pulse_length_m);
    }
    for (const std::uint8_t intensity : beam.intensities) {
      line += ',';
      line += std::to_string(intensity);
    }
    out << line << '\n';
  }
}

void writeBeamCsv(const std::string& path, const SonarLog& log) {
  checkWritable(log);  // before the temporary file is made
  writeFileAtomically(path, [&](std::ostream& out) { writeBeamCsv(out, log); });
}

}  // namespace sonarmap
