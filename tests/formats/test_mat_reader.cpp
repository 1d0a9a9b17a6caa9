/// Tests of readCrasMat: the real CRAS log, synthetic MAT-files with malformed beams, file errors.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>

#include "mat_fixture.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/mat_reader.hpp"
#include "common/temp_dir.hpp"

namespace sonarmap {
namespace {

using test::MatBeam;
using test::TempDir;

constexpr double kPi = std::numbers::pi;
const std::string kCrasLog = std::string(SONARMAP_SHARED_DATA) + "/cras_micron_tank_static.mat";

double degrees(double rad) { return rad * 180.0 / kPi; }

std::vector<MatBeam> threeGoodBeams() {
  std::vector<MatBeam> beams(3);
  for (int i = 0; i < 3; ++i) {
    beams[i].time = 1.0 + i;
    beams[i].angle = 10.0 * i;
    beams[i].intensities = std::vector<double>(10, 5.0 * i);
  }
  return beams;
}

TEST(sonarMatReader, ReadsTheRealCrasLog) {
  if (!std::filesystem::exists(kCrasLog)) GTEST_SKIP() << "no shared data at " << kCrasLog;
  const SonarLog log = readCrasMat(kCrasLog);
  ASSERT_EQ(log.beams.size(), 5603u);  // 5,604 in the file, the last one has 186 bins
  EXPECT_EQ(log.skipped_beams, 1u);
  ASSERT_EQ(log.skip_reasons.size(), 1u);
  EXPECT_NE(log.skip_reasons[0].find("parsedData(5604)"), std::string::npos) << log.skip_reasons[0];
  EXPECT_NE(log.skip_reasons[0].find("186 bins"), std::string::npos) << log.skip_reasons[0];
  for (const Beam& beam : log.beams) {
    ASSERT_EQ(beam.intensities.size(), 399u);
    ASSERT_NEAR(beam.bin_length_m, 0.0125313, 1e-6);
    ASSERT_GE(beam.bearing_rad, 0.0);
    ASSERT_LT(beam.bearing_rad, 2.0 * kPi);
  }
  // angle 180° → bearing radians(180 + 180) wrapped = 0; then +1.8° per beam.
  EXPECT_NEAR(degrees(log.beams[0].bearing_rad), 0.0, 1e-4);
  EXPECT_NEAR(degrees(log.beams[1].bearing_rad), 1.8, 1e-4);
  EXPECT_NEAR(degrees(log.beams[100].bearing_rad), 180.0, 1e-3);  // angle 0° (after the wrap 358.2 → 0)
  EXPECT_NEAR(log.beams[0].time_s, 10.28, 0.01);
  EXPECT_NEAR(log.beams.back().time_s, 249.92, 0.01);
}

TEST(sonarMatReader, ReadsSyntheticBeamsAndConvertsBearings) {
  TempDir dir;
  auto beams = threeGoodBeams();
  beams[2].angle = -200.0;  // −200 + 180 = −20 → 340°
  beams[1].intensity_class = MAT_C_DOUBLE;  // the published file stores doubles
  test::writeCrasMat(dir.file("ok.mat"), beams);
  const SonarLog log = readCrasMat(dir.file("ok.mat"));
  ASSERT_EQ(log.beams.size(), 3u);
  EXPECT_EQ(log.skipped_beams, 0u);
  EXPECT_NEAR(degrees(log.beams[0].bearing_rad), 180.0, 1e-9);
  EXPECT_NEAR(degrees(log.beams[1].bearing_rad), 190.0, 1e-9);
  EXPECT_NEAR(degrees(log.beams[2].bearing_rad), 340.0, 1e-9);
  EXPECT_EQ(log.beams[1].intensities, std::vector<std::uint8_t>(10, 5));
  EXPECT_DOUBLE_EQ(log.beams[2].time_s, 3.0);
}

TEST(sonarMatReader, SkipsMalformedBeamsWithReasons) {
  TempDir dir;
  auto beams = threeGoodBeams();
  for (int i = 0; i < 5; ++i) beams.push_back(threeGoodBeams()[0]);
  beams[3].intensities.resize(4);               // bin count differs from the dominant 10
  beams[4].time = std::nan("");                 // not finite
  beams[5].step_dist = 0.0;                     // bin length ≤ 0
  beams[6].scalar_class = MAT_C_INT16;          // wrong class
  beams[7].intensities[2] = 300.0;              // not a byte
  beams[7].intensity_class = MAT_C_DOUBLE;
  test::writeCrasMat(dir.file("mixed.mat"), beams);
  const SonarLog log = readCrasMat(dir.file("mixed.mat"));
  EXPECT_EQ(log.beams.size(), 3u);
  EXPECT_EQ(log.skipped_beams, 5u);
  ASSERT_EQ(log.skip_reasons.size(), 5u);
  EXPECT_NE(log.skip_reasons[0].find("4 bins"), std::string::npos) << log.skip_reasons[0];
  EXPECT_NE(log.skip_reasons[1].find("'time' is not finite"), std::string::npos) << log.skip_reasons[1];
  EXPECT_NE(log.skip_reasons[2].find("'step_dist'"), std::string::npos) << log.skip_reasons[2];
  EXPECT_NE(log.skip_reasons[3].find("is int16, expected single"), std::string::npos) << log.skip_reasons[3];
  EXPECT_NE(log.skip_reasons[4].find("[0, 255]"), std::string::npos) << log.skip_reasons[4];
}

TEST(sonarMatReader, ACompressedLogReadsAsItsUncompressedTwin) {
  // Compressed variables are read from their inflated copy: the beams and the skip reasons must be
  // those of the same log written uncompressed.
  TempDir dir;
  auto beams = threeGoodBeams();
  for (int i = 0; i < 3; ++i) beams.push_back(threeGoodBeams()[1]);
  beams[3].intensities.resize(4);
  beams[4].scalar_class = MAT_C_INT16;
  beams[5].intensities[2] = 300.0;
  beams[5].intensity_class = MAT_C_DOUBLE;
  const std::vector<const char*> fields = {"time", "angle", "step_dist", "intensities"};
  test::writeCrasMat(dir.file("log.mat"), beams, fields, "parsedData", MAT_COMPRESSION_NONE);
  test::writeCrasMat(dir.file("log_z.mat"), beams, fields, "parsedData", MAT_COMPRESSION_ZLIB);
  ASSERT_LT(std::filesystem::file_size(dir.file("log_z.mat")), std::filesystem::file_size(dir.file("log.mat")));
  const SonarLog plain = readCrasMat(dir.file("log.mat"));
  const SonarLog packed = readCrasMat(dir.file("log_z.mat"));
  ASSERT_EQ(packed.beams.size(), plain.beams.size());
  EXPECT_EQ(plain.beams.size(), 3u);
  for (std::size_t i = 0; i < plain.beams.size(); ++i) {
    EXPECT_EQ(packed.beams[i].time_s, plain.beams[i].time_s);
    EXPECT_EQ(packed.beams[i].bearing_rad, plain.beams[i].bearing_rad);
    EXPECT_EQ(packed.beams[i].bin_length_m, plain.beams[i].bin_length_m);
    EXPECT_EQ(packed.beams[i].intensities, plain.beams[i].intensities);
  }
  ASSERT_EQ(packed.skip_reasons.size(), 3u);
  for (std::size_t i = 0; i < packed.skip_reasons.size(); ++i) {
    std::string reason = plain.skip_reasons[i];
    reason.replace(reason.find("log.mat"), 7, "log_z.mat");
    EXPECT_EQ(packed.skip_reasons[i], reason);
  }
}

TEST(sonarMatReader, DoublesStoredAsBytesReadFromAnUncompressedFile) {
  // MATLAB stores a double array of whole counts as bytes: the declared doubles take 8 times the
  // bytes the file holds for them, which the size check must believe.
  TempDir dir;
  auto beams = threeGoodBeams();
  for (MatBeam& beam : beams) {
    beam.intensities = std::vector<double>(400, 7.0);
    beam.intensity_class = MAT_C_DOUBLE;
    beam.intensities_stored_as_bytes = true;
  }
  test::writeCrasMat(dir.file("bytes.mat"), beams);
  ASSERT_LT(std::filesystem::file_size(dir.file("bytes.mat")), 3u * 400u * 8u);
  const SonarLog log = readCrasMat(dir.file("bytes.mat"));
  ASSERT_EQ(log.beams.size(), 3u);
  EXPECT_EQ(log.beams[2].intensities, std::vector<std::uint8_t>(400, 7));
}

TEST(sonarMatReader, NonExistentFileIsFileError) {
  TempDir dir;
  const std::string path = dir.file("missing.mat");
  try {
    readCrasMat(path);
    FAIL() << "expected FileError";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(sonarMatReader, NonMatFileIsFileError) {
  TempDir dir;
  std::ofstream(dir.file("text.mat")) << "this is not a MAT-file\n";
  EXPECT_THROW(readCrasMat(dir.file("text.mat")), FileError);
  std::ofstream(dir.file("empty.mat")).close();
  EXPECT_THROW(readCrasMat(dir.file("empty.mat")), FileError);
}

TEST(sonarMatReader, FileLevelProblemsAreFileErrors) {
  TempDir dir;
  test::writeDoubleMat(dir.file("other.mat"), "somethingElse", {1.0, 2.0});
  EXPECT_THROW(readCrasMat(dir.file("other.mat")), FileError);  // no parsedData
  test::writeDoubleMat(dir.file("notstruct.mat"), "parsedData", {1.0, 2.0});
  EXPECT_THROW(readCrasMat(dir.file("notstruct.mat")), FileError);
  test::writeCrasMat(dir.file("nofield.mat"), threeGoodBeams(), {"time", "step_dist", "intensities"});
  try {
    readCrasMat(dir.file("nofield.mat"));
    FAIL() << "expected FileError";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("'angle'"), std::string::npos) << e.what();
  }
  auto bad = threeGoodBeams();
  for (auto& b : bad) b.step_dist = -1.0;
  test::writeCrasMat(dir.file("allbad.mat"), bad);
  EXPECT_THROW(readCrasMat(dir.file("allbad.mat")), FileError);  // no valid beam at all
}

TEST(sonarMatReader, AFileCutShortReadsTheWholeElementsBeforeTheCut) {
  TempDir dir;
  std::vector<MatBeam> beams(40);
  for (std::size_t i = 0; i < beams.size(); ++i) {
    beams[i].time = 10.0 + 0.05 * static_cast<double>(i);
    beams[i].angle = 1.8 * static_cast<double>(i);
    beams[i].intensities = std::vector<double>(12, static_cast<double>(i));
  }
  for (const matio_compression compression : {MAT_COMPRESSION_NONE, MAT_COMPRESSION_ZLIB}) {
    const std::string whole_path = dir.file("whole.mat");
    test::writeCrasMat(whole_path, beams, {"time", "angle", "step_dist", "intensities"}, "parsedData", compression);
    const SonarLog whole = readCrasMat(whole_path);
    ASSERT_EQ(whole.beams.size(), beams.size());
    std::ifstream in(whole_path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::size_t previous = 0;
    std::vector<std::size_t> cuts;
    for (std::size_t cut = 129; cut < bytes.size(); cut += 61) cuts.push_back(cut);
    cuts.push_back(bytes.size() - 1);  // in the last element (in the stream's checksum when compressed)
    for (const std::size_t cut : cuts) {
      const std::string path = dir.file("cut.mat");
      std::ofstream(path, std::ios::binary) << bytes.substr(0, cut);
      try {
        const SonarLog log = readCrasMat(path);
        ASSERT_GE(log.beams.size(), previous) << "cut at " << cut;  // more file, never fewer beams
        // all of them when only a compressed stream's checksum is cut
        ASSERT_LE(log.beams.size(), beams.size()) << "cut at " << cut;
        previous = log.beams.size();
        for (std::size_t i = 0; i < log.beams.size(); ++i) {
          ASSERT_EQ(log.beams[i].intensities, whole.beams[i].intensities) << "cut at " << cut;
          ASSERT_EQ(log.beams[i].bearing_rad, whole.beams[i].bearing_rad) << "cut at " << cut;
          ASSERT_EQ(log.beams[i].time_s, whole.beams[i].time_s) << "cut at " << cut;
        }
        ASSERT_EQ(log.skip_reasons.size(), 1u);
        EXPECT_NE(log.skip_reasons[0].find("(cut short): the first " + std::to_string(log.beams.size()) +
                                           " of the 40 elements of 'parsedData' read, the rest skipped"),
                  std::string::npos) << log.skip_reasons[0];
      } catch (const FileError& error) {  // nothing whole yet: said so
        ASSERT_EQ(previous, 0u) << "cut at " << cut << ": " << error.what();
        EXPECT_NE(std::string(error.what()).find("cut short"), std::string::npos) << error.what();
      }
    }
    EXPECT_GE(previous, beams.size() - 1) << "a cut in the last element keeps the others";
  }
}

TEST(sonarMatReader, TruncatedFileDoesNotCrash) {
  if (!std::filesystem::exists(kCrasLog)) GTEST_SKIP() << "no shared data at " << kCrasLog;
  TempDir dir;
  for (std::size_t size : {100u, 200u, 5000u, 800000u}) {
    const std::string path = dir.file("trunc" + std::to_string(size) + ".mat");
    std::filesystem::copy_file(kCrasLog, path);
    std::filesystem::resize_file(path, size);
    try {
      const SonarLog log = readCrasMat(path);
      EXPECT_LT(log.beams.size(), 5603u);  // a cut log loses beams, and says so
      EXPECT_GT(log.skipped_beams, 0u);
    } catch (const FileError&) {
      // also acceptable: the cut removed the variable
    }
  }
}

}  // namespace
}  // namespace sonarmap
