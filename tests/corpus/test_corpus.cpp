/// @file test_corpus.cpp
/// The hand-made broken-input corpus. For every row of broken/MANIFEST.tsv of exit code 1 (refused):
///  - the library reader the row's CLI command uses throws a sonarmap::Error (never another
///    exception type) whose message names the file and contains the row's text;
///  - the `sonarmap` CLI run on it exits with the row's code, prints exactly one line on stderr
///    (no stack trace, no sanitizer report) and creates nothing in its output folder.
/// For every row of exit code 0 (a file read up to its damage, docs/reliability.md):
///  - the readers read it, and the sonar log's skip reasons or notes hold the row's text;
///  - the CLI exits 0 with its output written and no error line; `map` prints the text when it is
///    a skip reason (its summary's "skipped N by the reader: ...").
/// And for every small valid file of valid/: each truncation and a fixed-seed sample of byte
/// flips either reads or throws a sonarmap::Error.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/io/point_text.hpp"
#include "sonarmap/io/scan_graph.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/nav/tum_trajectory.hpp"
#include "sonarmap/slam/point_scans.hpp"
#include "sonarmap/sim/scene_file.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/navigation_reader.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;
using test::ProgramRun;

const fs::path kCorpus = SONARMAP_CORPUS;
const fs::path kBroken = kCorpus / "broken";
const fs::path kValid = kCorpus / "valid";
constexpr const char* kManifest = "MANIFEST.tsv";

// ---- how a CLI command reaches a reader ----------------------------------------------------------

using Args = std::vector<std::string>;

/// One way into the readers: the library call a CLI command makes on its input, and the command
/// line that makes it (writing, when it gets that far, into `out`).
struct Route {
  std::string command;  ///< as written in the manifest
  std::function<void(const std::string& file)> read;
  std::function<Args(const std::string& file, const fs::path& out)> args;
};

std::string valid(const char* name) { return (kValid / name).string(); }
std::string in(const fs::path& out, const char* name) { return (out / name).string(); }

const std::vector<Route>& routes() {
  static const std::vector<Route> table = {
      {"map",
       [](const std::string& f) {  // the log, and its own navigation as map reads it (a ROS bag's)
         readSonarLog(f);
         if (const auto format = logFormatOfPath(f)) readLogNavigation(f, *format);
       },
       [](const std::string& f, const fs::path& out) -> Args { return {"map", f, "-o", in(out, "map.bt"), "-q"}; }},
      {"convert", [](const std::string& f) { readSonarLog(f); },
       [](const std::string& f, const fs::path& out) -> Args { return {"convert", f, "-o", in(out, "beams.csv")}; }},
      {"map --nav", [](const std::string& f) { readNavigation(f); },
       [](const std::string& f, const fs::path& out) -> Args {
         return {"map", valid("beams_small.csv"), "--nav", f, "-o", in(out, "map.bt"), "-q"};
       }},
      {"eval-trajectory", [](const std::string& f) { readTrajectory(f); },
       [](const std::string& f, const fs::path&) -> Args {
         return {"eval-trajectory", f, "--truth", valid("tum_small.txt")};
       }},
      {"cloud",
       [](const std::string& f) {
         if (fs::path(f).extension() == ".graph") {
           readScanGraph(f);
         } else {
           readPointText(f);
         }
       },
       [](const std::string& f, const fs::path& out) -> Args { return {"cloud", f, "-o", in(out, "map.bt"), "-q"}; }},
      {"eval", [](const std::string& f) { readMapFile(f); },
       [](const std::string& f, const fs::path&) -> Args { return {"eval", f, "--truth", valid("scene_small.txt")}; }},
      {"eval --truth", [](const std::string& f) { readScene(f); },
       [](const std::string& f, const fs::path&) -> Args { return {"eval", valid("tree_small.bt"), "--truth", f}; }},
      {"localize", [](const std::string& f) { readPointScansCsv(f); },
       [](const std::string& f, const fs::path& out) -> Args {
         return {"localize", f, "--trajectory", in(out, "trajectory.csv"), "-q"};
       }},
      {"simulate", [](const std::string& f) { readScene(f); },
       [](const std::string& f, const fs::path& out) -> Args { return {"simulate", f, "-o", in(out, "sim")}; }},
  };
  return table;
}

