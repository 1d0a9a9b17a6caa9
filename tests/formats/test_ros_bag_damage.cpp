/// Tests of ROS 1 bags read up to their damage (ros_bag_scan.hpp, docs/reliability.md): a bag cut
/// short at every place, one left unindexed by a stopped `rosbag record` (its chunks plain, bz2 or
/// lz4), and files that leave nothing usable.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "bag_bytes.hpp"
#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"
#include "sonarmap/formats/ros_bag_writer.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {
namespace {

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string writeBytes(const test::TempDir& dir, const std::string& name, const std::string& bytes) {
  std::ofstream(dir.file(name), std::ios::binary) << bytes;
  return dir.file(name);
}

/// A simulated tank of `turns` turns written as a bag (stamps of 2014: seconds since 1970).
std::string tankBag(const test::TempDir& dir, std::size_t turns, BagCompression compression = BagCompression::kNone) {
  MsisSimulationOptions options;
  options.turns = turns;
  SonarLog log = simulateMsis(builtinScene("tank"), options).log;
  for (Beam& beam : log.beams) beam.time_s += 1.4e9;
  writeRosBag(dir.file("whole.bag"), log, {}, {.compression = compression});
  return readBytes(dir.file("whole.bag"));
}

bool has(const std::vector<std::string>& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& line) { return line.find(part) != std::string::npos; });
}

/// `cut` holds the first beams of `whole`, each the same.
void expectPrefix(const SonarLog& cut, const SonarLog& whole, std::size_t count) {
  ASSERT_EQ(cut.beams.size(), count);
  for (std::size_t i = 0; i < count; ++i) {
    ASSERT_EQ(cut.beams[i].intensities, whole.beams[i].intensities) << "beam " << i;
    ASSERT_EQ(cut.beams[i].bearing_rad, whole.beams[i].bearing_rad) << "beam " << i;
    ASSERT_EQ(cut.beams[i].time_s, whole.beams[i].time_s) << "beam " << i;
    ASSERT_EQ(cut.beams[i].bin_length_m, whole.beams[i].bin_length_m) << "beam " << i;
  }
}

TEST(formatsRosBagDamage, ABagCutShortReadsEveryWholeMessageBeforeTheCut) {
  const test::TempDir dir;
  const std::string bag = tankBag(dir, 1);
  const SonarLog whole = readRosBag(dir.file("whole.bag"));
  const std::vector<test::BagBytesMessage> messages = test::bagMessages(bag);
  ASSERT_EQ(messages.size(), whole.beams.size());
  for (std::size_t cut = 14; cut < bag.size(); cut += bag.size() / 40 + 1) {
    const std::string path = writeBytes(dir, "cut.bag", bag.substr(0, cut));
    const std::size_t before = test::bagMessagesBefore(messages, cut);
    if (before == 0) {  // nothing usable: the damage named
      try {
        readRosBag(path);
        FAIL() << "cut at " << cut << ": read without a whole message";
      } catch (const FileError& error) {
        EXPECT_NE(std::string(error.what()).find("ROS bag: byte "), std::string::npos) << error.what();
      }
      continue;
    }
    const SonarLog log = readRosBag(path);
    expectPrefix(log, whole, before);
    if (cut < messages.back().end) {
      ASSERT_EQ(log.skip_reasons.size(), 1u) << "cut at " << cut;
      EXPECT_NE(log.skip_reasons[0].find("(cut short); its records read to byte "), std::string::npos) << log.skip_reasons[0];
    }
    EXPECT_TRUE(has(log.notes, "read by scanning its chunks from the start")) << "cut at " << cut;
  }
}

