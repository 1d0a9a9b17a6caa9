/// @file test_text_input.cpp
/// openTextInput (io/text_input.hpp): plain and gzip-compressed text read the same; truncated,
/// corrupt and mislabelled gzip files fail with a FileError naming the file; the CSV readers
/// (point scans, navigation, beams) read `.csv.gz` as `.csv`.

#include <gtest/gtest.h>
#include <zlib.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/io/text_input.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/slam/point_scans.hpp"

namespace sonarmap {
namespace {

/// `text` as one gzip member (zlib's deflate with the gzip wrapper: windowBits 15 + 16).
std::string gzipped(const std::string& text) {
  z_stream stream{};
  EXPECT_EQ(deflateInit2(&stream, Z_BEST_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&stream, static_cast<uLong>(text.size())) + 32, '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  stream.avail_in = static_cast<uInt>(text.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&stream, Z_FINISH), Z_STREAM_END);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string readAll(const std::string& path) {
  const auto in = openTextInput(path);
  return std::string(std::istreambuf_iterator<char>(*in), std::istreambuf_iterator<char>());
}

/// Lines of numbers, larger than the reader's 64 KiB chunks many times over.
std::string largeText() {
  std::string text = "scan,time_s,x_m,y_m\n";
  for (int i = 0; i < 40000; ++i) {
    text += std::to_string(i / 1000) + "," + std::to_string(0.01 * i) + "," + std::to_string(1.0 + (i % 97) * 0.1) + ",-0.5\n";
  }
  return text;
}

TEST(textInput, PlainTextReadsAsItIs) {
  test::TempDir dir;
  const std::string text = "time_s,x_m\r\n1,2\n";
  writeFile(dir.file("plain.csv"), text);
  EXPECT_EQ(readAll(dir.file("plain.csv")), text);
}

TEST(textInput, GzipReadsAsTheTextItHolds) {
  test::TempDir dir;
  const std::string text = largeText();
  writeFile(dir.file("big.csv.gz"), gzipped(text));
  EXPECT_EQ(readAll(dir.file("big.csv.gz")), text);
  // The content decides, not the name: gzip bytes under a plain name are inflated too.
  writeFile(dir.file("big.csv"), gzipped(text));
  EXPECT_EQ(readAll(dir.file("big.csv")), text);
}

TEST(textInput, ConcatenatedMembersReadAsOneText) {
  test::TempDir dir;
  writeFile(dir.file("two.csv.gz"), gzipped("first,line\n") + gzipped("second,line\n"));
  EXPECT_EQ(readAll(dir.file("two.csv.gz")), "first,line\nsecond,line\n");
}

TEST(textInput, TruncatedGzipFailsNamingTheFile) {
  test::TempDir dir;
  const std::string packed = gzipped(largeText());
  for (const std::size_t keep : {packed.size() / 3, packed.size() - 4, std::size_t{12}}) {
    const std::string path = dir.file("cut.csv.gz");
    writeFile(path, packed.substr(0, keep));
    try {
      readAll(path);
      ADD_FAILURE() << "a gzip file cut to " << keep << " bytes read without error";
    } catch (const FileError& error) {
      EXPECT_NE(std::string(error.what()).find("truncated gzip data"), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    }
  }
}

TEST(textInput, CorruptGzipFails) {
  test::TempDir dir;
  std::string packed = gzipped(largeText());
  for (std::size_t i = 100; i < 140; ++i) packed[i] = static_cast<char>(packed[i] ^ 0x5A);
  writeFile(dir.file("bad.csv.gz"), packed);
  EXPECT_THROW(readAll(dir.file("bad.csv.gz")), FileError);
}

TEST(textInput, NamedGzButNotGzipFailsAtOpening) {
  test::TempDir dir;
  writeFile(dir.file("text.csv.gz"), "scan,time_s,x_m,y_m\n0,0,1,1\n");
  try {
    openTextInput(dir.file("text.csv.gz"));
    ADD_FAILURE() << "a text file named .gz was opened";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find("not gzip-compressed"), std::string::npos) << error.what();
  }
  EXPECT_THROW(openTextInput(dir.file("missing.csv.gz")), FileError);
}

TEST(textInput, CsvReadersReadGzipAsPlain) {
  test::TempDir dir;
  const std::string scans = largeText();
  writeFile(dir.file("scans.csv"), scans);
  writeFile(dir.file("scans.csv.gz"), gzipped(scans));
  const std::vector<BodyPoint> plain = readPointScansCsv(dir.file("scans.csv"));
  const std::vector<BodyPoint> packed = readPointScansCsv(dir.file("scans.csv.gz"));
  ASSERT_EQ(plain.size(), packed.size());
  for (std::size_t i = 0; i < plain.size(); ++i) {
    EXPECT_EQ(plain[i].scan, packed[i].scan);
    EXPECT_EQ(plain[i].time_s, packed[i].time_s);
    EXPECT_EQ(plain[i].xy_m, packed[i].xy_m);
  }
  const std::string nav = "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n0,0,0,1,0,0,0\n20,1,0.5,1,0.01,0,0.1\n";
  writeFile(dir.file("nav.csv.gz"), gzipped(nav));
  const NavTrack track = readNavCsv(dir.file("nav.csv.gz"));
  ASSERT_EQ(track.size(), 2u);
  EXPECT_DOUBLE_EQ(track[1].yaw_rad, 0.1);
  const std::string beams = "time_s,bearing_deg,bin_length_m,b0,b1,b2,b3\n10.0,0,0.05,0,10,200,30\n10.05,1.8,0.05,0,12,190,25\n";
  writeFile(dir.file("beams.csv.gz"), gzipped(beams));
  ASSERT_EQ(logFormatOfPath(dir.file("beams.csv.gz")), LogFormat::kCsv);
  const SonarLog log = readSonarLog(dir.file("beams.csv.gz"));
  ASSERT_EQ(log.beams.size(), 2u);
  EXPECT_EQ(log.beams[1].intensities[2], 190);
}

}  // namespace
}  // namespace sonarmap
