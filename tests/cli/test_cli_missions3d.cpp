// End-to-end tests of the 3D missions of `sonarmap simulate` (sim/missions.hpp): any head
// flies the tilted loop with any mounting (--mounting, as `map --mounting`), and the map command it
// prints maps the run in 3D with that mounting. No shared data needed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

using cliMissions3d = CliTest;

/// The arguments of the command after "map it:  sonarmap " in `out`. Fails the test when missing.
Names printedMapCommand(const std::string& out) {
  const std::string marker = "map it:  sonarmap ";
  for (const std::string& line : linesOf(out)) {
    if (line.rfind(marker, 0) != 0) continue;
    std::istringstream words(line.substr(marker.size()));
    Names args;
    for (std::string word; words >> word;) args.push_back(word);
    return args;
  }
  ADD_FAILURE() << "no map command in:\n" << out;
  return {};
}

/// The precision `sonarmap eval MAP --truth SCENE` reported (its first line).
double precisionOf(const ProgramRun& scored) {
  EXPECT_EQ(scored.exit_code, 0) << scored.err;
  double precision = -1.0;
  EXPECT_EQ(std::sscanf(scored.out.c_str(), "precision %lf", &precision), 1) << scored.out;
  return precision;
}

/// The value after `option` in `args` ("" when absent).
std::string valueOf(const Names& args, const std::string& option) {
  for (std::size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[i] == option) return args[i + 1];
  }
  return {};
}

// Two heads fly the tilted loop with the sonar mounted 0.3 m ahead, 0.2 m down, tilted 45° down and
// turned 30° to starboard (not the mission's default 25° tilt); the map command simulate prints
// maps it in 3D with that mounting, so the occupied voxels lie on the scene: several times the
// precision of the same log mapped with the mission's default mounting.
TEST_F(cliMissions3d, TheTiltedLoopFliesWithAnyMountingAndItsMapCommandUsesIt) {
  const std::string mounting = "0.3,0,0.2,0,-45,30";
  for (const char* sonar : {"micron", "ping360-5m"}) {
    const fs::path dir = out_ / sonar;
    const ProgramRun simulated = run({"simulate", "quay3d", "--sonar", sonar, "--mission", "tilted-loop", "--mounting",
                                      mounting, "-o", dir.string(), "-q"});
    ASSERT_EQ(simulated.exit_code, 0) << sonar << ": " << simulated.err;
    EXPECT_EQ(listDir(dir), (Names{"beams.csv", "nav.csv", "scene.txt", "truth_nav.csv"})) << sonar;
    EXPECT_NE(simulated.out.find("mission tilted-loop: 1 lap(s)"), std::string::npos) << simulated.out;
    Names map_args = printedMapCommand(simulated.out);
    ASSERT_FALSE(map_args.empty());
    EXPECT_EQ(map_args[0], "map");
    EXPECT_EQ(valueOf(map_args, "--mounting"), mounting) << sonar;
    EXPECT_EQ(valueOf(map_args, "--nav"), (dir / "nav.csv").string());
    EXPECT_NE(std::find(map_args.begin(), map_args.end(), "--3d"), map_args.end()) << sonar;
    // At 0.1 m, to score quickly: the mounting moves surfaces by far more.
    map_args.insert(map_args.end(), {"--resolution", "0.1", "-q"});
    const ProgramRun mapped = run(map_args);
    ASSERT_EQ(mapped.exit_code, 0) << sonar << ": " << mapped.err;
    const double precision = precisionOf(run({"eval", (dir / "map.bt").string(), "--truth", (dir / "scene.txt").string()}));

    Names wrong_args = map_args;
    for (std::size_t i = 0; i + 1 < wrong_args.size(); ++i) {
      if (wrong_args[i] == "--mounting") wrong_args[i + 1] = "0,0,0,0,-25,0";
      if (wrong_args[i] == "-o") wrong_args[i + 1] = (dir / "wrong.bt").string();
    }
    ASSERT_EQ(run(wrong_args).exit_code, 0) << sonar;
    const double wrong_precision = precisionOf(run({"eval", (dir / "wrong.bt").string(), "--truth", (dir / "scene.txt").string()}));
    // Today (at 0.1 m) 0.65 against 0.10 (micron), 0.76 against 0.11 (ping360-5m).
    EXPECT_GT(precision, 0.15) << sonar;
    EXPECT_GT(precision, 3.0 * wrong_precision) << sonar << ": the map does not use the simulated mounting";
  }
}

// Every head preset flies the 3D missions, sized by its range.
TEST_F(cliMissions3d, EveryPresetFliesTheTiltedLoop) {
  for (const char* sonar : {"micron", "seaking-30", "seaking-50", "ping360", "ping360-2m", "ping360-5m",
                            "imagenex-881a"}) {
    const fs::path dir = out_ / sonar;
    const ProgramRun simulated =
        run({"simulate", "quay3d", "--sonar", sonar, "--mission", "tilted-loop", "-o", dir.string(), "-q"});
    ASSERT_EQ(simulated.exit_code, 0) << sonar << ": " << simulated.err;
    EXPECT_EQ(valueOf(printedMapCommand(simulated.out), "--mounting"), "0,0,0,0,-25,0") << sonar;
  }
  const ProgramRun mower = run({"simulate", "quay3d", "--sonar", "ping360-2m", "--mission", "lawnmower-3d", "-o",
                                (out_ / "mower").string(), "-q"});
  ASSERT_EQ(mower.exit_code, 0) << mower.err;
  EXPECT_EQ(valueOf(printedMapCommand(mower.out), "--mounting"), "0,0,0,0,0,0");
}

// A mounting that is not six finite numbers is refused in one line, before anything is written.
TEST_F(cliMissions3d, ABadMountingIsOneLineAndNoOutput) {
  for (const char* mounting : {"0,0,0,0,nan,0", "0,0,0,0,inf,0"}) {
    const ProgramRun result = run({"simulate", "quay3d", "--mission", "tilted-loop", "--mounting", mounting, "-o",
                                   (out_ / "sim").string(), "-q"});
    expectError(result, 2);
    EXPECT_NE(result.err.find("--mounting expects six finite numbers X,Y,Z,ROLL,PITCH,YAW"), std::string::npos)
        << result.err;
    EXPECT_FALSE(fs::exists(out_ / "sim")) << mounting;
  }
  const ProgramRun short_list =
      run({"simulate", "quay3d", "--mission", "tilted-loop", "--mounting", "1,2", "-o", (out_ / "sim").string()});
  expectError(short_list, 2);
  EXPECT_NE(short_list.err.find("--mounting"), std::string::npos) << short_list.err;
}

}  // namespace
}  // namespace sonarmap::test
