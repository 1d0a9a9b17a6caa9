// End-to-end tests of `sonarmap view`: its error contract (one line, exit code, nothing written),
// and the page it writes as headless Chromium shows it (browser_check.hpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <iostream>

#include "browser_check.hpp"
#include "cli_fixture.hpp"
#include "sonarmap/io/map_file.hpp"

namespace sonarmap::test {
namespace {

const fs::path kCrasLog = fs::path(SONARMAP_SHARED_DATA) / "cras_micron_tank_static.mat";

/// Occupied leaves of the map file at `path`: what the page must draw when not downsampled.
std::size_t occupiedLeaves(const fs::path& path) {
  const OcTree16 map = readMapFile(path.string());
  std::size_t occupied = 0;
  map.forEachLeaf([&](const LeafView<16>& leaf) { occupied += map.model().isOccupied(leaf.log_odds) ? 1 : 0; });
  return occupied;
}

class cliView : public CliTest {
 protected:
  /// A small map: a wall of 10 × 6 occupied voxels at 10 cm over a free floor.
  fs::path smallMap() const {
    OcTree16 map(0.1);
    for (int x = 0; x < 10; ++x) {
      for (int z = 0; z < 6; ++z) map.integrate(*map.coder().keyOf({0.1 * x + 0.05, 1.05, 0.1 * z + 0.05}), true);
      for (int y = 0; y < 10; ++y) map.integrate(*map.coder().keyOf({0.1 * x + 0.05, 0.1 * y + 0.05, -0.05}), false);
    }
    const fs::path path = root_ / "small.bt";
    writeMapFile(map, path.string());
    return path;
  }

