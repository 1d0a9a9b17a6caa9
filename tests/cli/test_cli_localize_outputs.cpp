// End-to-end tests of `sonarmap localize --map/--png`: the point scans placed on the corrected track
// as an occupancy map (read back with Debian's OctoMap) and as a picture beside the navigation's.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

using cliLocalizeOutputs = CliTest;

/// A still head in the middle of a square pool, 8 m across: 6 turns of 180 beams, one point per
/// beam on the walls, in the body frame (x forward = north, y starboard = east).
void writePoolScans(const fs::path& path) {
  std::ofstream csv(path);
  csv << "scan,time_s,x_m,y_m\n";
  for (int scan = 0; scan < 6; ++scan) {
    for (int k = 0; k < 180; ++k) {
      const double a = k * 2.0 * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
      const double r = std::min(std::abs(c) > 1e-9 ? 4.0 / std::abs(c) : 1e9, std::abs(s) > 1e-9 ? 4.0 / std::abs(s) : 1e9);
      csv << scan << ',' << 10.0 * scan + 0.05 * k << ',' << r * c << ',' << r * s << '\n';
    }
  }
}

TEST_F(cliLocalizeOutputs, TheMapAndPictureShowTheScansOnTheCorrectedTrack) {
  const fs::path scans = out_ / "pool.csv";
  writePoolScans(scans);
  const ProgramRun alone = run({"localize", scans.string(), "--trajectory", (out_ / "t.csv").string(), "--map",
                                (out_ / "pool.bt").string(), "--png", (out_ / "alone.png").string(), "--resolution", "0.1"});
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  EXPECT_NE(alone.out.find("0.1 m voxels -> " + (out_ / "pool.bt").string() + " in ENU"), std::string::npos) << alone.out;
  // OctoMap reads the map: every occupied voxel on the pool's walls (±4 m), each wall seen, the
  // water before them free.
  octomap::OcTree tree((out_ / "pool.bt").string());
  ASSERT_NEAR(tree.getResolution(), 0.1, 1e-9);
  std::size_t occupied = 0, north_wall = 0;
  for (auto leaf = tree.begin_leafs(); leaf != tree.end_leafs(); ++leaf) {
    if (!tree.isNodeOccupied(*leaf)) continue;
    ++occupied;
    const double x = leaf.getX(), y = leaf.getY();  // ENU: east, north
    EXPECT_NEAR(std::max(std::abs(x), std::abs(y)), 4.0, 0.1) << x << ", " << y;
    if (y > 3.9 && std::abs(x) < 1.0) ++north_wall;
  }
  EXPECT_GT(occupied, 100U);
  EXPECT_GT(north_wall, 3U);
  const octomap::OcTreeNode* water = tree.search(0.05, 2.05, 0.05);
  ASSERT_NE(water, nullptr);
  EXPECT_FALSE(tree.isNodeOccupied(water));
  EXPECT_EQ(tree.search(0.05, 6.05, 0.05), nullptr);  // behind the wall: never seen
  // With navigation the picture has two panels (the scans on it, and on the corrected track).
  {
    std::ofstream nav(out_ / "nav.csv");
    nav << "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n";
    for (int i = 0; i <= 70; ++i) nav << i << ",0,0,0,0,0,0\n";
  }
  const ProgramRun with_nav = run({"localize", scans.string(), "--nav", (out_ / "nav.csv").string(), "--trajectory",
                                   (out_ / "t2.csv").string(), "--png", (out_ / "nav.png").string(), "-q"});
  ASSERT_EQ(with_nav.exit_code, 0) << with_nav.err;
  const cv::Mat one = cv::imread((out_ / "alone.png").string());
  const cv::Mat two = cv::imread((out_ / "nav.png").string());
  ASSERT_FALSE(one.empty());
  ASSERT_FALSE(two.empty());
  EXPECT_GT(two.cols, 1.8 * one.cols * (static_cast<double>(two.rows) / one.rows) - 1.0);
  EXPECT_NE(alone.out.find("picture: 0.1 m cells -> " + (out_ / "alone.png").string()), std::string::npos) << alone.out;
}

TEST_F(cliLocalizeOutputs, ABadOutputIsRefusedBeforeAnyWork) {
  const fs::path scans = out_ / "pool.csv";
  writePoolScans(scans);
  const ProgramRun png_map = run({"localize", scans.string(), "--trajectory", (out_ / "t.csv").string(), "--map",
                                  (out_ / "m.png").string()});
  expectError(png_map, 2);
  EXPECT_NE(png_map.err.find("--map"), std::string::npos) << png_map.err;
  const ProgramRun bt_png = run({"localize", scans.string(), "--trajectory", (out_ / "t.csv").string(), "--png",
                                 (out_ / "p.bt").string()});
  expectError(bt_png, 2);
  const ProgramRun negative = run({"localize", scans.string(), "--trajectory", (out_ / "t.csv").string(), "--resolution", "-1"});
  expectError(negative, 2);
  const ProgramRun zero = run({"localize", scans.string(), "--trajectory", (out_ / "t.csv").string(), "--resolution", "0"});
  expectError(zero, 2);
  EXPECT_NE(zero.err.find("--resolution"), std::string::npos) << zero.err;
  EXPECT_EQ(listDir(out_), Names{"pool.csv"});
}

// The outputs appear together or not at all: a map that cannot be written (its folder is missing),
// or cannot hold the scans at the resolution asked, leaves no trajectory either.
TEST_F(cliLocalizeOutputs, AMapThatCannotBeWrittenLeavesNoOutput) {
  const fs::path scans = out_ / "pool.csv";
  writePoolScans(scans);
  const ProgramRun missing = run({"localize", scans.string(), "--trajectory", (out_ / "t.csv").string(), "--map",
                                  (out_ / "no_such_dir" / "m.bt").string(), "--png", (out_ / "p.png").string()});
  expectError(missing, 1);
  EXPECT_NE(missing.err.find("no_such_dir"), std::string::npos) << missing.err;
  EXPECT_EQ(listDir(out_), Names{"pool.csv"});
  // At 0.1 mm a map spans ±3.3 m: the pool's walls, 4 m away, are outside it.
  const ProgramRun fine = run({"localize", scans.string(), "--trajectory", (out_ / "t.csv").string(), "--map",
                               (out_ / "m.bt").string(), "--resolution", "0.0001"});
  expectError(fine, 1);
  EXPECT_NE(fine.err.find("outside the map"), std::string::npos) << fine.err;
  EXPECT_EQ(listDir(out_), Names{"pool.csv"});
}

}  // namespace
}  // namespace sonarmap::test
