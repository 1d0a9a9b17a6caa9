// End-to-end tests of `sonarmap simulate` and `sonarmap demo`: the simulated files, their
// determinism, that they map into an octree OctoMap 1.9 reads (test-only dependency), the demo's
// tank quality, and the CLI's error contract. No shared data needed.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>

#include "cli_fixture.hpp"
#include "figure_checks.hpp"

namespace sonarmap::test {
namespace {

const Names kSimulationFiles{"beams.csv", "nav.csv", "scene.txt", "truth_nav.csv"};
const Names kDemoFiles{"3d-mission", "beams.csv",          "scene.txt",      "tank.bt",
                       "tank.html",  "tank.png",           "tank_cartesian.png", "tank_polar.png"};

/// Occupied leaves of the .bt at `path` (read by OctoMap) whose centre is within a voxel of z = 0.
std::size_t occupiedLeavesAtZ0(const fs::path& path) {
  octomap::OcTree tree(0.1);
  if (!tree.readBinary(path.string())) ADD_FAILURE() << "OctoMap cannot read " << path;
  std::size_t occupied = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    occupied += tree.isNodeOccupied(*it) && std::abs(it.getZ()) < tree.getResolution() ? 1 : 0;
  }
  return occupied;
}

using cliSim = CliTest;

TEST_F(cliSim, SimulateWritesBeamsNavAndSceneThatMapIntoAnOctoMapTree) {
  const fs::path dir = out_ / "run";
  const ProgramRun result = run({"simulate", "tank", "-o", dir.string(), "--turns", "2", "--seed", "7"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  // 2 turns of 200 beams, 43 ms apart: 17.157 s of fixes at 10 Hz, 0 s to 17.2 s.
  EXPECT_EQ(linesOf(result.out),
            (Names{"micron: 400 beams in 2 turns, 173 nav fixes, 4 scene primitives -> " + dir.string(),
                   "nav.csv, truth_nav.csv: the true track"}));
  // -q (no progress bar, which is drawn only on a terminal anyway): the same files and summary.
  const fs::path quiet = out_ / "quiet";
  const ProgramRun quiet_run = run({"simulate", "tank", "-o", quiet.string(), "--turns", "2", "--seed", "7", "-q"});
  ASSERT_EQ(quiet_run.exit_code, 0) << quiet_run.err;
  EXPECT_EQ(quiet_run.err, "");
  EXPECT_EQ(readFile(quiet / "beams.csv"), readFile(dir / "beams.csv"));
  EXPECT_EQ(listDir(dir), kSimulationFiles);
  const Names rows = linesOf(readFile(dir / "beams.csv"));
  ASSERT_EQ(rows.size(), 401U);  // header + 400 beams
  EXPECT_EQ(rows[0].rfind("time_s,bearing_deg,bin_length_m,b0,b1,", 0), 0U) << rows[0];
  EXPECT_EQ(linesOf(readFile(dir / "nav.csv"))[0], "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad");
  EXPECT_EQ(readFile(dir / "truth_nav.csv"), readFile(dir / "nav.csv")) << "no dead-reckoning error: nav is the truth";

  const fs::path bt = out_ / "run.bt";
  const ProgramRun mapped = run({"map", (dir / "beams.csv").string(), "-o", bt.string(), "-q"});
  ASSERT_EQ(mapped.exit_code, 0) << mapped.err;
  EXPECT_GT(occupiedLeavesAtZ0(bt), 500U) << "the tank's walls should be mapped";
}

/// FNV-1a hash of `text`'s bytes.
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (const unsigned char byte : text) hash = (hash ^ byte) * 1099511628211ULL;
  return hash;
}

TEST_F(cliSim, DefaultRunIsTheMicronAndUnchanged) {
  const fs::path plain = out_ / "plain", micron = out_ / "micron";
  ASSERT_EQ(run({"simulate", "tank", "-o", plain.string(), "--turns", "2", "--seed", "7"}).exit_code, 0);
  ASSERT_EQ(run({"simulate", "tank", "-o", micron.string(), "--turns", "2", "--seed", "7", "--sonar", "micron",
                 "--sector", "360"})
                .exit_code,
            0);
  // Hashes of the files `sonarmap simulate tank --turns 2 --seed 7` writes; they change only on
  // purpose. Bearings count clockwise from ahead while the simulated head turns
  // counter-clockwise, so its bearings are written decreasing.
  EXPECT_EQ(fnv1a(readFile(plain / "beams.csv")), 0x3355be1bedef9eb4ULL);
  EXPECT_EQ(fnv1a(readFile(plain / "nav.csv")), 0xe498463d125b3807ULL);
  EXPECT_EQ(fnv1a(readFile(plain / "scene.txt")), 0x959b743603971cd6ULL);  // in ENU since scene files name their frame
  for (const std::string& file : kSimulationFiles) EXPECT_EQ(readFile(plain / file), readFile(micron / file)) << file;
}

TEST_F(cliSim, SonarPresetScansASectorOfASceneBuiltForItsRange) {
  const fs::path dir = out_ / "ping360";
  const ProgramRun result = run({"simulate", "harbour", "-o", dir.string(), "--sonar", "ping360", "--sector", "90",
                                 "--sector-center", "-10", "--turns", "2", "--nav-rate", "0"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  // 90° in 1-gradian (0.9°) steps: 100 steps, 101 beams a pass.
  EXPECT_EQ(linesOf(result.out), Names{"ping360: 202 beams in 2 passes across a 90 deg sector, 0 nav fixes, 8 scene "
                                       "primitives -> " + dir.string()});
  const Names rows = linesOf(readFile(dir / "beams.csv"));
  ASSERT_EQ(rows.size(), 203U);
  EXPECT_NE(rows[0].find(",b1199"), std::string::npos);  // 1200 samples
  EXPECT_EQ(rows[0].find(",b1200"), std::string::npos);
  double previous_deg = 0.0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    double time_s = 0, bearing_deg = 0, bin_length_m = 0;
    ASSERT_EQ(std::sscanf(rows[i].c_str(), "%lf,%lf,%lf", &time_s, &bearing_deg, &bin_length_m), 3) << rows[i];
    EXPECT_NEAR(bin_length_m, 50.0 / 1200.0, 1e-12);
    EXPECT_LE(std::abs(std::remainder(bearing_deg + 10.0, 360.0)), 45.0 + 1e-6) << i;
    const double step_deg = std::remainder(bearing_deg - previous_deg, 360.0);
    if (i == 2) {
      EXPECT_NEAR(step_deg, -0.9, 1e-6);  // the first pass turns counter-clockwise: bearings decrease
    } else if (i == 103) {
      EXPECT_NEAR(step_deg, 0.9, 1e-6);  // the second one back
    }
    previous_deg = bearing_deg;
  }
  // The harbour built for 50 m: the quay's face at 35 m (its block's centre 60 m north: ENU y 60).
  EXPECT_NE(readFile(dir / "scene.txt").find("\nbox 0 60 "), std::string::npos) << readFile(dir / "scene.txt");
}

TEST_F(cliSim, HelpListsPresetsScenesAndUnits) {
  const ProgramRun help = run({"simulate", "--help"});
  ASSERT_EQ(help.exit_code, 0);
  for (const char* name :
       {"micron", "seaking-30", "seaking-50", "ping360", "imagenex-881a", "tank", "harbour", "hull", "soft", "open-water",
        "degrees", "m/s"}) {
    EXPECT_NE(help.out.find(name), std::string::npos) << name;
  }
}

TEST_F(cliSim, SameSeedGivesIdenticalFilesAndAnotherSeedOtherBeams) {
  const auto simulate = [&](const std::string& name, const std::string& seed) {
    const ProgramRun result = run({"simulate", "harbour", "-o", (out_ / name).string(), "--turns", "1", "--seed", seed,
                                   "--speed", "0.3", "--heading", "90"});
    EXPECT_EQ(result.exit_code, 0) << result.err;
  };
  simulate("a", "3");
  simulate("b", "3");
  simulate("c", "4");
  for (const std::string& file : kSimulationFiles) {
    SCOPED_TRACE(file);
    EXPECT_EQ(readFile(out_ / "a" / file), readFile(out_ / "b" / file));
  }
  EXPECT_NE(readFile(out_ / "a" / "beams.csv"), readFile(out_ / "c" / "beams.csv"));
  EXPECT_EQ(readFile(out_ / "a" / "nav.csv"), readFile(out_ / "c" / "nav.csv"));
}

TEST_F(cliSim, MovingRunNavigationFollowsSpeedAndHeading) {
  const fs::path dir = out_ / "moving";
  ASSERT_EQ(run({"simulate", "harbour", "-o", dir.string(), "--turns", "1", "--speed", "0.5", "--heading", "90",
                 "--nav-rate", "2"})
                .exit_code,
            0);
  const Names rows = linesOf(readFile(dir / "nav.csv"));
  ASSERT_EQ(rows.size(), 20U);  // header + 19 fixes every 0.5 s over the 8.557 s of beams: 0 … 9 s
  double time_s = 0, x_m = 0, y_m = 0, z_m = 0, roll_rad = 0, pitch_rad = 0, yaw_rad = 0;
  ASSERT_EQ(std::sscanf(rows.back().c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &time_s, &x_m, &y_m, &z_m, &roll_rad,
                        &pitch_rad, &yaw_rad),
            7)
      << rows.back();
  EXPECT_DOUBLE_EQ(time_s, 9.0);
  EXPECT_NEAR(x_m, 0.0, 1e-9);  // heading 90°: east, NED +y
  EXPECT_NEAR(y_m, 4.5, 1e-9);
  EXPECT_NEAR(yaw_rad, std::numbers::pi / 2, 1e-12);
}

TEST_F(cliSim, SceneFileGivesTheSameRunAsTheBuiltInScene) {
  ASSERT_EQ(run({"simulate", "tank", "-o", (out_ / "builtin").string(), "--turns", "1", "--nav-rate", "0"}).exit_code, 0);
  EXPECT_EQ(listDir(out_ / "builtin"), (Names{"beams.csv", "scene.txt"})) << "--nav-rate 0 writes no nav.csv";
  const fs::path scene = root_ / "my_tank.txt";
  fs::copy_file(out_ / "builtin" / "scene.txt", scene);
  ASSERT_EQ(run({"simulate", scene.string(), "-o", (out_ / "file").string(), "--turns", "1", "--nav-rate", "0"}).exit_code,
            0);
  EXPECT_EQ(readFile(out_ / "file" / "beams.csv"), readFile(out_ / "builtin" / "beams.csv"));
}

TEST_F(cliSim, DemoMapsTheSimulatedTankWithItsWalls) {
  const fs::path dir = out_ / "demo" / "nested";  // created with its parent
  const ProgramRun result = run({"demo", "-o", dir.string(), "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  EXPECT_EQ(listDir(dir), kDemoFiles);
  const Names lines = linesOf(result.out);
  ASSERT_EQ(lines.size(), 6U) << result.out;  // the tank's three, then the 3D run's (test_cli_3d.cpp)
  std::size_t used = 0, skipped = 0, sweeps = 0;
  ASSERT_EQ(std::sscanf(lines[0].c_str(), "%zu beams used, %zu skipped, %zu sweeps", &used, &skipped, &sweeps), 3)
      << lines[0];
  EXPECT_EQ(used, 5600U);  // 28 turns of 200 beams
  EXPECT_EQ(skipped, 0U);
  EXPECT_EQ(sweeps, 28U);
  EXPECT_NE(lines[0].find("-> " + (dir / "tank.bt").string()), std::string::npos) << lines[0];

  double slice_z_m = 1, width_m = 0, height_m = 0, angle_deg = 0, on_walls = 0, covered = 0, rms_m = 0,
         free_inside = 0, occupied_inside = 0;
  std::size_t cells = 0;
  ASSERT_EQ(std::sscanf(lines[1].c_str(),
                        "tank: slice z = %lf m up (the layer with the most occupied cells), %lf x %lf m at %lf deg, "
                        "%zu occupied cells, %lf on walls, %lf of walls covered, rms %lf m, inside %lf free %lf occupied",
                        &slice_z_m, &width_m, &height_m, &angle_deg, &cells, &on_walls, &covered, &rms_m, &free_inside,
                        &occupied_inside),
            10)
      << lines[1];
  EXPECT_NEAR(slice_z_m, 0.0, 0.05) << lines[1];  // the sonar's plane
  // The built-in tank's inner faces are 4.2 m × 4.4 m apart (sim/builtin_scenes.hpp).
  EXPECT_NEAR(std::min(width_m, height_m), 4.2, 0.15) << lines[1];
  EXPECT_NEAR(std::max(width_m, height_m), 4.4, 0.15) << lines[1];
  EXPECT_GT(on_walls, 0.9) << lines[1];
  EXPECT_GT(covered, 0.8) << lines[1];
  EXPECT_LT(rms_m, 0.05) << lines[1];
  EXPECT_GT(free_inside, 0.8) << lines[1];
  EXPECT_LT(occupied_inside, 0.02) << lines[1];
  EXPECT_EQ(occupiedLeavesAtZ0(dir / "tank.bt"), cells);

  // The tank's figures: >= 800 px with a title and axes; the walls near-black over light-grey
  // water, the static sonar a red dot at the origin.
  const cv::Mat tank = readFigure(dir / "tank.png");
  ASSERT_FALSE(tank.empty());
  EXPECT_GT(pixelsOf(tank, kOccupiedBgr), static_cast<int>(cells) * 9);  // at least 3 × 3 pixels a voxel
  EXPECT_GT(pixelsOf(tank, kFreeBgr), pixelsOf(tank, kOccupiedBgr));
  EXPECT_GT(pixelsOf(tank, kTrackBgr), 20);
  readFigure(dir / "tank_polar.png");
  readFigure(dir / "tank_cartesian.png");
}

TEST_F(cliSim, UsageErrorsExitTwoAndWriteNothing) {
  const std::string dir = (out_ / "x").string();
  const ProgramRun lake = run({"simulate", "lake", "-o", dir});  // neither a built-in scene nor a file
  expectError(lake, 2);
  EXPECT_NE(lake.err.find("quay3d"), std::string::npos) << lake.err;  // the 3D scene is listed too
  expectError(run({"simulate", "quay3d", "-o", dir, "--depth", "inf"}), 2);
  expectError(run({"simulate", "tank", "-o", dir, "--turns", "0"}), 2);
  expectError(run({"simulate", "tank", "-o", dir, "--nav-rate", "-1"}), 2);
  expectError(run({"simulate", "tank", "-o", dir, "--speed", "fast"}), 2);
  expectError(run({"simulate", "tank", "-o", dir, "--sonar", "seabat"}), 2);
  for (const std::string sector : {"0", "-90", "361", "nan"}) {
    expectError(run({"simulate", "tank", "-o", dir, "--sector", sector}), 2);
  }
  expectError(run({"simulate", "tank", "-o", dir, "--sector", "1"}), 2);  // less than one 1.8° step
  expectError(run({"simulate", "tank", "-o", dir, "--sector", "90", "--sector-center", "inf"}), 2);
  expectError(run({"simulate", "tank"}), 2);  // no -o
  writeFile(out_ / "file.txt", "a file, not a folder\n");
  expectError(run({"simulate", "tank", "-o", (out_ / "file.txt").string()}), 2);
  expectError(run({"demo", "-o", (out_ / "file.txt").string()}), 2);
  EXPECT_EQ(listDir(out_), Names{"file.txt"});
}

TEST_F(cliSim, DataAndOutputErrorsExitOneAndWriteNothing) {
  const fs::path scene = root_ / "bad_scene.txt";
  writeFile(scene, "box 0 0 0 1 1\n");  // too few fields
  const ProgramRun bad_scene = run({"simulate", scene.string(), "-o", (out_ / "x").string()});
  expectError(bad_scene, 1);
  EXPECT_NE(bad_scene.err.find("line 1"), std::string::npos) << bad_scene.err;
  // A folder cannot be created below a file.
  writeFile(out_ / "file.txt", "a file, not a folder\n");
  expectError(run({"simulate", "tank", "--turns", "1", "-o", (out_ / "file.txt" / "run").string()}), 1);
  EXPECT_EQ(listDir(out_), Names{"file.txt"});
}

TEST_F(cliSim, FailureAfterTheWorkLeavesNoFileBehind) {
  // A file a command commits is a folder: every output is computed and staged, that rename fails,
  // and no file stays renamed into place (simulate: the first file; demo: a file after several).
  fs::create_directories(out_ / "sim" / "scene.txt");
  expectError(run({"simulate", "tank", "--turns", "1", "-o", (out_ / "sim").string()}), 1);
  EXPECT_EQ(listDir(out_ / "sim"), Names{"scene.txt"});
  // The demo's 3D map is committed after the tank's files: they are rolled back.
  fs::create_directories(out_ / "demo" / "3d-mission" / "map.bt");
  expectError(run({"demo", "-q", "-o", (out_ / "demo").string()}), 1);
  EXPECT_EQ(listDir(out_ / "demo"), Names{"3d-mission"});
  EXPECT_EQ(listDir(out_ / "demo" / "3d-mission"), Names{"map.bt"});
}

}  // namespace
}  // namespace sonarmap::test
