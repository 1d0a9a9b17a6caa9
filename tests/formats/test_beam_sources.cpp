/// Tests of the streaming readers (openBeamSource, log_reader.hpp; beam_source.hpp): each gives the
/// beams, header and errors of the reader that reads the log whole, pass after pass, and an MCAP
/// file whose messages are out of time order across chunks (or outside chunks) is read in time
/// order as the whole-log reader sorts it.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/mcap_writer.hpp"
#include "sonarmap/formats/ros_bag_writer.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"

namespace sonarmap {
namespace {

/// A moving Micron: 1,600 beams of 399 bins (4 chunks of MCAP), times in seconds since 1970 as ROS stamps are.
SonarLog movingLog(NavTrack* nav = nullptr) {
  SimulationArguments args;
  args.turns = 8;
  args.speed_mps = 0.05;
  const MsisSimulationOptions options = toSimulationOptions(args, "tank");
  MsisSimulation run = simulateMsis(sceneOf("tank", options.head), options);
  for (Beam& beam : run.log.beams) beam.time_s += 1.7e9;
  for (NavSample& fix : run.nav) fix.time_s += 1.7e9;
  if (nav != nullptr) *nav = run.nav;
  return run.log;
}

/// Every beam of `source`, from its first.
std::vector<Beam> drain(BeamSource& source) {
  std::vector<Beam> beams;
  source.rewind();
  while (std::optional<Beam> beam = source.next()) beams.push_back(std::move(*beam));
  return beams;
}

void expectSameBeams(const std::vector<Beam>& read, const std::vector<Beam>& expected) {
  ASSERT_EQ(read.size(), expected.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].time_s, expected[i].time_s) << "beam " << i;
    EXPECT_EQ(read[i].bearing_rad, expected[i].bearing_rad) << "beam " << i;
    EXPECT_EQ(read[i].bin_length_m, expected[i].bin_length_m) << "beam " << i;
    EXPECT_EQ(read[i].intensities, expected[i].intensities) << "beam " << i;
    EXPECT_EQ(read[i].intensity_span_db, expected[i].intensity_span_db) << "beam " << i;
    EXPECT_EQ(read[i].gain_setting, expected[i].gain_setting) << "beam " << i;
    EXPECT_EQ(read[i].pulse_length_m, expected[i].pulse_length_m) << "beam " << i;
  }
}

/// The source opened on `path` gives readSonarLog's beams and header, twice.
void expectSourceReadsAsWholeLog(const std::string& path, LogFormat format) {
  const SonarLog whole = readSonarLog(path, format);
  const std::unique_ptr<BeamSource> source = openBeamSource(path, format);
  for (int pass = 0; pass < 2; ++pass) {
    SCOPED_TRACE("pass " + std::to_string(pass));
    expectSameBeams(drain(*source), whole.beams);
    const SonarLog& header = source->header();
    EXPECT_EQ(header.sonar, whole.sonar);
    EXPECT_EQ(header.notes, whole.notes);
    EXPECT_EQ(header.skipped_beams, whole.skipped_beams);
    EXPECT_EQ(header.skip_reasons, whole.skip_reasons);
    EXPECT_EQ(header.clock_utc_s, whole.clock_utc_s);
    EXPECT_EQ(header.frame_id, whole.frame_id);
  }
}

void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

/// One MCAP record: its opcode and content.
struct Record {
  unsigned char opcode = 0;
  std::vector<unsigned char> content;
};

/// The records of MCAP bytes between the magics.
std::vector<Record> recordsOf(const std::vector<unsigned char>& bytes) {
  std::vector<Record> records;
  for (std::size_t at = 8; at + 8 < bytes.size();) {
    std::uint64_t length = 0;
    std::memcpy(&length, bytes.data() + at + 1, 8);
    records.push_back({bytes[at], std::vector<unsigned char>(bytes.begin() + static_cast<std::ptrdiff_t>(at + 9),
                                                             bytes.begin() + static_cast<std::ptrdiff_t>(at + 9 + length))});
    at += 9 + length;
  }
  return records;
}

