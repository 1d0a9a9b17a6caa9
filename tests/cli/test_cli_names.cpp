/// What the tool says and writes by name: the formats it knows come from the readers' registry
/// (map's error, map's, info's and convert's help), errors never name the library's functions, and
/// an output whose extension says another format than the one written is refused before any work.

#include <gtest/gtest.h>

#include <regex>

#include "cli_fixture.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/io/map_file.hpp"

namespace sonarmap::test {
namespace {

const fs::path kTankLog = fs::path(SONARMAP_SHARED_DATA) / "cras_micron_tank_static.mat";

using cliNames = CliTest;

// Every format the readers know is in the error for an unknown extension and in the help of the
// commands that read logs: one list, none of them a copy that can drift.
TEST_F(cliNames, EveryFormatOfTheRegistryIsListed) {
  writeFile(root_ / "log.xyz", "1 2 3\n");
  const ProgramRun unknown = run({"map", (root_ / "log.xyz").string(), "-o", (out_ / "map.bt").string()});
  expectError(unknown, 1);
  std::vector<std::pair<std::string, std::string>> texts{{"map's error", unknown.err}};
  for (const char* command : {"map", "info", "convert"}) {
    const ProgramRun help = run({command, "--help"});
    ASSERT_EQ(help.exit_code, 0) << help.err;
    texts.emplace_back(std::string(command) + " --help", help.out);
  }
  ASSERT_GE(logFormats().size(), 8u);
  for (const LogFormatEntry& format : logFormats()) {
    for (const auto& [what, text] : texts) {
      EXPECT_NE(text.find(std::string(format.extension)), std::string::npos) << format.extension << " missing from " << what << ":\n" << text;
      EXPECT_NE(text.find(std::string(format.name)), std::string::npos) << format.name << " missing from " << what << ":\n" << text;
    }
  }
  EXPECT_EQ(listDir(out_), Names{});
}

// A reader's error names the file and what is wrong with it, not the function that read it
// ("readCrasMat: ...").
TEST_F(cliNames, ErrorsNameNoFunction) {
  writeFile(root_ / "x.mat", "not a MATLAB file\n");
  writeFile(root_ / "x.V4LOG", "not a V4 log\n");
  writeFile(root_ / "x.csv", "not,a,beam,csv\n");
  const std::regex function_name("(^|[ (])[a-z]+[A-Z][A-Za-z0-9]*(::[A-Za-z]+)?: ");
  for (const char* name : {"x.mat", "x.V4LOG", "x.csv"}) {
    const ProgramRun result = run({"map", (root_ / name).string(), "-o", (out_ / "map.bt").string()});
    expectError(result, 1);
    EXPECT_NE(result.err.find(name), std::string::npos) << result.err;
    EXPECT_FALSE(std::regex_search(result.err, function_name)) << result.err;
  }
}

struct MismatchCase {
  const char* name;
  Names args;        ///< {OUT} is the output folder
  const char* path;  ///< the refused path, as the error names it
};

void PrintTo(const MismatchCase& c, std::ostream* os) { *os << c.name; }

class cliOutputExtension : public CliTest, public ::testing::WithParamInterface<MismatchCase> {};

// The check runs before the input is read (it is missing here): exit 2, one line naming the path
// and its extension, nothing written.
TEST_P(cliOutputExtension, IsRefusedBeforeAnyWork) {
  Names args;
  for (std::string arg : GetParam().args) {
    if (const std::size_t at = arg.find("{OUT}"); at != std::string::npos) arg.replace(at, 5, out_.string());
    if (arg == "{IN}") arg = (root_ / "missing.csv").string();
    args.push_back(arg);
  }
  const ProgramRun result = run(args);
  expectError(result, 2);
  EXPECT_NE(result.err.find(GetParam().path), std::string::npos) << result.err;
  EXPECT_EQ(listDir(out_), Names{});
}

INSTANTIATE_TEST_SUITE_P(
    Outputs, cliOutputExtension,
    ::testing::Values(MismatchCase{"MapAsPng", {"map", "{IN}", "-o", "{OUT}/x.png"}, "x.png"},
                      MismatchCase{"MapWithoutExtension", {"map", "{IN}", "-o", "{OUT}/map"}, "map"},
                      MismatchCase{"TopViewAsBt", {"map", "{IN}", "-o", "{OUT}/m.bt", "--png", "{OUT}/top.bt"}, "top.bt"},
                      MismatchCase{"PolarAsJpeg", {"map", "{IN}", "-o", "{OUT}/m.bt", "--polar-png", "{OUT}/p.jpg"}, "p.jpg"},
                      MismatchCase{"CartesianAsCsv", {"map", "{IN}", "-o", "{OUT}/m.bt", "--cartesian-png", "{OUT}/c.csv"}, "c.csv"},
                      MismatchCase{"TrajectoryAsPng",
                                   {"map", "{IN}", "-o", "{OUT}/m.bt", "--slam", "--trajectory", "{OUT}/t.png"}, "t.png"},
                      MismatchCase{"LiveMapAsPng", {"live", "-", "--format", "seanet", "-o", "{OUT}/x.png"}, "x.png"},
                      MismatchCase{"LiveTrajectoryAsBt",
                                   {"live", "-", "--format", "seanet", "--slam", "-o", "{OUT}/m.bt", "--trajectory", "{OUT}/t.bt"},
                                   "t.bt"},
                      MismatchCase{"LocalizeTrajectoryAsBt", {"localize", "{IN}", "--trajectory", "{OUT}/t.bt"}, "t.bt"},
                      MismatchCase{"LocalizeMapAsPng",
                                   {"localize", "{IN}", "--trajectory", "{OUT}/t.csv", "--map", "{OUT}/m.png"}, "m.png"},
                      MismatchCase{"LocalizePictureAsOt",
                                   {"localize", "{IN}", "--trajectory", "{OUT}/t.csv", "--png", "{OUT}/p.ot"}, "p.ot"}),
    [](const ::testing::TestParamInfo<MismatchCase>& info) { return std::string(info.param.name); });

// `-o NAME.ot` writes the full tree its extension names (not the binary tree under that
// name, which nothing reading .ot could open).
TEST_F(cliNames, AnOtOutputIsAFullTree) {
  if (!fs::exists(kTankLog)) GTEST_SKIP() << "shared data absent: " << kTankLog;
  const fs::path bt = out_ / "map.bt";
  const fs::path ot = out_ / "map.ot";
  ASSERT_EQ(run({"map", kTankLog.string(), "-q", "-o", bt.string()}).exit_code, 0);
  const ProgramRun full = run({"map", kTankLog.string(), "-q", "-o", ot.string()});
  ASSERT_EQ(full.exit_code, 0) << full.err;
  EXPECT_EQ(readFile(ot).rfind("# Octomap OcTree file", 0), 0u);  // OctoMap's full-tree header
  const OcTree16 binary_map = readMapFile(bt.string());
  const OcTree16 full_map = readMapFile(ot.string());
  EXPECT_GT(full_map.counts().leaves, 0u);
  EXPECT_EQ(full_map.resolution_m(), binary_map.resolution_m());
}

}  // namespace
}  // namespace sonarmap::test