const Route& routeOf(const std::string& command) {
  for (const Route& route : routes()) {
    if (route.command == command) return route;
  }
  throw std::invalid_argument("unknown command '" + command + "' in " + std::string(kManifest));
}

// ---- the manifest --------------------------------------------------------------------------------

/// One row of broken/MANIFEST.tsv: file, command, exit code, text the message must contain.
struct Row {
  std::string file;
  std::string command;
  int exit_code = 1;
  std::string message;
};

void PrintTo(const Row& row, std::ostream* out) { *out << row.file << " (" << row.command << ")"; }

std::vector<std::string> splitTabs(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  for (std::string field; std::getline(stream, field, '\t');) fields.push_back(field);
  return fields;
}

/// The rows of the manifest; `#` lines (the column names) and blank lines are skipped.
/// @throws std::runtime_error for a row without its four fields.
std::vector<Row> loadManifest() {
  std::ifstream in(kBroken / kManifest);
  if (!in) throw std::runtime_error("cannot open " + (kBroken / kManifest).string());
  std::vector<Row> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> fields = splitTabs(line);
    if (fields.size() != 4) throw std::runtime_error(std::string(kManifest) + ": not 4 tab-separated fields: " + line);
    rows.push_back({fields[0], fields[1], std::stoi(fields[2]), fields[3]});
  }
  return rows;
}

/// `name` with every character that is not a letter or digit replaced by '_' (a test name).
std::string identifier(std::string name) {
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

TEST(corpusManifest, listsEveryBrokenFileOnceWithAKnownCommand) {
  std::vector<std::string> listed;
  for (const Row& row : loadManifest()) {
    EXPECT_NO_THROW(routeOf(row.command)) << row.file;
    EXPECT_TRUE(fs::is_regular_file(kBroken / row.file)) << row.file << " is listed but missing";
    EXPECT_FALSE(row.message.empty()) << row.file;
    listed.push_back(row.file);
  }
  std::vector<std::string> present = test::listDir(kBroken);
  present.erase(std::remove(present.begin(), present.end(), kManifest), present.end());
  std::sort(listed.begin(), listed.end());
  EXPECT_EQ(std::adjacent_find(listed.begin(), listed.end()), listed.end()) << "a file is listed twice";
  EXPECT_EQ(listed, present);
}

// ---- every broken file ---------------------------------------------------------------------------

class corpusBroken : public ::testing::TestWithParam<Row> {
 protected:
  std::string path() const { return (kBroken / GetParam().file).string(); }
};

/// Whether the sonar log of `file` says `text` among its skip reasons (or, with `notes`, its notes).
bool logSays(const std::string& file, const std::string& text, bool notes) {
  const SonarLog log = readSonarLog(file);
  const auto has = [&](const std::vector<std::string>& lines) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& line) { return line.find(text) != std::string::npos; });
  };
  return has(log.skip_reasons) || (notes && has(log.notes));
}

TEST_P(corpusBroken, readerThrowsAnErrorNamingFileAndProblemOrReadsAroundIt) {
  const Row& row = GetParam();
  if (row.exit_code == 0) {
    EXPECT_NO_THROW(routeOf(row.command).read(path())) << row.file;
    EXPECT_TRUE(logSays(path(), row.message, /*notes=*/true)) << row.file << ": no skip reason or note says '" << row.message << "'";
    return;
  }
  try {
    routeOf(row.command).read(path());
    ADD_FAILURE() << row.file << ": read without an error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(row.file), std::string::npos) << "the message does not name the file: " << message;
    EXPECT_NE(message.find(row.message), std::string::npos) << "expected '" << row.message << "' in: " << message;
  } catch (const std::exception& error) {
    ADD_FAILURE() << row.file << ": threw an exception that is not a sonarmap::Error: " << error.what();
  }
}