TEST(formatsRosBagDamage, AStoppedRecordingIsReadByScanningItsChunks) {
  const test::TempDir dir;
  const std::string bag = tankBag(dir, 4);
  const SonarLog whole = readRosBag(dir.file("whole.bag"));
  std::vector<test::BagBytesRecord> chunks;
  for (const test::BagBytesRecord& record : test::bagRecords(bag, 13, bag.size())) {
    if (record.op == 0x05) chunks.push_back(record);
  }
  ASSERT_GE(chunks.size(), 2u);
  const std::vector<test::BagBytesMessage> messages = test::bagMessages(bag);
  const std::size_t cut = chunks.back().data + (chunks.back().end - chunks.back().data) / 2;
  const std::string path = writeBytes(dir, "stopped.bag", test::stoppedRecording(bag, cut));
  const SonarLog log = readRosBag(path);
  expectPrefix(log, whole, test::bagMessagesBefore(messages, cut));
  EXPECT_TRUE(has(log.notes, "the ROS bag is unindexed (its header's index position is 0, as a stopped `rosbag record` "
                             "leaves it): read by scanning its chunks from the start"));
  ASSERT_EQ(log.skip_reasons.size(), 1u);
  EXPECT_NE(log.skip_reasons[0].find("byte " + std::to_string(chunks.back().at) + ": a chunk left unterminated"), std::string::npos)
      << log.skip_reasons[0];
  // Stopped just after a whole message: everything before is read, and nothing is said skipped.
  const std::size_t at_a_message =
      std::find_if(messages.begin(), messages.end(), [&](const test::BagBytesMessage& m) { return m.end > chunks.back().data; })->end;
  const SonarLog clean = readRosBag(writeBytes(dir, "clean.bag", test::stoppedRecording(bag, at_a_message)));
  EXPECT_EQ(clean.skipped_beams, 0u);
  EXPECT_TRUE(has(clean.notes, "is unindexed"));
  // Beam by beam, as a map reads it: the same beams and skips.
  const std::unique_ptr<BeamSource> source = openRosBag(path);
  std::size_t count = 0;
  while (const std::optional<Beam> beam = source->next()) {
    ASSERT_EQ(beam->intensities, log.beams.at(count).intensities);
    ++count;
  }
  EXPECT_EQ(count, log.beams.size());
  EXPECT_EQ(source->header().skip_reasons, log.skip_reasons);
}

TEST(formatsRosBagDamage, AStoppedCompressedRecordingKeepsItsClosedChunks) {
  for (const BagCompression compression : {BagCompression::kBz2, BagCompression::kLz4}) {
    const test::TempDir dir;
    const std::string bag = tankBag(dir, 4, compression);
    const SonarLog whole = readRosBag(dir.file("whole.bag"));
    std::vector<test::BagBytesRecord> chunks;
    for (const test::BagBytesRecord& record : test::bagRecords(bag, 13, bag.size())) {
      if (record.op == 0x05) chunks.push_back(record);
    }
    ASSERT_GE(chunks.size(), 2u);
    // The messages of the closed chunks: those of the whole bag up to the last chunk's first.
    const SonarLog closed = readRosBag(writeBytes(dir, "closed.bag", test::stoppedRecording(bag, chunks.back().data)));
    ASSERT_GT(closed.beams.size(), 0u);
    const std::string path = writeBytes(dir, "stopped.bag", test::stoppedRecording(bag, chunks.back().data + 100));
    const SonarLog log = readRosBag(path);
    expectPrefix(log, whole, closed.beams.size());  // nothing of the cut stream's block decompresses
    ASSERT_EQ(log.skip_reasons.size(), 1u);
    EXPECT_NE(log.skip_reasons[0].find("a chunk left unterminated"), std::string::npos) << log.skip_reasons[0];
    EXPECT_NE(log.skip_reasons[0].find("decompress from it read, the rest skipped"), std::string::npos) << log.skip_reasons[0];
  }
}

TEST(formatsRosBagDamage, AFileThatIsNoBagOrIsCutInItsHeaderIsAClearError) {
  const test::TempDir dir;
  std::ofstream(dir.file("text.bag")) << "not a bag\n";
  EXPECT_THROW(readRosBag(dir.file("text.bag")), FileError);
  EXPECT_THROW(readRosBag(dir.file("missing.bag")), FileError);
  const std::string bag = tankBag(dir, 1);
  try {
    readRosBag(writeBytes(dir, "header.bag", bag.substr(0, 2000)));  // inside the bag header's padding
    FAIL() << "a bag cut in its header read";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find("ROS bag: byte 13: record data of"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("runs past its end (no whole message before it)"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace sonarmap
