// End-to-end tests of the `sonarmap` command-line tool: the built executable (SONARMAP_CLI) runs as
// a child process with stderr redirected to a file (never a terminal). Covers the happy path on the
// paper's tank log, interop of the written .bt with OctoMap 1.9 (test-only dependency), usage errors
// (exit 2), data errors (exit 1) and the promise that a failed run leaves no partial output.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "cli_fixture.hpp"
#include "figure_checks.hpp"

namespace sonarmap::test {
namespace {

namespace fs = std::filesystem;
using Names = std::vector<std::string>;

const fs::path kTankLog = fs::path(SONARMAP_SHARED_DATA) / "cras_micron_tank_static.mat";
constexpr std::size_t kTankBeams = 5604;  // ../shared/data/README.md
constexpr double kResolution_m = 0.02;    // the CLI's default --resolution
constexpr double kFloorEchoRange_m = 1.56;

#define SKIP_WITHOUT_TANK_LOG() \
  if (!fs::exists(kTankLog)) GTEST_SKIP() << "shared data absent: " << kTankLog

// ---------------------------------------------------------------------------------------------
// 1. Happy path
// ---------------------------------------------------------------------------------------------

using cliMap = CliTest;

TEST_F(cliMap, WritesMapAndImagesAndPrintsOneSummaryLine) {
  SKIP_WITHOUT_TANK_LOG();
  const fs::path bt = out_ / "MAP.bt";
  const ProgramRun result = run({"map", kTankLog.string(), "-o", bt.string(), "--png", (out_ / "slice.png").string(),
                                 "--polar-png", (out_ / "polar.png").string(), "--cartesian-png",
                                 (out_ / "cartesian.png").string(), "-q"});
  ASSERT_EQ(result.signal, 0);
  ASSERT_EQ(result.exit_code, 0) << "stderr: " << result.err;
  EXPECT_EQ(result.err, "") << "-q with stderr not a terminal must print nothing on stderr";

  const Names lines = linesOf(result.out);
  ASSERT_EQ(lines.size(), 1u) << result.out;
  EXPECT_EQ(result.out.back(), '\n');
  const std::string& line = lines[0];
  for (const char* part : {"beams used", "skipped", "sweeps", "obstacles", "map nodes", "KiB", " s"}) {
    EXPECT_NE(line.find(part), std::string::npos) << "'" << part << "' missing from: " << line;
  }
  // The beam the reader skipped is said with why (README: the very last beam has 186 bins).
  EXPECT_TRUE(std::regex_search(line, std::regex(" [0-9.]+ s, skipped 1 by the reader: .*186 bins.* -> "))) << line;
  EXPECT_NE(line.find(bt.string()), std::string::npos) << line;
  std::size_t used = 0, skipped = 0, sweeps = 0, obstacles = 0;
  ASSERT_EQ(std::sscanf(line.c_str(), "%zu beams used, %zu skipped, %zu sweeps, %zu obstacles", &used, &skipped, &sweeps,
                        &obstacles),
            4)
      << line;
  EXPECT_EQ(used + skipped, kTankBeams);
  EXPECT_GT(used, kTankBeams * 9 / 10);
  EXPECT_GE(sweeps, 27u);  // about 28 full sweeps of 200 beams
  EXPECT_LE(sweeps, 29u);
  EXPECT_GT(obstacles, 0u);

  ASSERT_TRUE(fs::is_regular_file(bt));
  EXPECT_EQ(readFile(bt).rfind("# Octomap OcTree binary file", 0), 0u);
  // Figures a person can read: >= 800 px, a title, axes; the walls near-black, the sonar a red dot.
  for (const char* name : {"slice.png", "polar.png", "cartesian.png"}) readFigure(out_ / name);
  const cv::Mat slice = readFigure(out_ / "slice.png");
  EXPECT_GT(pixelsOf(slice, kOccupiedBgr), 9000) << "the walls, over a thousand voxels of 3 x 3 pixels or more";
  EXPECT_GT(pixelsOf(slice, kFreeBgr), 200000);
  EXPECT_GT(pixelsOf(slice, kTrackBgr), 20) << "the sonar at the origin";
  // The polar image of a full turn: range along x (399 bins magnified), 200 beams up.
  const cv::Mat polar = cv::imread((out_ / "polar.png").string());
  EXPECT_GT(polar.cols, polar.rows);
  // Atomic writes leave no temporary file behind.
  EXPECT_EQ(listDir(out_), (Names{"MAP.bt", "cartesian.png", "polar.png", "slice.png"}));
}

TEST_F(cliMap, NoProgressBarWhenStderrIsNotATerminal) {
  SKIP_WITHOUT_TANK_LOG();
  const ProgramRun result = run({"map", kTankLog.string(), "-o", (out_ / "MAP.bt").string()});  // no -q
  ASSERT_EQ(result.exit_code, 0) << "stderr: " << result.err;
  EXPECT_EQ(result.err, "");
  EXPECT_EQ(linesOf(result.out).size(), 1u) << result.out;
  EXPECT_TRUE(fs::is_regular_file(out_ / "MAP.bt"));
}

// ---------------------------------------------------------------------------------------------
// 2. OctoMap 1.9 reads the .bt; the floor echo at a constant 1.56 m does not become a ring
// ---------------------------------------------------------------------------------------------

using cliOctomap = CliTest;

/// OctoMap 1.9 reads `bt`; at z = 0 at least 90 % of the occupied leaves lie 1.5 to 3.5 m from
/// the sonar (the tank) and under 5 % on the 1.56 m floor-echo ring.
void expectOctoMapSeesTankNotRing(const fs::path& bt) {
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(bt.string()));
  EXPECT_NEAR(tree.getResolution(), kResolution_m, 1e-12);

