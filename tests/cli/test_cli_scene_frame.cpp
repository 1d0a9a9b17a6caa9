// End-to-end tests of scene files in the map's frame: a wall written by hand in ENU (or NED) is
// simulated and mapped where its file says, read back by OctoMap (test-only dependency);
// `simulate` writes scene.txt in its --map-frame; a file with the old header (NWU, written before
// frames were named) still gives the same run and the same scores as its rewrites.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include <Eigen/Core>

#include "cli_fixture.hpp"
#include "octomap_leaves.hpp"

namespace sonarmap::test {
namespace {

/// Checks that the occupied voxels' coordinates across a wall at 5 m lie on it: the median on the
/// voxel (0.1 m) that holds it, nine in ten within 0.25 m (far along the wall the beam meets it at
/// a grazing angle and its footprint smears the echo behind it), all within 1 m.
void expectAtTheWall(std::vector<double> across_m) {
  ASSERT_FALSE(across_m.empty());
  std::sort(across_m.begin(), across_m.end());
  EXPECT_NEAR(across_m[across_m.size() / 2], 5.0, 0.1);
  std::size_t near = 0;
  for (const double x : across_m) near += std::abs(x - 5.0) < 0.25 ? 1 : 0;
  EXPECT_GE(static_cast<double>(near), 0.9 * static_cast<double>(across_m.size()));
  EXPECT_GT(across_m.front(), 4.0);
  EXPECT_LT(across_m.back(), 6.0);
}

constexpr const char* kEnuHeader =
    "# sonarmap scene: map frame ENU (x east, y north, z up), metres, radians; reflectivity in [0, 1]\n";

class cliSceneFrame : public CliTest {
 protected:
  /// Writes `text` to root/`name` and returns its path.
  fs::path writeText(const std::string& name, const std::string& text) const {
    const fs::path path = root_ / name;
    std::ofstream(path) << text;
    return path;
  }

