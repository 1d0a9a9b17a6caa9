/// Tests of readSeaNetV4Log: the real SeaNet sector log, synthetic V4LOG files built here (field
/// conversion, skipped records, 4-bit bins), dispatch by extension, and broken files.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/v4log_reader.hpp"
#include "common/temp_dir.hpp"
#include "v4log_fixture.hpp"

namespace sonarmap {
namespace {

using test::TempDir;

constexpr double kPi = std::numbers::pi;
const std::string kSectorLog = std::string(SONARMAP_SHARED_DATA) + "/seanet_sector_target.V4LOG";

double degrees(double rad) { return rad * 180.0 / kPi; }

// ---- synthetic files ---------------------------------------------------------------------------

// The synthetic file builder (v4log_fixture.hpp), under this file's short names.
using Record = test::V4Record;
using test::setU16;
using test::setU32;
using test::v4log;
constexpr std::size_t kDataOffsetAt = test::kV4DataOffsetAt;
constexpr std::size_t kRecordCountAt = test::kV4RecordCountAt;
constexpr std::size_t kDateAt = test::kV4DateAt;
constexpr std::size_t kAdIntervalAt = test::kV4AdIntervalAt;
constexpr std::size_t kBearingAt = test::kV4BearingAt;
constexpr std::size_t kDataBytesAt = test::kV4DataBytesAt;
constexpr double kFirstDate_days = test::kV4FirstDate_days;

std::string writeFile(const TempDir& dir, const std::string& name, const std::string& bytes) {
  const std::string path = dir.file(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

/// The FileError message of reading `bytes` as a file, or "" when nothing is thrown.
std::string fileErrorOf(const TempDir& dir, const std::string& bytes) {
  const std::string path = writeFile(dir, "broken.V4LOG", bytes);
  try {
    readSeaNetV4Log(path);
  } catch (const FileError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    return message;
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// ---- the real log --------------------------------------------------------------------------------

TEST(sonarV4log, ReadsTheRealSectorLog) {
  if (!std::filesystem::exists(kSectorLog)) GTEST_SKIP() << "no shared data at " << kSectorLog;
  const SonarLog log = readSonarLog(kSectorLog);
  ASSERT_EQ(log.beams.size(), 468u);
  EXPECT_EQ(log.skipped_beams, 0u);
  EXPECT_TRUE(log.skip_reasons.empty());

  // ADInterval 33 × 640 ns × 1500 m/s / 2 = 15.84 mm; the range scale (10 m) / 642 bins is
  // 15.58 mm: the head samples 642 × 15.84 mm = 10.17 m.
  const double bin_length_m = 33 * 640e-9 * 1500.0 / 2.0;
  double min_deg = 360.0;
  double max_deg = -360.0;
  std::size_t repeated = 0;
  for (std::size_t i = 0; i < log.beams.size(); ++i) {
    const Beam& beam = log.beams[i];
    ASSERT_EQ(beam.intensities.size(), 642u) << "beam " << i;
    ASSERT_NEAR(beam.bin_length_m, bin_length_m, 1e-12) << "beam " << i;
    ASSERT_GE(beam.bearing_rad, 0.0);
    ASSERT_LT(beam.bearing_rad, 2.0 * kPi);
    // From ahead, in (−180°, 180°]: the sector straddles bearing 0.
    const double from_ahead_deg = std::remainder(degrees(beam.bearing_rad), 360.0);
    min_deg = std::min(min_deg, from_ahead_deg);
    max_deg = std::max(max_deg, from_ahead_deg);
    if (i == 0) continue;
    ASSERT_GT(beam.time_s, log.beams[i - 1].time_s) << "beam " << i;
    const double step_deg = std::remainder(degrees(beam.bearing_rad - log.beams[i - 1].bearing_rad), 360.0);
    ASSERT_NEAR(std::abs(step_deg), std::abs(step_deg) < 1.8 ? 0.0 : 3.6, 1e-9) << "beam " << i;
    repeated += std::abs(step_deg) < 1.8 ? 1 : 0;
  }
  EXPECT_NEAR(bin_length_m * 642, 10.17, 0.01);
  EXPECT_NEAR(10.0 / 642, bin_length_m, 0.02 * bin_length_m);
  // SeaNet bearings 2368…3968 (1/16 gradian, clockwise, ahead 3200); the head's HdCtrl has
  // `invert` set (0x230D), so its count runs the other way: (3200 − b) × 360° / 6400.
  EXPECT_NEAR(min_deg, -43.2, 1e-9);
  EXPECT_NEAR(max_deg, 46.8, 1e-9);
  EXPECT_NEAR(max_deg - min_deg, 90.0, 1e-9);
  EXPECT_EQ(repeated, 18u);  // the head pings twice at each end of the sector
  EXPECT_NEAR(degrees(log.beams[0].bearing_rad), 352.8, 1e-9);  // SeaNet 3328, inverted: 7.2° to port
  EXPECT_NEAR(degrees(log.beams[1].bearing_rad), 349.2, 1e-9);  // 3392: +64 on the inverted head is 3.6° counter-clockwise
  EXPECT_DOUBLE_EQ(log.beams[0].time_s, 0.0);
  EXPECT_NEAR(log.beams[1].time_s, 0.844, 0.001);
  EXPECT_NEAR(log.beams.back().time_s, 45.188, 0.001);
  // The bins start 46 bytes into the record: the first beam begins 00 00 00 3E 63.
  const std::vector<std::uint8_t> first(log.beams[0].intensities.begin(), log.beams[0].intensities.begin() + 5);
  EXPECT_EQ(first, (std::vector<std::uint8_t>{0x00, 0x00, 0x00, 0x3E, 0x63}));
}

// ---- synthetic logs ------------------------------------------------------------------------------

TEST(sonarV4log, ConvertsSyntheticRecordsAndSkipsOthers) {
  TempDir dir;
  std::vector<Record> records(6);
  for (Record& record : records) record.head_control = 0x2305;  // an upright head: adc8on, scanright
  records[0].bearing = 3200;  // Tritech's ahead
  records[0].ad_interval = 10;
  records[1].type = 6;  // mtBBUserData: not a beam
  records[2].head_control = 0x2304;  // adc8on clear: 4-bit bins
  records[2].bearing = 1600;
  records[2].data = {0xF1, 0x0A};
  records[3].bearing = 4800;
  records[3].date_days = kFirstDate_days + 1.5 / 86400.0;
  records[3].appended_bytes = 7;
  records[4].data.clear();  // no data bytes
  records[5].bearing = 3201;
  records[5].date_days = kFirstDate_days + 2.0 / 86400.0;  // times must not go backwards
  const SonarLog log = readSeaNetV4Log(writeFile(dir, "synthetic.V4LOG", v4log(records)));

  ASSERT_EQ(log.beams.size(), 4u);
  ASSERT_EQ(log.skipped_beams, 2u);
  ASSERT_EQ(log.skip_reasons.size(), 2u);
  EXPECT_TRUE(contains(log.skip_reasons[0], "record 1")) << log.skip_reasons[0];
  EXPECT_TRUE(contains(log.skip_reasons[0], "message type 6")) << log.skip_reasons[0];
  EXPECT_TRUE(contains(log.skip_reasons[1], "record 4")) << log.skip_reasons[1];
  EXPECT_TRUE(contains(log.skip_reasons[1], "no data bytes")) << log.skip_reasons[1];

  EXPECT_DOUBLE_EQ(log.beams[0].bearing_rad, 0.0);
  EXPECT_NEAR(log.beams[0].bin_length_m, 10 * 640e-9 * 750.0, 1e-15);
  EXPECT_EQ(log.beams[0].intensities, (std::vector<std::uint8_t>{10, 20, 30}));
  // SeaNet 1600 is three quarters of a turn clockwise from ahead (3200): port.
  EXPECT_NEAR(log.beams[1].bearing_rad, 1.5 * kPi, 1e-12);
  EXPECT_EQ(log.beams[1].intensities, (std::vector<std::uint8_t>{255, 17, 0, 170}));  // high nibble first, ×17
  EXPECT_NEAR(log.beams[2].bearing_rad, 0.5 * kPi, 1e-12);
  EXPECT_NEAR(log.beams[2].time_s, 1.5, 1e-6);
  EXPECT_NEAR(log.beams[3].bearing_rad, 2.0 * kPi / 6400, 1e-12);  // read after the appended bytes
  EXPECT_NEAR(log.beams[3].time_s, 2.0, 1e-6);
  // ADspan 149 of SeaNet's 80 dB scale: the intensities span 46.7 dB (the detector's dB thresholds).
  ASSERT_TRUE(log.beams[0].intensity_span_db.has_value());
  EXPECT_NEAR(*log.beams[0].intensity_span_db, 149.0 * 80.0 / 255.0, 1e-12);
}

TEST(sonarV4log, BinLengthFollowsTheSoundSpeed) {
  TempDir dir;
  const std::string path = writeFile(dir, "one.V4LOG", v4log({Record{}}));
  EXPECT_NEAR(readSeaNetV4Log(path, V4LogOptions{1400.0}).beams.at(0).bin_length_m, 33 * 640e-9 * 700.0, 1e-15);
  EXPECT_THROW(readSeaNetV4Log(path, V4LogOptions{0.0}), ValueError);
  EXPECT_THROW(readSeaNetV4Log(path, V4LogOptions{std::numeric_limits<double>::quiet_NaN()}), ValueError);
}

TEST(sonarV4log, ReadSonarLogDispatchesByExtensionInAnyCase) {
  TempDir dir;
  const std::string bytes = v4log({Record{}, Record{}});
  for (const char* name : {"a.V4LOG", "b.v4log", "c.V4Log"}) {
    EXPECT_EQ(readSonarLog(writeFile(dir, name, bytes)).beams.size(), 2u) << name;
  }
  try {
    readSonarLog(writeFile(dir, "d.v4", bytes));
    ADD_FAILURE() << "no FileError for an unknown extension";
  } catch (const FileError& e) {
    EXPECT_TRUE(contains(e.what(), ".V4LOG")) << e.what();
  }
}

// ---- broken files --------------------------------------------------------------------------------

TEST(sonarV4log, RejectsAWrongMagic) {
  TempDir dir;
  std::string bytes = v4log({Record{}});
  bytes[7] = '5';  // "SeaNetV5 ..."
  const std::string message = fileErrorOf(dir, bytes);
  EXPECT_TRUE(contains(message, "byte 0")) << message;
  EXPECT_TRUE(contains(message, "magic is 'SeaNetV5 Log File V1'")) << message;
  // A short file of another kind is named as such, not as a truncated log.
  EXPECT_TRUE(contains(fileErrorOf(dir, "time,angle\n"), "not a SeaNet V4 log"));
}

TEST(sonarV4log, ReadsTheWholeRecordsBeforeACutAndRefusesACutThatLeavesNone) {
  TempDir dir;
  const std::string bytes = v4log({Record{}, Record{}});  // 80 + 2 × 49 bytes
  ASSERT_EQ(bytes.size(), 178u);
  for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
    const std::string path = writeFile(dir, "cut.V4LOG", bytes.substr(0, cut));
    if (cut < 129) {  // before the end of record 0: nothing usable, a FileError naming the byte
      const std::string message = fileErrorOf(dir, bytes.substr(0, cut));
      ASSERT_TRUE(contains(message, "byte ")) << "cut at " << cut << ": " << message;
      continue;
    }
    const SonarLog log = readSeaNetV4Log(path);  // record 0 whole, record 1 cut
    ASSERT_EQ(log.beams.size(), 1u) << "cut at " << cut;
    ASSERT_EQ(log.skipped_beams, 1u) << "cut at " << cut;
    EXPECT_TRUE(contains(log.skip_reasons.at(0), "byte 129: ")) << log.skip_reasons.at(0);
    EXPECT_TRUE(contains(log.skip_reasons.at(0), "(cut short); the last " + std::to_string(cut - 129) +
                                                     " bytes and the 1 record(s) the header declares from there skipped"))
        << log.skip_reasons.at(0);
  }
  EXPECT_TRUE(contains(fileErrorOf(dir, bytes.substr(0, 50)), "file ends, expected the 80-byte SeaNet V4 file header"));
  const std::string in_record = fileErrorOf(dir, bytes.substr(0, 120));  // record 0 cut: no beam
  EXPECT_TRUE(contains(in_record, "no beam in the 2 record(s)")) << in_record;
  EXPECT_TRUE(contains(in_record, "byte 80: length of record 0 is 49 but the file ends 40 bytes after the record's start (cut short)"))
      << in_record;
  const SonarLog log = readSeaNetV4Log(writeFile(dir, "cut.V4LOG", bytes.substr(0, 170)));
  EXPECT_TRUE(contains(log.skip_reasons.at(0), "byte 129: length of record 1 is 49 but the file ends 41 bytes")) << log.skip_reasons.at(0);
  EXPECT_TRUE(contains(readSeaNetV4Log(writeFile(dir, "cut.V4LOG", bytes.substr(0, 130))).skip_reasons.at(0),
                       "byte 129: the file ends 1 byte(s) into the length of record 1 (cut short)"));
}

TEST(sonarV4log, RejectsHugeDeclaredSizesThatFrameNothing) {
  TempDir dir;
  const std::string good = v4log({Record{}});
  std::string bytes = good;
  // More records declared than the file holds reads as a cut file: its one record, and a warning.
  setU32(bytes, kRecordCountAt, 0xFFFFFFFFU);
  const SonarLog log = readSeaNetV4Log(writeFile(dir, "count.V4LOG", bytes));
  EXPECT_EQ(log.beams.size(), 1u);
  ASSERT_EQ(log.skip_reasons.size(), 1u);
  EXPECT_TRUE(contains(log.skip_reasons[0], "byte 129: the file ends 0 byte(s) into the length of record 1 (cut short); "
                                            "the last 0 bytes and the 4294967294 record(s)"))
      << log.skip_reasons[0];
  bytes = good;
  setU32(bytes, kDataOffsetAt, 0xFFFFFFF0U);
  EXPECT_TRUE(contains(fileErrorOf(dir, bytes), "byte 40: data offset is 4294967280"));
  bytes = good;
  setU16(bytes, 80, 0xFFFF);
  EXPECT_TRUE(contains(fileErrorOf(dir, bytes), "byte 80: length of record 0 is 65535 but the file ends 49 bytes"));
  bytes = good;
  setU16(bytes, 80 + kDataBytesAt, 60000);
  const std::string message = fileErrorOf(dir, bytes);
  EXPECT_TRUE(contains(message, "byte 124: data byte count of record 0 is 60000 but the record holds 3 bytes")) << message;
}

TEST(sonarV4log, RejectsBadFields) {
  TempDir dir;
  const std::string good = v4log({Record{}});
  std::string bytes = good;
  setU16(bytes, 80 + kAdIntervalAt, 0);
  EXPECT_TRUE(contains(fileErrorOf(dir, bytes), "byte 115: ADInterval of record 0 is 0"));
  bytes = good;
  setU16(bytes, 80 + kBearingAt, 6400);
  EXPECT_TRUE(contains(fileErrorOf(dir, bytes), "byte 122: bearing of record 0 is 6400"));
  bytes = good;
  setU16(bytes, 80, 20);  // an mtHeadData record shorter than its header
  EXPECT_TRUE(contains(fileErrorOf(dir, bytes), "byte 80: length of record 0 is 20, expected at least 46"));
  bytes = good;
  setU16(bytes, 80, 5);
  EXPECT_TRUE(contains(fileErrorOf(dir, bytes), "byte 80: length of record 0 is 5, expected at least 13"));
  bytes = good;
  for (std::size_t i = 0; i < 8; ++i) bytes[80 + kDateAt + i] = '\xFF';  // a NaN date
  const std::string message = fileErrorOf(dir, bytes);
  EXPECT_TRUE(contains(message, "byte 82: record date")) << message;
  EXPECT_TRUE(contains(message, "expected a finite number")) << message;
}

}  // namespace
}  // namespace sonarmap