  std::size_t occupied = 0, in_tank = 0, on_ring = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it) || std::abs(it.getZ()) >= kResolution_m) continue;
    ++occupied;
    const double range_m = std::hypot(it.getX(), it.getY());
    if (range_m >= 1.5 && range_m <= 3.5) ++in_tank;
    if (std::abs(range_m - kFloorEchoRange_m) < 0.04) ++on_ring;
  }
  ASSERT_GT(occupied, 0u) << "no occupied leaf at z = 0";
  EXPECT_GE(static_cast<double>(in_tank), 0.90 * static_cast<double>(occupied))
      << in_tank << " of " << occupied << " occupied leaves at z = 0 lie 1.5 to 3.5 m from the sonar";
  EXPECT_LT(static_cast<double>(on_ring), 0.05 * static_cast<double>(occupied))
      << on_ring << " of " << occupied << " occupied leaves lie on the " << kFloorEchoRange_m << " m floor-echo ring";
}

TEST_F(cliOctomap, OctoMapReadsTheMapAndWallsAreNotTheFloorEchoRing) {
  SKIP_WITHOUT_TANK_LOG();
  const fs::path bt = out_ / "MAP.bt";
  const ProgramRun result = run({"map", kTankLog.string(), "-o", bt.string(), "-q"});
  ASSERT_EQ(result.exit_code, 0) << "stderr: " << result.err;
  expectOctoMapSeesTankNotRing(bt);
}

TEST_F(cliOctomap, CfarDetectorsMapTheWallsNotTheFloorEchoRing) {
  SKIP_WITHOUT_TANK_LOG();
  for (const char* detector : {"cfar-ca", "cfar-so", "cfar-go", "cfar-os"}) {
    SCOPED_TRACE(detector);
    const fs::path bt = out_ / (std::string(detector) + ".bt");
    const ProgramRun result = run({"map", kTankLog.string(), "-o", bt.string(), "--detector", detector, "-q"});
    ASSERT_EQ(result.exit_code, 0) << "stderr: " << result.err;
    expectOctoMapSeesTankNotRing(bt);
  }
}

// ---------------------------------------------------------------------------------------------
// 3. Usage errors: exit 2, one line on stderr, no output
// ---------------------------------------------------------------------------------------------

struct UsageCase {
  const char* name;
  Names args;  // "{IN}" → the tank log (present or not), "{OUT}" → the output folder
};

void PrintTo(const UsageCase& usage, std::ostream* os) { *os << usage.name; }