  /// `simulate SCENE -o out/DIR` of a static Imagenex 881A (20 m) at the origin, heading north,
  /// two turns; `extra` appended.
  fs::path simulate(const fs::path& scene, const std::string& dir, Names extra = {}) const {
    const fs::path folder = out_ / dir;
    Names args{"simulate", scene.string(), "-o", folder.string(), "--sonar", "imagenex-881a", "--turns", "2", "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const ProgramRun sim = run(args);
    EXPECT_EQ(sim.exit_code, 0) << sim.err;
    return folder;
  }

  /// `map DIR/beams.csv --nav DIR/nav.csv -o out/NAME` with `extra`; returns the map's path.
  fs::path map(const fs::path& sim, const std::string& name, Names extra = {}) const {
    const fs::path bt = out_ / name;
    Names args{"map", (sim / "beams.csv").string(), "--nav", (sim / "nav.csv").string(), "-o", bt.string(), "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const ProgramRun mapped = run(args);
    EXPECT_EQ(mapped.exit_code, 0) << mapped.err;
    return bt;
  }
};

TEST_F(cliSceneFrame, WallWrittenInEnuIsMappedWhereTheFileSays) {
  // A wall 5 m east of the head, facing it: ENU x = 5.
  const fs::path wall = writeText("wall_enu.txt", std::string(kEnuHeader) + "plane 5 0 0  -1 0 0  0.9\n");
  const fs::path sim = simulate(wall, "enu");
  EXPECT_EQ(linesOf(readFile(sim / "scene.txt"))[0], linesOf(kEnuHeader)[0]);
  EXPECT_NE(readFile(sim / "scene.txt").find("\nplane 5 0 0 -1 0 0 0.9\n"), std::string::npos)
      << readFile(sim / "scene.txt");  // written back as it was read

  const std::vector<Eigen::Vector3d> occupied = occupiedCentres(map(sim, "enu.bt"));
  ASSERT_GE(occupied.size(), 100u);
  std::vector<double> east_m;
  double min_y = 1e9, max_y = -1e9;
  for (const Eigen::Vector3d& p : occupied) {
    east_m.push_back(p.x());
    min_y = std::min(min_y, p.y());
    max_y = std::max(max_y, p.y());
  }
  expectAtTheWall(east_m);
  EXPECT_LT(min_y, -5.0);  // along the wall, north and south of the head
  EXPECT_GT(max_y, 5.0);

  // eval reads the ENU scene and the ENU map into one frame: the wall's voxels match it.
  const ProgramRun scored = run({"eval", (out_ / "enu.bt").string(), "--truth", wall.string(), "-q"});
  ASSERT_EQ(scored.exit_code, 0) << scored.err;
  double precision = 0.0;
  ASSERT_EQ(std::sscanf(scored.out.c_str(), "precision %lf", &precision), 1) << scored.out;
  EXPECT_GT(precision, 0.9);

  // simulate --map-frame ned writes the same wall in NED (y east = 5), and the NED map has it there.
  const fs::path sim_ned = simulate(wall, "ned", {"--map-frame", "ned"});
  EXPECT_EQ(readFile(sim_ned / "beams.csv"), readFile(sim / "beams.csv"));
  EXPECT_NE(readFile(sim_ned / "scene.txt").find("map frame NED (x north, y east, z down)"), std::string::npos);
  EXPECT_NE(readFile(sim_ned / "scene.txt").find("\nplane 0 5 0 0 -1 0 0.9\n"), std::string::npos)
      << readFile(sim_ned / "scene.txt");
  const std::vector<Eigen::Vector3d> in_ned = occupiedCentres(map(sim_ned, "ned.bt", {"--map-frame", "ned"}));
  ASSERT_EQ(in_ned.size(), occupied.size());
  std::vector<double> ned_east_m;
  for (const Eigen::Vector3d& p : in_ned) ned_east_m.push_back(p.y());
  expectAtTheWall(ned_east_m);
}

TEST_F(cliSceneFrame, OldHeaderSceneGivesTheSameRunAndScoresAsItsRewrites) {
  // Written before frames were named: NWU (x north, y west, z up). A wall 4 m west, a pile 3 m
  // north and 2 m east, a block turned 30° from north towards west, 5 m south.
  const fs::path old_scene = writeText(
      "old.txt",
      "# sonarmap scene: map frame (x north, y west, z up), metres, radians; reflectivity in [0, 1]\n"
      "plane 0 4 0  0 -1 0  0.9\n"
      "cylinder 3 -2 0.3 -3 3 0.8\n"
      "box -5 0 0  1 3 2  0.5235987755982988  0.7\n");
  const fs::path from_old = simulate(old_scene, "old");
  // simulate wrote the scene in ENU; read back, the same scene gives the same run byte for byte.
  EXPECT_NE(readFile(from_old / "scene.txt").find(kEnuHeader), std::string::npos);
  const fs::path enu_scene = root_ / "rewritten_enu.txt";
  fs::copy_file(from_old / "scene.txt", enu_scene);
  const fs::path from_enu = simulate(enu_scene, "enu");
  EXPECT_EQ(readFile(from_enu / "beams.csv"), readFile(from_old / "beams.csv"));
  EXPECT_EQ(readFile(from_enu / "scene.txt"), readFile(enu_scene));
  const fs::path from_ned = simulate(old_scene, "ned", {"--map-frame", "ned"});
  const fs::path ned_scene = root_ / "rewritten_ned.txt";
  fs::copy_file(from_ned / "scene.txt", ned_scene);
  EXPECT_EQ(readFile(simulate(ned_scene, "ned_again") / "beams.csv"), readFile(from_old / "beams.csv"));

  // eval --truth: the same scores, line for line, from the old file and from its rewrites.
  const fs::path bt = map(from_old, "old.bt");
  // The last line ends with the time taken, which varies.
  auto scores = [&](const fs::path& scene) {
    const ProgramRun eval = run({"eval", bt.string(), "--truth", scene.string(), "-q"});
    EXPECT_EQ(eval.exit_code, 0) << eval.err;
    Names lines = linesOf(eval.out);
    if (!lines.empty()) lines.back() = lines.back().substr(0, lines.back().rfind(" in "));
    return lines;
  };
  const Names old_scores = scores(old_scene);
  ASSERT_GE(old_scores.size(), 10u);
  EXPECT_EQ(old_scores[6].rfind("surface 0 plane", 0), 0u) << old_scores[6];  // the wall is matched
  EXPECT_EQ(scores(enu_scene), old_scores);
  EXPECT_EQ(scores(ned_scene), old_scores);
}

TEST_F(cliSceneFrame, UnknownFrameIsOneLineNamingTheLine) {
  const fs::path bad = writeText("bad.txt",
                                 "# sonarmap scene: map frame ECEF (x, y, z), metres\nplane 5 0 0 -1 0 0 0.9\n");
  const ProgramRun result = run({"simulate", bad.string(), "-o", (out_ / "sim").string(), "-q"});
  expectError(result, 1);
  EXPECT_NE(result.err.find(bad.string() + ": line 1: scene frame 'ECEF' unknown, expected ENU, NED or NWU"),
            std::string::npos)
      << result.err;
  EXPECT_FALSE(fs::exists(out_ / "sim" / "beams.csv"));
}

}  // namespace
}  // namespace sonarmap::test
