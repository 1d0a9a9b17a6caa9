// `sonarmap map` tells the user when a map comes out empty or an option cannot work, and refuses
// work beyond its budget or a map no beam fits in, naming the option to change.
#include <string>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

using cliWarnings = CliTest;

/// Simulates `scene` (2 turns) into root/sim and returns its beam CSV.
std::string simulate(const CliTest& test, const ProgramRun& result, const fs::path& dir) {
  EXPECT_EQ(result.exit_code, 0) << result.err;
  (void)test;
  return (dir / "beams.csv").string();
}

TEST_F(cliWarnings, OpenWaterSaysTheMapIsEmptyAndWhy) {
  const fs::path dir = root_ / "sim";
  const std::string beams = simulate(*this, run({"simulate", "open-water", "-o", dir.string(), "--turns", "2"}), dir);
  const ProgramRun result = run({"map", beams, "-o", (out_ / "MAP.bt").string(), "-q"});
  EXPECT_EQ(result.exit_code, 0) << result.err;  // an empty map of open water is a right answer
  EXPECT_NE(result.out.find("0 obstacles (EMPTY MAP)"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("1 warning"), std::string::npos) << result.out;
  EXPECT_NE(result.err.find("sonarmap: warning: no obstacle in 400 beams"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("--false-alarm"), std::string::npos) << result.err;
  EXPECT_EQ(listDir(out_), Names{"MAP.bt"});
}

TEST_F(cliWarnings, MinimumRangeBeyondTheWallsIsNamed) {
  const fs::path dir = root_ / "sim";
  const std::string beams = simulate(*this, run({"simulate", "tank", "-o", dir.string(), "--turns", "2"}), dir);
  const ProgramRun result = run({"map", beams, "-o", (out_ / "MAP.bt").string(), "-q", "--min-range", "4.5"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.err.find("sonarmap: warning:"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(".. 4.50 m in their sweeps)"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("--min-range"), std::string::npos) << result.err;
}

TEST_F(cliWarnings, OptionBeyondTheLogsReachIsNamed) {
  const fs::path dir = root_ / "sim";
  const std::string beams = simulate(*this, run({"simulate", "tank", "-o", dir.string(), "--turns", "2"}), dir);
  const ProgramRun result = run({"map", beams, "-o", (out_ / "MAP.bt").string(), "-q", "--min-range", "1e9"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.err.find("--min-range) 1e+09 m is beyond the log's reach"), std::string::npos) << result.err;
  EXPECT_NE(result.out.find("EMPTY MAP"), std::string::npos) << result.out;
}

TEST_F(cliWarnings, WorkBeyondTheBudgetIsRefusedNamingTheOption) {
  const fs::path dir = root_ / "sim";
  const std::string beams = simulate(*this, run({"simulate", "tank", "-o", dir.string(), "--turns", "2"}), dir);
  const ProgramRun result = run({"map", beams, "-o", (out_ / "MAP.bt").string(), "-q", "--resolution", "0.0001"});
  expectError(result, 1);
  EXPECT_NE(result.err.find("--max-voxel-updates-per-beam"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("auto: 0.02 m"), std::string::npos) << result.err;
  EXPECT_EQ(listDir(out_), Names{});
}

TEST_F(cliWarnings, MapNoBeamFitsInIsAnErrorNamingTheResolutionThatFits) {
  const fs::path dir = root_ / "sim";
  const std::string beams = simulate(*this, run({"simulate", "tank", "-o", dir.string(), "--turns", "2"}), dir);
  const ProgramRun result = run({"map", beams, "-o", (out_ / "MAP.bt").string(), "-q", "--resolution", "1e-5",
                                 "--max-voxel-updates-per-beam", "1e16"});
  expectError(result, 1);
  EXPECT_NE(result.err.find("no beam could be mapped"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("a resolution of at least"), std::string::npos) << result.err;
  EXPECT_EQ(listDir(out_), Names{});
}

TEST_F(cliWarnings, AutomaticValuesAreReportedInTheSummary) {
  const fs::path dir = root_ / "sim";
  const std::string beams = simulate(*this, run({"simulate", "tank", "-o", dir.string(), "--turns", "2"}), dir);
  const ProgramRun result = run({"map", beams, "-o", (out_ / "MAP.bt").string(), "-q"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");  // a good map warns of nothing
  EXPECT_NE(result.out.find("0.02 m voxels"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("threshold 16.8 dB on 45 dB"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("min range 0.3"), std::string::npos) << result.out;  // the band's end
}

}  // namespace
}  // namespace sonarmap::test