std::vector<unsigned char> mcapOf(const std::vector<Record>& records) {
  std::vector<unsigned char> bytes = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  for (const Record& record : records) {
    bytes.push_back(record.opcode);
    const std::uint64_t length = record.content.size();
    const auto* raw = reinterpret_cast<const unsigned char*>(&length);
    bytes.insert(bytes.end(), raw, raw + 8);
    bytes.insert(bytes.end(), record.content.begin(), record.content.end());
  }
  bytes.insert(bytes.end(), {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'});
  return bytes;
}

/// The records inside an uncompressed Chunk record's content.
std::vector<Record> chunkRecords(const std::vector<unsigned char>& chunk) {
  std::size_t at = 8 + 8 + 8 + 4;
  std::uint32_t compression = 0;
  std::memcpy(&compression, chunk.data() + at, 4);
  at += 4 + compression + 8;
  std::vector<unsigned char> inner = {0, 0, 0, 0, 0, 0, 0, 0};  // recordsOf skips a magic's length
  inner.insert(inner.end(), chunk.begin() + static_cast<std::ptrdiff_t>(at), chunk.end());
  inner.insert(inner.end(), 9, 0);
  std::vector<Record> records = recordsOf(inner);
  records.pop_back();
  return records;
}

TEST(formatsBeamSources, RosLogsAndBeamCsvReadBeamByBeamAsWhole) {
  const test::TempDir dir;
  NavTrack nav;
  const SonarLog log = movingLog(&nav);
  writeMcap(dir.file("run.mcap"), log, nav);
  writeRosBag(dir.file("run.bag"), log, nav);
  writeBeamCsv(dir.file("run.csv"), log);
  expectSourceReadsAsWholeLog(dir.file("run.mcap"), LogFormat::kMcap);
  expectSourceReadsAsWholeLog(dir.file("run.bag"), LogFormat::kRosBag);
  expectSourceReadsAsWholeLog(dir.file("run.csv"), LogFormat::kCsv);
  expectSourceReadsAsWholeLog(dir.file("run.csv"), LogFormat::kCsv);
  if (std::filesystem::exists(SONARMAP_SHARED_DATA "/micron_pool_ros1.bag")) {
    expectSourceReadsAsWholeLog(SONARMAP_SHARED_DATA "/micron_pool_ros1.bag", LogFormat::kRosBag);
  }
}

TEST(formatsBeamSources, McapMessagesOutOfOrderAcrossChunksComeInTimeOrder) {
  const test::TempDir dir;
  const SonarLog log = movingLog();
  const std::vector<unsigned char> bytes = mcapBytes(log, {}, {.compression = McapCompression::kNone});
  writeBytes(dir.file("ordered.mcap"), bytes);
  const SonarLog ordered = readSonarLog(dir.file("ordered.mcap"));
  // The chunks in reverse order: every chunk's messages precede the chunk before it in the file.
  std::vector<Record> records = recordsOf(bytes);
  const auto first_chunk = std::find_if(records.begin(), records.end(), [](const Record& r) { return r.opcode == 0x06; });
  const auto end_chunks = std::find_if(first_chunk, records.end(), [](const Record& r) { return r.opcode != 0x06; });
  ASSERT_GT(end_chunks - first_chunk, 2);
  std::vector<Record> reversed(records.begin(), first_chunk);
  reversed.insert(reversed.end(), std::make_reverse_iterator(end_chunks), std::make_reverse_iterator(first_chunk));
  reversed.insert(reversed.end(), end_chunks, records.end());
  writeBytes(dir.file("reversed.mcap"), mcapOf(reversed));
  expectSameBeams(readSonarLog(dir.file("reversed.mcap")).beams, ordered.beams);
  expectSourceReadsAsWholeLog(dir.file("reversed.mcap"), LogFormat::kMcap);
  // The messages outside chunks, every third one moved to the end (runs in time order, then not).
  std::vector<Record> loose(records.begin(), first_chunk), late;
  std::size_t index = 0;
  for (auto chunk = first_chunk; chunk != end_chunks; ++chunk) {
    for (Record& inner : chunkRecords(chunk->content)) {
      if (inner.opcode != 0x05) {
        loose.push_back(std::move(inner));
      } else {
        (index++ % 3 == 0 ? late : loose).push_back(std::move(inner));
      }
    }
  }
  loose.insert(loose.end(), late.begin(), late.end());
  loose.insert(loose.end(), end_chunks, records.end());
  writeBytes(dir.file("loose.mcap"), mcapOf(loose));
  expectSameBeams(readSonarLog(dir.file("loose.mcap")).beams, ordered.beams);
  expectSourceReadsAsWholeLog(dir.file("loose.mcap"), LogFormat::kMcap);
}

TEST(formatsBeamSources, ABeamCsvFailsAtItsBadRowAsTheWholeReaderDoes) {
  const test::TempDir dir;
  std::ofstream(dir.file("late.csv")) << "time_s,bearing_deg,bin_length_m,b0\n1,0,0.1,5\n2,1,0.1,300\n";
  std::string whole_error;
  try {
    readBeamCsv(dir.file("late.csv"));
  } catch (const FileError& error) {
    whole_error = error.what();
  }
  ASSERT_FALSE(whole_error.empty());
  const std::unique_ptr<BeamSource> source = openBeamCsv(dir.file("late.csv"));
  ASSERT_TRUE(source->next().has_value());
  try {
    source->next();
    ADD_FAILURE() << "the bad row was read";
  } catch (const FileError& error) {
    EXPECT_EQ(std::string(error.what()), whole_error);
  }
  std::ofstream(dir.file("header.csv")) << "time_s,bearing_deg,bin_length_m,b0\n";
  EXPECT_THROW(openBeamCsv(dir.file("header.csv")), FileError);  // no beam: refused on opening
  EXPECT_THROW(openBeamCsv(dir.file("missing.csv")), FileError);
}

}  // namespace
}  // namespace sonarmap