TEST_P(corpusBroken, cliFailsWithOneLineAndWritesNothingOrReadsWithTheWarning) {
  const Row& row = GetParam();
  const fs::path out = test::makeTempDir("corpus_out");
  const fs::path capture = test::makeTempDir("corpus_capture");
  const ProgramRun run = test::runProgram(SONARMAP_CLI, routeOf(row.command).args(path(), out), capture);
  EXPECT_EQ(run.signal, 0);
  EXPECT_EQ(run.exit_code, row.exit_code) << run.err;
  if (row.exit_code == 0) {
    EXPECT_EQ(run.err.find("error"), std::string::npos) << run.err;
    EXPECT_EQ(test::listDir(out).size(), 1u) << "no output written for " << row.file;
    if (row.command == "map" && logSays(path(), row.message, /*notes=*/false)) {  // in its summary
      EXPECT_NE(run.out.find(row.message), std::string::npos) << run.out;
    }
    fs::remove_all(out);
    fs::remove_all(capture);
    return;
  }
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << "stderr:\n" << run.err;
  EXPECT_TRUE(run.err.ends_with('\n')) << run.err;
  EXPECT_NE(run.err.find(row.file), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(row.message), std::string::npos) << "expected '" << row.message << "' in: " << run.err;
  for (const char* forbidden : {"Sanitizer", "runtime error", "terminate called", "what():", "Aborted", "#0 "}) {
    EXPECT_EQ(run.err.find(forbidden), std::string::npos) << run.err;
  }
  EXPECT_EQ(test::listDir(out), std::vector<std::string>{}) << "output written for " << row.file;
  fs::remove_all(out);
  fs::remove_all(capture);
}

INSTANTIATE_TEST_SUITE_P(manifest, corpusBroken, ::testing::ValuesIn(loadManifest()),
                         [](const ::testing::TestParamInfo<Row>& info) { return identifier(info.param.file); });

// ---- truncations and byte flips of valid files ---------------------------------------------------

/// A small valid file of each format and the command whose reader reads it.
struct Seed {
  const char* file;
  const char* command;
};
constexpr Seed kSeeds[] = {
    {"cras_small.mat", "map"},       {"cras_small_compressed.mat", "map"}, {"seanet_small.V4LOG", "map"},
    {"beams_small.csv", "map"},      {"nav_small.csv", "map --nav"},       {"scan_small.graph", "cloud"},
    {"points_small.xyz", "cloud"},   {"tree_small.bt", "eval"},            {"tree_small.ot", "eval"},
    {"scene_small.txt", "simulate"}, {"beams_span_small.csv", "map"},
    {"seanet_small.seanet", "map"},  {"ping_small.bin", "map"},           {"viewer_small.bin", "map"},
    {"viewer_small_utf16.bin", "map"}, {"viewer_locale_digits.bin", "map"}, {"viewer_chunked.bin", "map"},
    {"viewer_range_changes.bin", "map"}, {"tum_small.txt", "eval-trajectory"},
    {"bag_small.bag", "map"},        {"bag_small_bz2.bag", "map"},         {"bag_with_odometry.bag", "map"},
    {"bag_miniking.bag", "map"},     {"scan_small.mcap", "map"},
    {"rosbag2_small.db3", "map"},    {"tlog_small.tlog", "map --nav"},    {"dataflash_small.BIN", "map --nav"},
    {"scans_small.csv", "localize"},  {"scans_small.csv.gz", "localize"},  {"scans_two_members.csv.gz", "localize"},
    {"nav_small.csv.gz", "map --nav"}, {"beams_small.csv.gz", "map"},
};
void PrintTo(const Seed& seed, std::ostream* out) { *out << seed.file << " (" << seed.command << ")"; }