class cliUsage : public CliTest, public ::testing::WithParamInterface<UsageCase> {};

TEST_P(cliUsage, ExitsTwoWithOneErrorLineAndWritesNothing) {
  Names args = GetParam().args;
  for (std::string& arg : args) {
    if (arg == "{IN}") arg = kTankLog.string();
    if (arg.rfind("{OUT}", 0) == 0) arg = out_.string() + arg.substr(5);
  }
  expectError(run(args), 2);
  EXPECT_EQ(listDir(out_), Names{});
}

const Names kWithOutputs = {"-o", "{OUT}/MAP.bt", "--png", "{OUT}/MAP.png", "--polar-png", "{OUT}/polar.png"};

Names mapWith(std::initializer_list<std::string> extra) {
  Names args{"map", "{IN}"};
  args.insert(args.end(), kWithOutputs.begin(), kWithOutputs.end());
  args.insert(args.end(), extra);
  return args;
}

INSTANTIATE_TEST_SUITE_P(
    cli, cliUsage,
    ::testing::Values(UsageCase{"MissingOutput", {"map", "{IN}", "--png", "{OUT}/MAP.png"}},
                      UsageCase{"UnknownOption", mapWith({"--bogus"})},
                      UsageCase{"NegativeResolution", mapWith({"--resolution", "-1"})},
                      UsageCase{"ZeroResolution", mapWith({"--resolution", "0"})},
                      UsageCase{"NonNumericResolution", mapWith({"--resolution", "fine"})},
                      UsageCase{"UnknownDetector", mapWith({"--detector", "bogus"})},
                      UsageCase{"UnknownCfarVariant", mapWith({"--detector", "cfar-xx"})},
                      UsageCase{"CfarWithoutVariant", mapWith({"--detector", "cfar"})},
                      UsageCase{"UnknownSmoothing", mapWith({"--smoothing", "bogus"})},
                      UsageCase{"UnknownRay", mapWith({"--ray", "bogus"})},
                      UsageCase{"RemovedAggregation", mapWith({"--aggregation", "mean"})},
                      UsageCase{"NegativeBeamWidth", mapWith({"--beam-width", "-1"})},
                      UsageCase{"HalfTurnBeamWidth", mapWith({"--beam-width", "180"})},
                      UsageCase{"FalseAlarmOfOneHalf", mapWith({"--false-alarm", "0.5"})},
                      UsageCase{"NegativeMinRange", mapWith({"--min-range", "-1"})},
                      UsageCase{"MinRangeNotANumber", mapWith({"--min-range", "near"})},
                      UsageCase{"NegativeMinEchoLength", mapWith({"--min-echo-length", "-0.1"})},
                      UsageCase{"ZeroIntensitySpan", mapWith({"--intensity-span", "0"})},
                      UsageCase{"ZeroCfarTraining", mapWith({"--cfar-training", "0"})},
                      UsageCase{"CertainHit", mapWith({"--hit-probability", "1"})},
                      UsageCase{"ZeroBudget", mapWith({"--max-voxel-updates-per-beam", "0"})},
                      UsageCase{"RemovedSelfReflection", mapWith({"--self-reflection", "0.5"})},
                      UsageCase{"RemovedLeadingEdge", mapWith({"--leading-edge", "6"})},
                      UsageCase{"NoSubcommand", {}},
                      UsageCase{"UnknownSubcommand", {"mapp", "{IN}", "-o", "{OUT}/MAP.bt"}}),
    [](const ::testing::TestParamInfo<UsageCase>& info) { return std::string(info.param.name); });

using cliMistyped = CliTest;

