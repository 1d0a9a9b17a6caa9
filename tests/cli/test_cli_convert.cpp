// End-to-end tests of `sonarmap convert`: a log written as beam CSV maps to the very same octree
// as the log itself, and the CLI's error contract holds.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

const fs::path kCrasLog = fs::path(SONARMAP_SHARED_DATA) / "cras_micron_tank_static.mat";
const fs::path kSeaNetLog = fs::path(SONARMAP_SHARED_DATA) / "seanet_sector_target.V4LOG";

std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

using cliConvert = CliTest;

TEST_F(cliConvert, MatAsBeamCsvMapsToTheIdenticalOctree) {
  if (!fs::exists(kCrasLog)) GTEST_SKIP() << "shared data absent: " << kCrasLog;
  const fs::path csv = out_ / "cras.csv";
  const ProgramRun converted = run({"convert", kCrasLog.string(), "-o", csv.string()});
  ASSERT_EQ(converted.exit_code, 0) << converted.err;
  // The .mat reader skips one malformed beam of the 5,604 (it reports why); the CSV holds the rest.
  EXPECT_EQ(linesOf(converted.out), Names{"5603 beams written, 1 skipped -> " + csv.string()});
  const fs::path from_mat = out_ / "mat.bt", from_csv = out_ / "csv.bt";
  ASSERT_EQ(run({"map", kCrasLog.string(), "-o", from_mat.string(), "-q"}).exit_code, 0);
  ASSERT_EQ(run({"map", csv.string(), "-o", from_csv.string(), "-q"}).exit_code, 0);
  EXPECT_EQ(bytesOf(from_mat), bytesOf(from_csv));
  EXPECT_GT(fs::file_size(from_mat), 1000U);
}

// The SeaNet log records its intensity span (ADspan): the CSV keeps it, so the converted log is
// calibrated on the same dB scale and maps to the identical octree.
TEST_F(cliConvert, SeaNetLogBecomesOneRowPerBeamAndMapsToTheIdenticalOctree) {
  if (!fs::exists(kSeaNetLog)) GTEST_SKIP() << "shared data absent: " << kSeaNetLog;
  const fs::path csv = out_ / "seanet.csv";
  const ProgramRun converted = run({"convert", kSeaNetLog.string(), "-o", csv.string()});
  ASSERT_EQ(converted.exit_code, 0) << converted.err;
  const Names rows = linesOf(bytesOf(csv));
  ASSERT_EQ(rows.size(), 469U);  // header + 468 beams
  EXPECT_EQ(rows[0].rfind("time_s,bearing_deg,bin_length_m,intensity_span_db,gain_setting,b0,b1,", 0), 0U) << rows[0];
  const fs::path from_log = out_ / "v4.bt", from_csv = out_ / "csv.bt";
  ASSERT_EQ(run({"map", kSeaNetLog.string(), "-o", from_log.string(), "-q"}).exit_code, 0);
  ASSERT_EQ(run({"map", csv.string(), "-o", from_csv.string(), "-q"}).exit_code, 0);
  EXPECT_EQ(bytesOf(from_log), bytesOf(from_csv));
}

// The SeaNet log as the packets its head sent (a .seanet wire capture), and under another name with
// --format: the identical octree. The CRAS log as a Ping360 stream maps with the Ping360's 2° beam
// by default, as with --beam-width 2 given.
TEST_F(cliConvert, LogsAsWireCapturesMapLikeTheLogs) {
  if (!fs::exists(kSeaNetLog) || !fs::exists(kCrasLog)) GTEST_SKIP() << "shared data absent";
  const fs::path capture = out_ / "sector.seanet", renamed = out_ / "sector.raw";
  ASSERT_EQ(run({"convert", kSeaNetLog.string(), "-o", capture.string()}).exit_code, 0);
  fs::copy_file(capture, renamed);
  const fs::path from_log = out_ / "v4.bt", from_wire = out_ / "wire.bt", from_raw = out_ / "raw.bt";
  ASSERT_EQ(run({"map", kSeaNetLog.string(), "-o", from_log.string(), "-q"}).exit_code, 0);
  ASSERT_EQ(run({"map", capture.string(), "-o", from_wire.string(), "-q"}).exit_code, 0);
  ASSERT_EQ(run({"map", renamed.string(), "--format", "seanet", "-o", from_raw.string(), "-q"}).exit_code, 0);
  EXPECT_EQ(bytesOf(from_log), bytesOf(from_wire));
  EXPECT_EQ(bytesOf(from_log), bytesOf(from_raw));
  expectError(run({"map", renamed.string(), "-o", (out_ / "no.bt").string(), "-q"}), 1);  // unknown extension

  const fs::path ping = out_ / "cras.bin";
  ASSERT_EQ(run({"convert", kCrasLog.string(), "-o", ping.string()}).exit_code, 0);
  const fs::path by_default = out_ / "p.bt", two = out_ / "p2.bt", three = out_ / "p3.bt";
  ASSERT_EQ(run({"map", ping.string(), "-o", by_default.string(), "-q"}).exit_code, 0);
  ASSERT_EQ(run({"map", ping.string(), "--beam-width", "2", "-o", two.string(), "-q"}).exit_code, 0);
  ASSERT_EQ(run({"map", ping.string(), "--beam-width", "3", "-o", three.string(), "-q"}).exit_code, 0);
  EXPECT_EQ(bytesOf(by_default), bytesOf(two));
  EXPECT_NE(bytesOf(by_default), bytesOf(three));
}

TEST_F(cliConvert, BadArgumentsAndInputsFailWithOneLineAndWriteNothing) {
  const fs::path input = root_ / "broken.csv";
  std::ofstream(input) << "time_s,bearing_deg,bin_length_m,b0\n0,10,0.01,300\n";  // 300 > 255
  expectError(run({"convert", input.string(), "-o", (out_ / "x.bt").string()}), 2);   // not a .csv, .seanet or .bin output
  expectError(run({"convert", input.string(), "-o", (out_ / "x.csv").string()}), 1);  // bad intensity
  expectError(run({"convert", (root_ / "missing.mat").string(), "-o", (out_ / "y.csv").string()}), 1);
  EXPECT_TRUE(fs::is_empty(out_));
}

}  // namespace
}  // namespace sonarmap::test