constexpr std::uint32_t kFlipSeed = 20240505;
constexpr int kFlipsPerSeed = 400;

class corpusMutated : public ::testing::TestWithParam<Seed> {
 protected:
  std::string original() const { return test::readFile(kValid / GetParam().file); }

  /// Writes `bytes` under the seed's file name and reads it: it must read or throw a sonarmap::Error.
  void expectReadOrError(const std::string& bytes, const std::string& mutation) {
    const std::string path = dir_.file(GetParam().file);
    test::writeFile(path, bytes);
    try {
      routeOf(GetParam().command).read(path);
    } catch (const Error&) {
      // the expected outcome for most mutations
    } catch (const std::exception& error) {
      ADD_FAILURE() << GetParam().file << ", " << mutation << ": not a sonarmap::Error: " << error.what();
    }
  }

 private:
  test::TempDir dir_;
};

TEST_P(corpusMutated, originalReads) { EXPECT_NO_THROW(routeOf(GetParam().command).read((kValid / GetParam().file).string())); }

TEST_P(corpusMutated, everyTruncationReadsOrThrowsError) {
  const std::string bytes = original();
  for (std::size_t length = 0; length < bytes.size(); ++length) {
    expectReadOrError(bytes.substr(0, length), "truncated to " + std::to_string(length) + " bytes");
  }
}

TEST_P(corpusMutated, byteFlipsReadOrThrowError) {
  const std::string bytes = original();
  std::mt19937 random(kFlipSeed);
  std::uniform_int_distribution<std::size_t> position(0, bytes.size() - 1);
  std::uniform_int_distribution<int> flips(1, 4), mask(1, 255);
  for (int trial = 0; trial < kFlipsPerSeed; ++trial) {
    std::string mutated = bytes;
    std::string mutation = "trial " + std::to_string(trial) + ", bytes flipped at";
    for (int n = flips(random); n > 0; --n) {
      const std::size_t at = position(random);
      mutated[at] = static_cast<char>(mutated[at] ^ mask(random));
      mutation += ' ';
      mutation += std::to_string(at);
    }
    expectReadOrError(mutated, mutation);
  }
}

INSTANTIATE_TEST_SUITE_P(valid, corpusMutated, ::testing::ValuesIn(kSeeds),
                         [](const ::testing::TestParamInfo<Seed>& info) { return identifier(info.param.file); });

// ---- trajectories: readTrajectory tells a navigation CSV from a TUM file by content ----------------

TEST(corpusTrajectory, validTumFileReadsEveryPoseAndTheCliScoresIt) {
  // comments, a blank line, a tab, a CRLF line end; quaternions of yaw 0, 0.2, (about) 0.6 and 1 rad
  const NavTrack track = readTrajectory(valid("tum_small.txt"));
  ASSERT_EQ(track.size(), 4u);
  EXPECT_EQ(track[1].time_s, 0.5);
  EXPECT_EQ(track[2].position_ned_m, Eigen::Vector3d(2.0, 1.5, 2.5));
  EXPECT_NEAR(track[1].yaw_rad, 0.2, 1e-9);
  EXPECT_NEAR(track[3].yaw_rad, 1.0, 1e-9);
  EXPECT_EQ(readTrajectory(valid("nav_small.csv")).size(), readNavCsv(valid("nav_small.csv")).size());
  test::TempDir dir;
  const ProgramRun run =
      test::runProgram(SONARMAP_CLI, {"eval-trajectory", valid("tum_small.txt"), "--truth", valid("tum_small.txt")},
                       dir.path());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("poses 4\n"), std::string::npos) << run.out;
}

