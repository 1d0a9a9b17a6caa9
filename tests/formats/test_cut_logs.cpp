/// Every shared log cut short at 10 places (../shared/data; skipped without it), as a full disk, a
/// pulled cable or a killed recorder leave them (docs/reliability.md): the beams read from the cut
/// file are the first beams of the whole file, each the same, as many as the whole records before
/// the cut hold, and a skip reason says where the file was cut; a cut that leaves nothing usable is
/// a FileError naming the byte. The scan graph (one node) and the point scans (gzip) are refused.

#include <gtest/gtest.h>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bag_bytes.hpp"
#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/io/scan_graph.hpp"
#include "sonarmap/slam/point_scans.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;

constexpr int kCuts = 10;

std::string shared(const std::string& name) { return std::string(SONARMAP_SHARED_DATA) + "/" + name; }

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The 10 places a file of `size` bytes is cut at: k/11 of it, k = 1 … 10.
std::vector<std::size_t> cutsOf(std::size_t size) {
  std::vector<std::size_t> cuts;
  for (int k = 1; k <= kCuts; ++k) cuts.push_back(size * static_cast<std::size_t>(k) / (kCuts + 1));
  return cuts;
}

/// Writes the first `cut` bytes of `bytes` as `name` in `dir`.
std::string cutFile(const test::TempDir& dir, const std::string& name, const std::string& bytes, std::size_t cut) {
  const std::string path = dir.file(name);
  std::ofstream(path, std::ios::binary) << bytes.substr(0, cut);
  return path;
}

/// `cut`'s beams are the first of `whole`'s, each the same.
void expectPrefix(const SonarLog& cut, const SonarLog& whole, const std::string& what) {
  ASSERT_LE(cut.beams.size(), whole.beams.size()) << what;
  for (std::size_t i = 0; i < cut.beams.size(); ++i) {
    const Beam& a = cut.beams[i];
    const Beam& b = whole.beams[i];
    ASSERT_EQ(a.time_s, b.time_s) << what << ", beam " << i;
    ASSERT_EQ(a.bearing_rad, b.bearing_rad) << what << ", beam " << i;
    ASSERT_EQ(a.bin_length_m, b.bin_length_m) << what << ", beam " << i;
    ASSERT_EQ(a.intensities, b.intensities) << what << ", beam " << i;
  }
}

/// Whether a skip reason of `log` contains `part`.
bool skipSays(const SonarLog& log, const std::string& part) {
  for (const std::string& reason : log.skip_reasons) {
    if (reason.find(part) != std::string::npos) return true;
  }
  return false;
}

/// Reads every cut of the shared log `name` as readSonarLog reads it; `expected(cut)` gives the
/// beams the cut must keep, or nothing when it must be refused.
void checkCuts(const std::string& name, const std::function<std::optional<std::size_t>(std::size_t)>& expected,
               const std::string& warning) {
  const std::string path = shared(name);
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  const std::string bytes = readBytes(path);
  const SonarLog whole = readSonarLog(path);
  const test::TempDir dir;
  for (const std::size_t cut : cutsOf(bytes.size())) {
    const std::string what = name + " cut at " + std::to_string(cut);
    const std::string file = cutFile(dir, "cut" + fs::path(name).extension().string(), bytes, cut);
    const std::optional<std::size_t> count = expected(cut);
    if (!count) {
      try {
        readSonarLog(file);
        ADD_FAILURE() << what << ": read, expected a refusal";
      } catch (const FileError& error) {
        EXPECT_NE(std::string(error.what()).find("byte "), std::string::npos) << what << ": " << error.what();
      }
      continue;
    }
    const SonarLog log = readSonarLog(file);
    expectPrefix(log, whole, what);
    EXPECT_EQ(log.beams.size(), *count) << what;
    EXPECT_TRUE(skipSays(log, warning)) << what << ": no skip reason says '" << warning << "'";
  }
}

TEST(formatsCutLogs, SeaNetV4LogKeepsEveryWholeRecord) {
  // record lengths from the data offset (uint32 at byte 40), a uint16 at each record's start;
  // every record of the shared log is an mtHeadData beam
  const std::string path = shared("seanet_sector_target.V4LOG");
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  const std::string bytes = readBytes(path);
  const std::uint32_t data_offset = test::bagU32(bytes, 40), records = test::bagU32(bytes, 44);
  std::vector<std::size_t> ends;
  for (std::size_t at = data_offset; ends.size() < records; at = ends.back()) {
    ends.push_back(at + static_cast<unsigned char>(bytes[at]) + 256u * static_cast<unsigned char>(bytes[at + 1]));
  }
  checkCuts("seanet_sector_target.V4LOG", [&](std::size_t cut) -> std::optional<std::size_t> {
    if (cut < data_offset || cut < ends.front()) return std::nullopt;  // in the header, or no whole record
    return static_cast<std::size_t>(std::count_if(ends.begin(), ends.end(), [&](std::size_t end) { return end <= cut; }));
  }, "(cut short); the last ");
}

TEST(formatsCutLogs, RosBagKeepsEveryWholeMessage) {
  const std::string path = shared("micron_pool_ros1.bag");
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  const std::string bytes = readBytes(path);
  const std::vector<test::BagBytesMessage> messages = test::bagMessages(bytes);
  std::map<std::uint32_t, std::size_t> per_connection;
  for (const test::BagBytesMessage& message : messages) ++per_connection[message.connection];
  const auto sonar = std::max_element(per_connection.begin(), per_connection.end(),
                                      [](const auto& a, const auto& b) { return a.second < b.second; });
  checkCuts("micron_pool_ros1.bag", [&](std::size_t cut) -> std::optional<std::size_t> {
    return test::bagMessagesBefore(messages, cut, sonar->first);
  }, "(cut short); its records read to byte ");
}

