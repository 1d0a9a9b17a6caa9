/// Tests of the beam CSV (beam_csv.hpp): round trips (synthetic, the real CRAS log), the bearing
/// conversion and its exactness, broken files, and readSonarLog's dispatch of `.csv`.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "common/temp_dir.hpp"

namespace sonarmap {
namespace {

using test::TempDir;

constexpr double kPi = std::numbers::pi;
const std::string kCrasLog = std::string(SONARMAP_SHARED_DATA) + "/cras_micron_tank_static.mat";

void write(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string readText(const std::string& path) {
  std::ostringstream text;
  text << std::ifstream(path, std::ios::binary).rdbuf();
  return text.str();
}

Beam beam(double time_s, double bearing_rad, double bin_length_m, std::vector<std::uint8_t> intensities) {
  return Beam{time_s, bearing_rad, bin_length_m, std::move(intensities), std::nullopt};
}

void expectIdentical(const SonarLog& read, const SonarLog& written) {
  ASSERT_EQ(read.beams.size(), written.beams.size());
  EXPECT_EQ(read.skipped_beams, 0u);
  for (std::size_t i = 0; i < written.beams.size(); ++i) {
    const Beam& a = read.beams[i];
    const Beam& b = written.beams[i];
    ASSERT_EQ(a.time_s, b.time_s) << "beam " << i;
    ASSERT_EQ(a.bearing_rad, b.bearing_rad) << "beam " << i;
    ASSERT_EQ(a.bin_length_m, b.bin_length_m) << "beam " << i;
    ASSERT_EQ(a.intensities, b.intensities) << "beam " << i;
    ASSERT_EQ(a.intensity_span_db, b.intensity_span_db) << "beam " << i;
    ASSERT_EQ(a.gain_setting, b.gain_setting) << "beam " << i;
    ASSERT_EQ(a.pulse_length_m, b.pulse_length_m) << "beam " << i;
  }
}

SonarLog roundTrip(const SonarLog& log, const TempDir& dir) {
  writeBeamCsv(dir.file("log.csv"), log);
  return readBeamCsv(dir.file("log.csv"));
}

/// The bearing readBeamCsv gives for `bearing_deg`, read from a one-beam file.
double readBearing(const std::string& bearing_deg) {
  const TempDir dir;
  write(dir.file("b.csv"), "time_s,bearing_deg,bin_length_m,b0\n0," + bearing_deg + ",0.1,0\n");
  return readBeamCsv(dir.file("b.csv")).beams.at(0).bearing_rad;
}

// ---- round trips ---------------------------------------------------------------------------------

TEST(sonarBeamCsv, SyntheticRoundTripIsExact) {
  SonarLog log;
  log.beams = {beam(0.1, 0.0, 0.0125313, {0, 255, 7}),
               beam(0.1, kPi, 1.0 / 3.0, {1, 2, 3, 4, 5}),  // same time: allowed
               beam(0.2, 2.0 * kPi - 1e-12, 1e-6, {}),      // no bins at all
               beam(1e6, 0.1 * kPi / 180.0, 100.0, {9})};
  log.skipped_beams = 3;  // not stored in the file
  const TempDir dir;
  expectIdentical(roundTrip(log, dir), log);
  const std::string text = readText(dir.file("log.csv"));
  EXPECT_EQ(text.substr(0, text.find('\n')), "time_s,bearing_deg,bin_length_m,b0,b1,b2,b3,b4");
  EXPECT_NE(text.find("\n0.1,180,0.3333333333333333,1,2,3,4,5\n"), std::string::npos) << text;
}

// A log that records its intensity span (a SeaNet head's AD span) keeps it, so that a converted
// log calibrates, detects and maps as its source does; a log without one writes no such column.
TEST(sonarBeamCsv, IntensitySpanRoundTripsAndIsOptional) {
  SonarLog log;
  log.beams = {beam(0.1, 0.0, 0.05, {3, 200}), beam(0.2, 0.1, 0.05, {7})};
  log.beams[0].intensity_span_db = 80.0 * 150 / 255;  // SeaNet ADspan 150
  const TempDir dir;
  expectIdentical(roundTrip(log, dir), log);  // the second beam's span stays unknown
  const std::string text = readText(dir.file("log.csv"));
  EXPECT_EQ(text.substr(0, text.find('\n')), "time_s,bearing_deg,bin_length_m,intensity_span_db,b0,b1");
  EXPECT_NE(text.find("\n0.2,"), std::string::npos);
  EXPECT_NE(text.find(",0.05,,7\n"), std::string::npos) << text;  // empty span field, then the bins
  write(dir.file("span.csv"), "time_s,bearing_deg,bin_length_m,intensity_span_db,b0\n0,0,0.1,46.7,9\n1,0,0.1\n");
  const SonarLog read = readBeamCsv(dir.file("span.csv"));
  ASSERT_EQ(read.beams.size(), 2u);
  EXPECT_EQ(read.beams[0].intensity_span_db, 46.7);
  EXPECT_EQ(read.beams[0].intensities, std::vector<std::uint8_t>{9});
  EXPECT_FALSE(read.beams[1].intensity_span_db.has_value());  // row ends before the span
  EXPECT_TRUE(read.beams[1].intensities.empty());
}

TEST(sonarBeamCsv, GainAndPulseLengthRoundTripAndAreOptional) {
  SonarLog log;
  log.beams = {beam(0.1, 0.0, 0.00165, {3, 200}), beam(0.2, 0.1, 0.00825, {7})};
  log.beams[0].gain_setting = 0;
  log.beams[0].pulse_length_m = 0.00825;  // a Ping360 at 2 m: 11 µs
  log.beams[1].gain_setting = 1;
  const TempDir dir;
  expectIdentical(roundTrip(log, dir), log);
  const SonarLog read = readBeamCsv(dir.file("log.csv"));
  EXPECT_EQ(read.beams[0].pulse_length_m, 0.00825);
  EXPECT_FALSE(read.beams[1].pulse_length_m.has_value());  // an empty field: unknown
  EXPECT_EQ(read.beams[1].gain_setting, 1);
  const std::string text = readText(dir.file("log.csv"));
  EXPECT_EQ(text.substr(0, text.find('\n')), "time_s,bearing_deg,bin_length_m,gain_setting,pulse_length_m,b0,b1");
}

TEST(sonarBeamCsv, CrasLogRoundTripIsExact) {
  if (!std::filesystem::exists(kCrasLog)) GTEST_SKIP() << "no shared data at " << kCrasLog;
  const SonarLog log = readSonarLog(kCrasLog);
  ASSERT_EQ(log.beams.size(), 5603u);
  const TempDir dir;
  expectIdentical(roundTrip(log, dir), log);
  // Degrees as readCrasMat's angle + 180, wrapped: the first beam (angle 180°) is at 0°, the
  // second at 1.8° (written as the degree value that reads back to the identical radians).
  std::istringstream rows(readText(dir.file("log.csv")));
  std::string header, first, second;
  std::getline(rows, header);
  std::getline(rows, first);
  std::getline(rows, second);
  EXPECT_EQ(first.substr(first.find(','), 3), ",0,") << first;
  EXPECT_NEAR(std::stod(second.substr(second.find(',') + 1)), 1.8, 1e-5) << second;
}

// ---- bearings ------------------------------------------------------------------------------------

TEST(sonarBeamCsv, BearingDegreesAreWrappedToRadians) {
  EXPECT_EQ(readBearing("0"), 0.0);
  EXPECT_EQ(readBearing("180"), kPi);
  EXPECT_NEAR(readBearing("90"), kPi / 2, 1e-15);      // counter-clockwise from +x: +y (left)
  EXPECT_NEAR(readBearing("-90"), 3 * kPi / 2, 1e-15);  // clockwise 90° = 270°
  EXPECT_NEAR(readBearing("720.5"), 0.5 * kPi / 180, 1e-15);
  EXPECT_EQ(readBearing("360"), 0.0);
  EXPECT_EQ(readBearing("-360"), 0.0);
  EXPECT_EQ(readBearing("-1e-300"), 0.0);  // wraps to 360°, which is 0
  const double just_below = readBearing("359.99999999999994");
  EXPECT_GE(just_below, 0.0);
  EXPECT_LT(just_below, 2 * kPi);
  EXPECT_NEAR(readBearing("1e15"), std::fmod(1e15, 360.0) * kPi / 180, 1e-12);
}

TEST(sonarBeamCsv, BearingsFromDegreesRoundTripExactly) {
  // Every bearing the readers produce comes from degrees: those must come back identical.
  std::ostringstream text;
  text.precision(17);
  text << "time_s,bearing_deg,bin_length_m\n";
  std::mt19937_64 random(42);
  std::uniform_real_distribution<double> degrees(-720.0, 720.0);
  for (int i = 0; i < 3600; ++i) text << i << ',' << 0.1 * i << ",0.1\n";  // a 0.1° grid
  for (int i = 0; i < 200; ++i) text << 3600 + i << ',' << static_cast<float>(1.8 * i) + 180.0 << ",0.1\n";  // CRAS
  for (int i = 0; i < 100000; ++i) text << 4000 + i << ',' << degrees(random) << ",0.1\n";
  const TempDir dir;
  write(dir.file("degrees.csv"), text.str());
  const SonarLog log = readBeamCsv(dir.file("degrees.csv"));
  ASSERT_EQ(log.beams.size(), 103800u);
  expectIdentical(roundTrip(log, dir), log);
}

TEST(sonarBeamCsv, AnyBearingRoundTripsWithinOneUlp) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> radians(0.0, 2 * kPi);
  SonarLog log;
  for (int i = 0; i < 100000; ++i) log.beams.push_back(beam(i, radians(random), 0.1, {}));
  const TempDir dir;
  const SonarLog read = roundTrip(log, dir);
  ASSERT_EQ(read.beams.size(), log.beams.size());
  std::size_t inexact = 0;
  for (std::size_t i = 0; i < log.beams.size(); ++i) {
    const double written = log.beams[i].bearing_rad;
    const double back = read.beams[i].bearing_rad;
    if (back == written) continue;
    ++inexact;
    const double ulp = std::nextafter(written, HUGE_VAL) - written;
    ASSERT_LE(std::abs(back - written), ulp) << "beam " << i << ": " << written << " → " << back;
  }
  RecordProperty("inexact_bearings", static_cast<int>(inexact));
  // About 22 % of uniformly drawn radians values are the image of no double degree value.
  EXPECT_LT(inexact, log.beams.size() * 3 / 10) << inexact;
}

// ---- lenient input -------------------------------------------------------------------------------

TEST(sonarBeamCsv, ShortRowsPaddingCrlfAndWhitespaceAreAccepted) {
  const TempDir dir;
  write(dir.file("log.csv"),
        "\xEF\xBB\xBFtime_s,bearing_deg,bin_length_m,b0,b1,b2\r\n"
        "1,90,0.5,1,2,3\r\n"
        "\r\n"
        "2, 45 ,0.5,4,,\t\r\n"  // spreadsheet padding: two absent bins
        "2,0,0.25\n");           // no bins
  const SonarLog log = readBeamCsv(dir.file("log.csv"));
  ASSERT_EQ(log.beams.size(), 3u);
  EXPECT_EQ(log.beams[0].intensities, (std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(log.beams[1].intensities, std::vector<std::uint8_t>{4});
  EXPECT_NEAR(log.beams[1].bearing_rad, kPi / 4, 1e-15);
  EXPECT_TRUE(log.beams[2].intensities.empty());
  EXPECT_EQ(log.beams[2].bin_length_m, 0.25);
}

// ---- broken files --------------------------------------------------------------------------------

/// Expects readBeamCsv to throw a FileError whose message holds the file name and every part.
void expectFileError(const std::string& text, std::initializer_list<std::string> parts) {
  const TempDir dir;
  const std::string path = dir.file("log.csv");
  write(path, text);
  try {
    readBeamCsv(path);
    ADD_FAILURE() << "no FileError for:\n" << text;
  } catch (const FileError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

TEST(sonarBeamCsv, BrokenFilesNameLineAndField) {
  const std::string h = "time_s,bearing_deg,bin_length_m,b0,b1\n";
  expectFileError("", {"empty", "time_s,bearing_deg"});
  expectFileError(h, {"no beams"});
  expectFileError("time_s,bearing_rad,bin_length_m,b0\n", {"line 1", "'bearing_rad'", "expected 'bearing_deg'"});
  expectFileError("time_s,bearing_deg\n", {"line 1", "'bin_length_m'"});
  expectFileError("time_s,bearing_deg,bin_length_m,b0,b2\n", {"line 1", "column 5 is 'b2', expected 'b1'"});
  expectFileError("time_s,bearing_deg,bin_length_m,b1\n", {"line 1", "expected 'b0'"});
  expectFileError(h + "0,0\n", {"line 2", "2 field(s), expected at least 3"});
  expectFileError(h + "0,0,0.1,1,2\n1,0,0.1,1,2,3\n", {"line 3", "3 bins, more than the 2 b-columns"});
  expectFileError(h + "0,0,0.1,1,256\n", {"line 2", "field 'b1' (column 5)", "'256' is out of range", "0...255"});
  expectFileError(h + "0,0,0.1,-1\n", {"line 2", "field 'b0'", "'-1' is out of range"});
  expectFileError(h + "0,0,0.1,99999999999999999999999\n", {"line 2", "field 'b0'", "out of range"});
  expectFileError(h + "0,0,0.1,1.5\n", {"line 2", "field 'b0'", "'1.5' is not an integer"});
  expectFileError(h + "0,0,0.1,x\n", {"line 2", "field 'b0'", "not an integer"});
  expectFileError(h + "0,0,0.1,,7\n", {"line 2", "field 'b0'", "empty"});
  expectFileError(h + "0,nan,0.1,1\n", {"line 2", "field 'bearing_deg' (column 2)", "not finite"});
  expectFileError(h + "0,-inf,0.1,1\n", {"line 2", "field 'bearing_deg'", "not finite"});
  expectFileError(h + "nan,0,0.1,1\n", {"line 2", "field 'time_s'", "not finite"});
  expectFileError(h + "0,0,0,1\n", {"line 2", "field 'bin_length_m' (column 3)", "expected metres > 0"});
  expectFileError(h + "0,0,-0.1,1\n", {"line 2", "field 'bin_length_m'", "> 0"});
  expectFileError(h + "0,0,inf,1\n", {"line 2", "field 'bin_length_m'", "not finite"});
  expectFileError(h + "0,0,1e999,1\n", {"line 2", "field 'bin_length_m'", "out of the range"});
  expectFileError(h + "0,0,0.1m,1\n", {"line 2", "field 'bin_length_m'", "'0.1m' is not a number"});
  const std::string hs = "time_s,bearing_deg,bin_length_m,intensity_span_db,b0\n";
  expectFileError(hs + "0,0,0.1,0,1\n", {"line 2", "field 'intensity_span_db' (column 4)", "expected dB > 0"});
  expectFileError(hs + "0,0,0.1,-3,1\n", {"line 2", "field 'intensity_span_db'", "dB > 0"});
  expectFileError(hs + "0,0,0.1,inf,1\n", {"line 2", "field 'intensity_span_db'", "not finite"});
  expectFileError(hs + "0,0,0.1,45dB,1\n", {"line 2", "field 'intensity_span_db'", "not a number"});
  expectFileError(hs + "0,0,0.1,45,1,2\n", {"line 2", "2 bins, more than the 1 b-columns"});
  const std::string hp = "time_s,bearing_deg,bin_length_m,pulse_length_m,b0\n";
  expectFileError(hp + "0,0,0.1,0,1\n", {"line 2", "field 'pulse_length_m' (column 4)", "expected metres > 0"});
  expectFileError(hp + "0,0,0.1,nan,1\n", {"line 2", "field 'pulse_length_m'", "not finite"});
  expectFileError(h + "5,0,0.1,1\n\n4.5,0,0.1,1\n",
                  {"line 4", "field 'time_s'", "times go backwards",
                   "4.5 s is before the previous beam's 5 s (line 2)"});
}

// A stream reads as the file does (the demo maps its 3D log as its beams.csv holds it), and
// names the stream it was given in its errors.
TEST(sonarBeamCsv, StreamReadsAsTheFileDoes) {
  SonarLog log;
  log.beams = {beam(0.1, 0.3, 0.0125313, {0, 255, 7}), beam(0.2, 2.0 * kPi - 1e-12, 0.0125313, {1, 2})};
  const TempDir dir;
  const SonarLog from_file = roundTrip(log, dir);
  std::stringstream text;
  writeBeamCsv(text, log);
  expectIdentical(readBeamCsv(text, "beams.csv"), from_file);
  std::stringstream broken("time_s,bearing_deg,bin_length_m,b0\n0,0,0.1,300\n");
  try {
    readBeamCsv(broken, "stream.csv");
    FAIL() << "no FileError";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find("stream.csv"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("line 2"), std::string::npos) << error.what();
  }
}

TEST(sonarBeamCsv, MissingFileIsFileError) {
  const TempDir dir;
  EXPECT_THROW(readBeamCsv(dir.file("missing.csv")), FileError);
}

TEST(sonarBeamCsv, WriterRejectsLogsTheReaderWouldReject) {
  const TempDir dir;
  const std::string path = dir.file("log.csv");
  write(path, "keep me");
  const auto expectValueError = [&](std::vector<Beam> beams, const std::string& part) {
    SonarLog log;
    log.beams = std::move(beams);
    try {
      writeBeamCsv(path, log);
      ADD_FAILURE() << "no ValueError, expected one mentioning " << part;
    } catch (const ValueError& error) {
      EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
    }
  };
  expectValueError({}, "no beam");
  expectValueError({beam(0.0, std::nan(""), 0.1, {})}, "beam 0: time or bearing is not finite");
  expectValueError({beam(0.0, 0.0, 0.1, {}), beam(INFINITY, 0.0, 0.1, {})}, "beam 1: time or bearing");
  expectValueError({beam(0.0, 0.0, 0.0, {})}, "beam 0: bin length 0 m");
  expectValueError({beam(1.0, 0.0, 0.1, {}), beam(0.5, 0.0, 0.1, {})}, "beam 1: time 0.5 s is before");
  Beam no_span = beam(0.0, 0.0, 0.1, {});
  no_span.intensity_span_db = 0.0;
  expectValueError({no_span}, "beam 0: intensity span 0 dB");
  EXPECT_EQ(readText(path), "keep me");  // nothing was written
  SonarLog one;
  one.beams = {beam(0.0, 0.0, 0.1, {1})};
  EXPECT_THROW(writeBeamCsv(dir.file("no-such-folder/log.csv"), one), FileError);
}

// ---- readSonarLog --------------------------------------------------------------------------------

TEST(sonarBeamCsv, ReadSonarLogOpensCsvByExtension) {
  const TempDir dir;
  SonarLog log;
  log.beams = {beam(1.0, 0.5, 0.1, {1, 2})};
  for (const char* name : {"log.csv", "LOG.CSV"}) {
    writeBeamCsv(dir.file(name), log);
    expectIdentical(readSonarLog(dir.file(name)), log);
  }
}

}  // namespace
}  // namespace sonarmap