// A MiniKing's miniking_ros/AcousticBeam (a range and a bin count, `uint8[] intensities`, its
// angle in degrees) is found by its fields, as the Micron's ScanLine is.
TEST(corpusRosBag, aMiniKingTopicReadsByItsFields) {
  const SonarLog log = readSonarLog(valid("bag_miniking.bag"));
  ASSERT_EQ(log.beams.size(), 3u);
  EXPECT_EQ(log.sonar, "ROS topic /miniking_node/sonar (miniking_ros/AcousticBeam)");
  EXPECT_DOUBLE_EQ(log.beams[0].bin_length_m, 10.0 / 8.0);  // range_max over the bins
  EXPECT_EQ(log.beams[0].intensities, (std::vector<std::uint8_t>{0, 1, 5, 200, 80, 9, 4, 2}));
  EXPECT_NEAR(log.beams[1].bearing_rad, 90.9 * 3.14159265358979 / 180.0, 1e-6);  // clockwise, as beam.hpp counts
  EXPECT_DOUBLE_EQ(log.beams[2].time_s, 1002.0);
}

// ---- what real Ping Viewer logs do (../shared/data/README.md), in files made by make_corpus.py ---------

TEST(corpusRealViewer, timeStampsInPersianDigitsReadAsSeconds) {
  const SonarLog log = readSonarLog(valid("viewer_locale_digits.bin"));
  ASSERT_EQ(log.beams.size(), 4u);
  EXPECT_DOUBLE_EQ(log.beams.front().time_s, 0.100);
  EXPECT_DOUBLE_EQ(log.beams.back().time_s, 0.150);  // the records' second stamp, "۰۰:۰۰:۰۰.۱۵۰"
  EXPECT_TRUE(log.notes.empty());
  EXPECT_EQ(log.skipped_beams, 0u);
}

TEST(corpusRealViewer, messagesSplitOverRecordsOrSharingOneAreReassembled) {
  // one message over three records, then three messages and a half in one record, the rest in a last
  const SonarLog log = readSonarLog(valid("viewer_chunked.bin"));
  ASSERT_EQ(log.beams.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    // angles 0, 1, 2, 3 gradians clockwise from ahead: bearings clockwise from ahead (beam.hpp)
    EXPECT_NEAR(log.beams[i].bearing_rad, static_cast<double>(i) * 2.0 * 3.141592653589793 / 400.0, 1e-12)
        << i;
    EXPECT_EQ(log.beams[i].intensities.size(), 3u) << i;
  }
  EXPECT_EQ(log.skipped_beams, 0u);
}

TEST(corpusRealViewer, powerOnPingsThenRangeAndGainChangesKeepEachBeamsSetting) {
  const SonarLog log = readSonarLog(valid("viewer_range_changes.bin"));
  ASSERT_EQ(log.beams.size(), 9u);
  EXPECT_NE(log.sonar.find("Ping360 (firmware 3.1.1)"), std::string::npos) << log.sonar;
  // sample period 88 and 440 ticks of 25 ns at 1500 m/s: 1.65 mm and 8.25 mm bins
  for (std::size_t i = 0; i < 9; ++i) {
    EXPECT_NEAR(log.beams[i].bin_length_m, i < 3 ? 0.00165 : 0.00825, 1e-9) << i;
    EXPECT_EQ(log.beams[i].gain_setting, i < 6 ? 0 : 1) << i;
  }
}

TEST(corpusRealViewer, theDefaultMapCommandReadsEveryRealBehaviourFile) {
  // the beams are too short (3 samples) to map anything: the command must still end with exit 0,
  // a map file and a summary that counts every beam
  for (const char* name : {"viewer_locale_digits.bin", "viewer_chunked.bin", "viewer_range_changes.bin"}) {
    test::TempDir dir;
    const std::string map = dir.file("map.bt");
    const ProgramRun run = test::runProgram(SONARMAP_CLI, {"map", valid(name), "-o", map, "-q"}, dir.path());
    EXPECT_EQ(run.exit_code, 0) << name << ": " << run.err;
    EXPECT_TRUE(fs::exists(map)) << name;
  }
}

}  // namespace
}  // namespace sonarmap