  /// Opens `page` in Chromium (skipping when it is absent) and checks that it drew `expected_boxes`
  /// boxes and that its screenshot, kept as `screenshot`, is not blank.
  void expectShown(const fs::path& page, std::size_t expected_boxes, const fs::path& screenshot) const {
    const BrowserCheck check = checkInChromium(page, screenshot, root_);
    if (check.skipped) GTEST_SKIP() << check.message;
    std::cout << page.filename().string() << ": " << check.message << '\n';
    EXPECT_EQ(check.boxes, expected_boxes) << check.message;
    EXPECT_EQ(check.stated, expected_boxes) << check.message;
    EXPECT_TRUE(check.ok) << check.message;
    EXPECT_GE(check.bands, 1U) << check.message;
    EXPECT_EQ(check.unseen_bands, 0U) << check.message << " (a height band's mesh drew nothing)";
    EXPECT_LE(check.missing_px * 100, check.box_px) << check.message << " (meshes drew each other's boxes)";
    // The boxes alone cover pixels of the page's own frame; the screenshot is not blank: its centre
    // shows coloured boxes, not only the grey grid, and the page has many colours.
    EXPECT_GT(check.box_px, 1000U) << check.message;
    EXPECT_GT(check.page_painted_px, check.box_px) << check.message << " (grid, axes)";
    EXPECT_GT(check.centre_saturated_px, 500U) << check.message;
    EXPECT_GT(check.screenshot_colours, 50U) << check.message;
  }
};

TEST_F(cliView, WritesOnePageAndSaysWhatItDraws) {
  const fs::path map = smallMap(), page = out_ / "small.html";
  const ProgramRun result = run({"view", map.string(), "-o", page.string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  EXPECT_EQ(linesOf(result.out), Names{"60 occupied boxes (60 occupied leaves), " + std::string("100 free boxes (100 free leaves) -> ") +
                                       page.string()});
  EXPECT_EQ(listDir(out_), Names{"small.html"});
  const std::string html = readFile(page);
  EXPECT_NE(html.find("REVISION"), std::string::npos) << "three.js is inlined";
  EXPECT_NE(html.find("OrbitControls"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos) << "nothing is loaded from elsewhere";
  // The same map gives the same bytes.
  ASSERT_EQ(run({"view", map.string(), "-o", (root_ / "again.html").string()}).exit_code, 0);
  EXPECT_EQ(readFile(root_ / "again.html"), html);
}

// The navigation CSV's fixes (NED) become the page's trajectory in the viewer's frame, ENU
// (x east, y north, z up): (n, e, d) -> (e, n, -d).
TEST_F(cliView, TrajectoryIsTheNavigationInTheMapFrame) {
  const fs::path map = smallMap(), page = out_ / "small.html", nav = root_ / "nav.csv";
  writeFile(nav, "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n0,1,2,3,0,0,0\n1,1.5,-2,0.25,0,0,1\n");
  const ProgramRun result = run({"view", map.string(), "-o", page.string(), "--trajectory", nav.string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(readFile(page).find("\"trajectory_m\":[2,1,-3,-2,1.5,-0.25],\"trajectory_source\":\"nav.csv\""),
            std::string::npos);
}

TEST_F(cliView, AboveTheCapItDownsamplesAndSaysSoOnStderr) {
  const fs::path map = smallMap(), page = out_ / "small.html";
  const ProgramRun result = run({"view", map.string(), "-o", page.string(), "--max-boxes", "10"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const Names notes = linesOf(result.err);
  ASSERT_EQ(notes.size(), 1U) << result.err;
  EXPECT_EQ(notes[0].rfind("sonarmap: note: 60 occupied leaves exceed --max-boxes 10: drawn as ", 0), 0U) << notes[0];
  std::size_t boxes = 0;
  ASSERT_EQ(std::sscanf(result.out.c_str(), "%zu occupied boxes (60 occupied leaves)", &boxes), 1) << result.out;
  EXPECT_LE(boxes, 10U);
  EXPECT_GT(boxes, 0U);
  expectShown(page, boxes, root_ / "downsampled.png");
}

TEST_F(cliView, BadArgumentsAndInputsFailWithOneLineAndWriteNothing) {
  const fs::path map = smallMap();
  expectError(run({"view", (root_ / "missing.bt").string(), "-o", (out_ / "m.html").string()}), 1);
  expectError(run({"view", (root_ / "map.txt").string(), "-o", (out_ / "m.html").string()}), 2);
  expectError(run({"view", map.string(), "-o", (out_ / "m.png").string()}), 2);
  expectError(run({"view", map.string(), "-o", (out_ / "m.html").string(), "--max-boxes", "0"}), 2);
  writeFile(root_ / "broken.bt", "# Octomap OcTree binary file\nid OcTree\nsize 3\nres 0.1\ndata\n\x01");
  expectError(run({"view", (root_ / "broken.bt").string(), "-o", (out_ / "m.html").string()}), 1);
  writeFile(root_ / "nav.csv", "time_s,x_m\n1,2\n");
  expectError(run({"view", map.string(), "-o", (out_ / "m.html").string(), "--trajectory", (root_ / "nav.csv").string()}), 1);
  expectError(run({"view", map.string(), "-o", (out_ / "no" / "such" / "folder" / "m.html").string()}), 1);
  EXPECT_EQ(listDir(out_), Names{});
  // An existing page is left as it was when the new one cannot be made.
  writeFile(out_ / "keep.html", "old");
  expectError(run({"view", (root_ / "broken.bt").string(), "-o", (out_ / "keep.html").string()}), 1);
  EXPECT_EQ(readFile(out_ / "keep.html"), "old");
  EXPECT_EQ(listDir(out_), Names{"keep.html"});
}

// The pages of `sonarmap demo`: the simulated 3D mission's map.html (with the trajectory), and the
// simulated tank's tank.html, show every occupied leaf of their maps.
TEST_F(cliView, DemoMissionPageShowsEveryOccupiedLeafInChromium) {
  const fs::path dir = out_ / "demo";
  const ProgramRun demo = run({"demo", "-o", dir.string(), "-q"});
  ASSERT_EQ(demo.exit_code, 0) << demo.err;
  const fs::path mission = dir / "3d-mission";
  ASSERT_TRUE(fs::exists(mission / "map.html"));
  EXPECT_NE(readFile(mission / "map.html").find("\"trajectory_source\":\"nav.csv\""), std::string::npos);
  expectShown(mission / "map.html", occupiedLeaves(mission / "map.bt"), root_ / "mission.png");
}

TEST_F(cliView, DemoTankPageShowsEveryOccupiedLeafInChromium) {
  const fs::path dir = out_ / "demo";
  const ProgramRun demo = run({"demo", "-o", dir.string(), "-q"});
  ASSERT_EQ(demo.exit_code, 0) << demo.err;
  expectShown(dir / "tank.html", occupiedLeaves(dir / "tank.bt"), root_ / "tank.png");
}

TEST_F(cliView, CrasMapShowsEveryOccupiedLeafInChromium) {
  if (!fs::exists(kCrasLog)) GTEST_SKIP() << "shared data absent: " << kCrasLog;
  const fs::path map = out_ / "cras.bt", page = out_ / "cras.html";
  ASSERT_EQ(run({"map", kCrasLog.string(), "-o", map.string(), "-q"}).exit_code, 0);
  const ProgramRun result = run({"view", map.string(), "-o", page.string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  expectShown(page, occupiedLeaves(map), root_ / "cras.png");
}

}  // namespace
}  // namespace sonarmap::test