// A mistyped command or option is answered with the nearest names and the usage line, on one line.
TEST_F(cliMistyped, CommandIsAnsweredWithTheNearestCommand) {
  const ProgramRun result = run({"mapp", kTankLog.string(), "-o", (out_ / "MAP.bt").string()});
  expectError(result, 2);
  EXPECT_NE(result.err.find("unknown command `mapp`: did you mean `map`?"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("Usage: sonarmap COMMAND"), std::string::npos) << result.err;
  EXPECT_NE(run({"locallize"}).err.find("did you mean `localize`?"), std::string::npos);
  const ProgramRun far = run({"photograph"});
  expectError(far, 2);
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;  // nothing is near
}

TEST_F(cliMistyped, OptionIsAnsweredWithTheNearestOptionsOfItsCommand) {
  const ProgramRun result =
      run({"map", kTankLog.string(), "-o", (out_ / "MAP.bt").string(), "--resolutoin", "0.1"});
  expectError(result, 2);
  EXPECT_NE(result.err.find("unknown option `--resolutoin`: did you mean `--resolution`?"), std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("Usage: sonarmap map [OPTIONS]"), std::string::npos) << result.err;
  EXPECT_NE(run({"map", kTankLog.string(), "-o", (out_ / "MAP.bt").string(), "--vertical-apperture=30"})
                .err.find("did you mean `--vertical-aperture`?"),
            std::string::npos);
  EXPECT_EQ(listDir(out_), Names{});
}

using cliUsageOk = CliTest;

TEST_F(cliUsageOk, EveryDetectorNamePassesTheUsageCheck) {
  // A missing input is a data error (exit 1) found after the arguments were checked (exit 2):
  // exit 1 naming the file shows the detector name was accepted, without running a whole map.
  for (const char* detector : {"background", "threshold", "canny", "cfar-ca", "cfar-so", "cfar-go", "cfar-os"}) {
    const ProgramRun result = run({"map", (root_ / "missing.mat").string(), "-o", (out_ / "MAP.bt").string(),
                                   "--detector", detector});
    expectError(result, 1);
    EXPECT_NE(result.err.find("missing.mat"), std::string::npos) << detector << ": " << result.err;
  }
  EXPECT_EQ(listDir(out_), Names{});
}

// ---------------------------------------------------------------------------------------------
// 4. Data errors: exit 1, one line on stderr naming the file, no output
// ---------------------------------------------------------------------------------------------

using cliData = CliTest;

TEST_F(cliData, MissingInput) {
  const fs::path input = root_ / "missing.mat";
  const ProgramRun result = run({"map", input.string(), "-o", (out_ / "MAP.bt").string(), "--png", (out_ / "MAP.png").string()});
  expectError(result, 1);
  EXPECT_NE(result.err.find("missing.mat"), std::string::npos) << result.err;
  EXPECT_EQ(listDir(out_), Names{});
}

TEST_F(cliData, TextFileNamedMat) {
  const fs::path input = root_ / "x.mat";
  writeFile(input, "not a MATLAB file\n");
  const ProgramRun result = run({"map", input.string(), "-o", (out_ / "MAP.bt").string(), "--png", (out_ / "MAP.png").string()});
  expectError(result, 1);
  EXPECT_NE(result.err.find("x.mat"), std::string::npos) << result.err;
  EXPECT_EQ(listDir(out_), Names{});
}

TEST_F(cliData, UnknownInputExtension) {
  const fs::path input = root_ / "log.xyz";
  writeFile(input, "1 2 3\n");
  const ProgramRun result = run({"map", input.string(), "-o", (out_ / "MAP.bt").string(), "--png", (out_ / "MAP.png").string()});
  expectError(result, 1);
  EXPECT_NE(result.err.find(".xyz"), std::string::npos) << result.err;
  EXPECT_EQ(listDir(out_), Names{});
}

TEST_F(cliData, OutputInMissingDirectory) {
  SKIP_WITHOUT_TANK_LOG();
  const fs::path bt = out_ / "no_such_dir" / "MAP.bt";
  const ProgramRun result = run({"map", kTankLog.string(), "-o", bt.string(), "--png", (out_ / "MAP.png").string(), "-q"});
  expectError(result, 1);
  EXPECT_NE(result.err.find(bt.string()), std::string::npos) << result.err;
  EXPECT_EQ(listDir(out_), Names{}) << "neither the folder nor the PNG may be created";
}

// ---------------------------------------------------------------------------------------------
// 5. A failed run leaves existing outputs untouched and no temporary files
// ---------------------------------------------------------------------------------------------

using cliOutput = CliTest;

const std::string kOldMap = "old map, must survive a failed run\n";

TEST_F(cliOutput, BadInputLeavesExistingMapUntouched) {
  const fs::path bt = out_ / "MAP.bt";
  writeFile(bt, kOldMap);
  const fs::path input = root_ / "x.mat";
  writeFile(input, "not a MATLAB file\n");
  expectError(run({"map", input.string(), "-o", bt.string(), "--png", (out_ / "MAP.png").string()}), 1);
  EXPECT_TRUE(readFile(bt) == kOldMap) << "MAP.bt was replaced (" << fs::file_size(bt) << " bytes)";
  EXPECT_EQ(listDir(out_), Names{"MAP.bt"});
}

TEST_F(cliOutput, FailedRenameLeavesNoTemporaryFile) {
  SKIP_WITHOUT_TANK_LOG();
  // MAP.bt is a folder: the map is computed and written to a temporary file whose rename fails.
  const fs::path bt = out_ / "MAP.bt";
  fs::create_directory(bt);
  writeFile(bt / "keep.txt", kOldMap);
  expectError(run({"map", kTankLog.string(), "-o", bt.string(), "-q"}), 1);
  EXPECT_TRUE(fs::is_directory(bt));
  EXPECT_EQ(readFile(bt / "keep.txt"), kOldMap);
  EXPECT_EQ(listDir(out_), Names{"MAP.bt"});
}

// The PNG cannot be staged (its folder is missing): nothing is committed, MAP.bt keeps its content.
// Failures after some outputs were already renamed into place: test_cli_atomic.cpp.
TEST_F(cliOutput, FailedImageWriteLeavesExistingMapUntouched) {
  SKIP_WITHOUT_TANK_LOG();
  const fs::path bt = out_ / "MAP.bt";
  writeFile(bt, kOldMap);
  expectError(run({"map", kTankLog.string(), "-o", bt.string(), "--png", (out_ / "no_such_dir" / "MAP.png").string(), "-q"}), 1);
  EXPECT_TRUE(readFile(bt) == kOldMap) << "MAP.bt was replaced (" << fs::file_size(bt) << " bytes)";
  EXPECT_EQ(listDir(out_), Names{"MAP.bt"});
}

// ---------------------------------------------------------------------------------------------
// 6. Help
// ---------------------------------------------------------------------------------------------

using cliHelp = CliTest;

TEST_F(cliHelp, HelpPrintsUsageOnStdout) {
  const ProgramRun result = run({"--help"});
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.err, "");
  EXPECT_NE(result.out.find("Usage:"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("map"), std::string::npos) << result.out;
  EXPECT_EQ(listDir(out_), Names{});
}

TEST_F(cliHelp, MapHelpListsItsOptions) {
  const ProgramRun result = run({"map", "--help"});
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.err, "");
  for (const char* option : {"Usage:", "--output", "--png", "--polar-png", "--cartesian-png", "--resolution", "--detector",
                             "--smoothing", "--ray", "--beam-width", "--quiet", "--false-alarm",
                             "--min-echo-length", "--min-range", "--intensity-span", "--smoothing-range",
                             "--smoothing-bearing", "--cfar-training", "--cfar-guard", "--max-range",
                             "--max-voxel-updates-per-beam", "--hit-probability"}) {
    EXPECT_NE(result.out.find(option), std::string::npos) << option << " missing from:\n" << result.out;
  }
  // Settings the pipeline derives or fixes are not options: the echo's leading edge at the -3 dB
  // beam's 6 dB, the free space's end from the bin, voxel and rise, the near field's zeroed bins
  // with --min-range, the threshold from --false-alarm alone, OctoMap's max aggregation.
  for (const char* removed : {"--leading-edge", "--range-tolerance", "--self-reflection", "--min-contrast",
                              "--aggregation"}) {
    EXPECT_EQ(result.out.find(removed), std::string::npos) << removed << " still in:\n" << result.out;
  }
  // Every number's unit is in its help.
  for (const char* unit : {"METRES", "DEGREES", "DB", "PROBABILITY", "VOXEL UPDATES"}) {
    EXPECT_NE(result.out.find(unit), std::string::npos) << unit << " missing from:\n" << result.out;
  }
}

}  // namespace
}  // namespace sonarmap::test
