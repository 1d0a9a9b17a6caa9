// End-to-end tests that a run failing half way changes nothing: every output is computed and
// staged, the first ones are already renamed into place, then a later one cannot be (a folder is
// in its way). The run must exit 1 with one line naming that file, the previous run's outputs must
// be byte for byte what they were, files the run created must be gone, and no temporary or backup
// file may remain (listDir lists hidden files too). Inputs come from `sonarmap simulate`.
#include <gtest/gtest.h>

#include <map>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

using Contents = std::map<std::string, std::string>;

class cliAtomic : public CliTest {
 protected:
  /// Simulates one turn of `scene` with `seed` into root/`name` (outside out_); returns the folder.
  fs::path simulate(const std::string& name, const std::string& scene, const std::string& seed) const {
    const fs::path dir = root_ / name;
    const ProgramRun result = run({"simulate", scene, "-o", dir.string(), "--turns", "1", "--seed", seed});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return dir;
  }

  /// The content of each of `names` in `dir`.
  static Contents contentsOf(const fs::path& dir, const Names& names) {
    Contents contents;
    for (const std::string& name : names) contents[name] = readFile(dir / name);
    return contents;
  }

  /// Puts a non-empty folder where `path` (an output) would go.
  static void blockWithFolder(const fs::path& path) {
    fs::remove(path);
    fs::create_directory(path);
    writeFile(path / "keep.txt", "a user's file\n");
  }

  /// Exit 1, one line on stderr naming `path`, and the folder at `path` untouched.
  static void expectFailedOn(const ProgramRun& result, const fs::path& path) {
    expectError(result, 1);
    std::string quoted = "'";  // appended piecewise: GCC 12 warns falsely on "'" + std::string
    quoted += path.string();
    quoted += "'";
    EXPECT_NE(result.err.find(quoted), std::string::npos) << result.err;
    EXPECT_EQ(readFile(path / "keep.txt"), "a user's file\n");
  }
};

TEST_F(cliAtomic, MapFailingOnItsLastImageKeepsThePreviousMapAndImages) {
  const fs::path first = simulate("first", "tank", "1") / "beams.csv";
  const fs::path second = simulate("second", "harbour", "2") / "beams.csv";
  const fs::path bt = out_ / "MAP.bt", top = out_ / "TOP.png", polar = out_ / "POLAR.png", cartesian = out_ / "CART.png";
  ASSERT_EQ(run({"map", first.string(), "-o", bt.string(), "--polar-png", polar.string(), "-q", "--resolution", "0.1"})
                .exit_code,
            0);
  const Contents before = contentsOf(out_, {"MAP.bt", "POLAR.png"});

  // Staged and renamed in this order: MAP.bt (exists), TOP.png (new), POLAR.png (exists), then
  // CART.png, whose rename fails.
  blockWithFolder(cartesian);
  const Names again{"map", second.string(), "-o", bt.string(), "--png", top.string(), "--polar-png", polar.string(),
                    "--cartesian-png", cartesian.string(), "-q", "--resolution", "0.1"};
  expectFailedOn(run(again), cartesian);
  EXPECT_TRUE(contentsOf(out_, {"MAP.bt", "POLAR.png"}) == before) << "an earlier output was replaced";
  EXPECT_EQ(listDir(out_), (Names{"CART.png", "MAP.bt", "POLAR.png"})) << "TOP.png or a temporary file remains";

  // With the folder out of the way the same run replaces both: the files above were really restored.
  fs::remove_all(cartesian);
  ASSERT_EQ(run(again).exit_code, 0);
  EXPECT_NE(readFile(bt), before.at("MAP.bt"));
  EXPECT_NE(readFile(polar), before.at("POLAR.png"));
  EXPECT_EQ(listDir(out_), (Names{"CART.png", "MAP.bt", "POLAR.png", "TOP.png"}));
}

TEST_F(cliAtomic, SimulateFailingOnItsLastFileKeepsThePreviousRun) {
  const fs::path dir = out_ / "sim";
  ASSERT_EQ(run({"simulate", "harbour", "-o", dir.string(), "--turns", "1", "--seed", "1"}).exit_code, 0);
  const Contents before = contentsOf(dir, {"beams.csv", "scene.txt", "truth_nav.csv"});

  // Staged and renamed in this order: scene.txt, beams.csv, then nav.csv, whose rename fails
  // (truth_nav.csv, after it, is not replaced either).
  blockWithFolder(dir / "nav.csv");
  expectFailedOn(run({"simulate", "tank", "-o", dir.string(), "--turns", "1", "--seed", "2"}), dir / "nav.csv");
  EXPECT_TRUE(contentsOf(dir, {"beams.csv", "scene.txt", "truth_nav.csv"}) == before) << "an earlier output was replaced";
  EXPECT_EQ(listDir(dir), (Names{"beams.csv", "nav.csv", "scene.txt", "truth_nav.csv"}));
}

TEST_F(cliAtomic, DemoFailingOnItsLastFileKeepsEveryOtherFile) {
  const Names earlier{"scene.txt", "tank.bt", "tank.png", "tank_cartesian.png", "tank_polar.png"};
  for (const std::string& name : earlier) writeFile(out_ / name, "old " + name + "\n");
  // The map's outputs, then scene.txt, are renamed into place before beams.csv fails.
  blockWithFolder(out_ / "beams.csv");
  expectFailedOn(run({"demo", "-q", "-o", out_.string()}), out_ / "beams.csv");
  for (const std::string& name : earlier) EXPECT_EQ(readFile(out_ / name), "old " + name + "\n");
  EXPECT_EQ(listDir(out_), (Names{"beams.csv", "scene.txt", "tank.bt", "tank.png", "tank_cartesian.png",
                                  "tank_polar.png"}));
}

}  // namespace
}  // namespace sonarmap::test