/// The byte each record of a Ping Viewer log starts at (header: QStrings of a uint32 big-endian
/// length, an int32 version, five QStrings, two int32; records: a QString time, a QByteArray).
std::vector<std::size_t> viewerRecordStarts(const std::string& bytes) {
  const auto be32 = [&](std::size_t at) {
    return (std::uint32_t{static_cast<unsigned char>(bytes[at])} << 24) | (std::uint32_t{static_cast<unsigned char>(bytes[at + 1])} << 16) |
           (std::uint32_t{static_cast<unsigned char>(bytes[at + 2])} << 8) | static_cast<unsigned char>(bytes[at + 3]);
  };
  const auto skipString = [&](std::size_t at) { return at + 4 + (be32(at) == 0xFFFFFFFFU ? 0 : be32(at)); };
  std::size_t at = skipString(0) + 4;
  for (int i = 0; i < 5; ++i) at = skipString(at);
  at += 8;
  std::vector<std::size_t> starts;
  while (at + 4 <= bytes.size()) {
    starts.push_back(at);
    const std::size_t data = skipString(at);
    if (data + 4 > bytes.size()) break;
    at = skipString(data);
  }
  return starts;
}

/// A Ping Viewer log cut inside a record reads as the same log cut where that record starts: the
/// messages of the whole records before it (a message spans records: the serial link's chunks).
void checkViewerLog(const std::string& name) {
  const std::string path = shared(name);
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  const std::string bytes = readBytes(path);
  const std::vector<std::size_t> starts = viewerRecordStarts(bytes);
  const test::TempDir dir;
  checkCuts(name, [&](std::size_t cut) -> std::optional<std::size_t> {
    const std::size_t record = *(std::upper_bound(starts.begin(), starts.end(), cut) - 1);
    return readSonarLog(cutFile(dir, "boundary.bin", bytes, record)).beams.size();
  }, "bytes skipped");  // "record N at byte B: data of N bytes, the file ends M bytes after their start; the last K bytes skipped"
}

TEST(formatsCutLogs, PingViewerBasinLogKeepsTheMessagesOfItsWholeRecords) { checkViewerLog("ping360_basin.bin"); }

TEST(formatsCutLogs, PingViewerHarbourLogKeepsTheMessagesOfItsWholeRecords) {
  checkViewerLog("ping360_harbour_range_changes.bin");
}

/// What inflates from `compressed` (a zlib stream, cut short or not).
std::string inflated(const std::string& compressed) {
  z_stream stream{};
  inflateInit(&stream);
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = static_cast<uInt>(compressed.size());
  std::string out;
  char buffer[1 << 16];
  int status = Z_OK;
  while (status == Z_OK) {
    stream.next_out = reinterpret_cast<Bytef*>(buffer);
    stream.avail_out = sizeof buffer;
    status = inflate(&stream, Z_NO_FLUSH);
    out.append(buffer, sizeof buffer - stream.avail_out);
    if (stream.avail_out == sizeof buffer) break;  // no progress: the input ran out
  }
  inflateEnd(&stream);
  return out;
}

TEST(formatsCutLogs, CrasMatKeepsTheWholeElementsOfItsCompressedVariable) {
  // One compressed variable (an miCOMPRESSED element at byte 128): what inflates from the bytes
  // before the cut is its miMATRIX; the struct's elements are its whole miMATRIX subelements (four
  // fields each) after its flags, dimensions, name and field names (MAT-File Format, version 5).
  const std::string path = shared("cras_micron_tank_static.mat");
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
  const std::string bytes = readBytes(path);
  checkCuts("cras_micron_tank_static.mat", [&](std::size_t cut) -> std::optional<std::size_t> {
    const std::string matrix = inflated(bytes.substr(136, cut - 136));
    std::size_t whole_fields = 0;
    for (std::size_t at = 8; at + 8 <= matrix.size();) {
      const std::uint32_t word = test::bagU32(matrix, at);
      const std::size_t size = (word >> 16) != 0 ? 0 : test::bagU32(matrix, at + 4);
      const std::size_t next = at + 8 + ((word >> 16) != 0 ? 0 : (size + 7) / 8 * 8);
      if (at + 8 + size > matrix.size()) break;
      whole_fields += word == 14;
      at = next;
    }
    return whole_fields / 4 > 0 ? std::optional<std::size_t>(whole_fields / 4) : std::nullopt;
  }, "(cut short): the first ");
}

TEST(formatsCutLogs, TheScanGraphAndThePointScansAreRefusedNamingTheCut) {
  // One node of 10,201 points: any cut leaves no whole node. The point scans are one gzip member:
  // a cut member is refused by the gzip reader (text_input.hpp).
  const test::TempDir dir;
  for (const auto& [name, read] : std::vector<std::pair<std::string, std::function<void(const std::string&)>>>{
           {"octomap_spherical_scan.graph", [](const std::string& f) { readScanGraph(f); }},
           {"stpere_marina/scans.csv.gz", [](const std::string& f) { readPointScansCsv(f); }}}) {
    const std::string path = shared(name);
    if (!fs::exists(path)) GTEST_SKIP() << "no " << path;
    const std::string bytes = readBytes(path);
    for (const std::size_t cut : cutsOf(bytes.size())) {
      const std::string file = cutFile(dir, fs::path(name).filename().string(), bytes, cut);
      EXPECT_THROW(read(file), FileError) << name << " cut at " << cut;
    }
  }
}

}  // namespace
}  // namespace sonarmap
