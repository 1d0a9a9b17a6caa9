// End-to-end tests of the 3D outputs: `sonarmap map --3d` with the top view coloured by
// height (--png) and the side view (--side-png), the summary's height extent, and the demo: its two
// scoring commands (the tank, and the 3D run with its scoring file) run as printed, and the 3D run
// remade by the commands docs/commands.md gives. No shared data needed.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "cli_fixture.hpp"
#include "figure_checks.hpp"

namespace sonarmap::test {
namespace {

using cli3d = CliTest;

/// "occupied z LO .. HI m" of a summary line. Fails the test when it is missing.
std::pair<double, double> heightExtent(const std::string& line) {
  double lo = 0.0, hi = 0.0;
  const std::size_t at = line.find("occupied z ");
  EXPECT_NE(at, std::string::npos) << line;
  if (at == std::string::npos) return {0.0, 0.0};
  EXPECT_EQ(std::sscanf(line.c_str() + at, "occupied z %lf .. %lf m, ", &lo, &hi), 2) << line;
  return {lo, hi};
}

/// The figures' legend panel is at least this wide (render/figure.cpp) and right of the plot.
constexpr int kLegendCols = 200;

/// Distinct colours of the pixels of `image` (BGR) that are neither a shade of grey nor a shade of
/// the track's red, left of the legend panel (the plot, the axes and the title).
std::set<std::tuple<int, int, int>> colours(const cv::Mat& image) {
  std::set<std::tuple<int, int, int>> found;
  for (int row = 0; row < image.rows; ++row) {
    for (int col = 0; col < image.cols - kLegendCols; ++col) {
      const cv::Vec3b p = image.at<cv::Vec3b>(row, col);
      const bool reddish = p[0] == p[1] && p[2] > p[1];  // the track blended with white or grey
      if ((p[0] != p[1] || p[1] != p[2]) && !reddish) found.emplace(p[0], p[1], p[2]);
    }
  }
  return found;
}

/// The arguments of the command in `line` after "PREFIX  sonarmap ", split at spaces.
Names commandArgs(const std::string& line, const std::string& prefix) {
  const std::string marker = prefix + "  sonarmap ";
  EXPECT_EQ(line.rfind(marker, 0), 0U) << line;
  std::istringstream words(line.substr(marker.size()));
  Names args;
  for (std::string word; words >> word;) args.push_back(word);
  return args;
}

TEST_F(cli3d, MapWritesTopAndSideViewsAndTheHeightExtent) {
  const fs::path sim = root_ / "sim";
  ASSERT_EQ(run({"simulate", "tank", "-o", sim.string(), "--turns", "1", "--nav-rate", "0"}).exit_code, 0);
  const std::string beams = (sim / "beams.csv").string();
  const fs::path bt = out_ / "map.bt", top = out_ / "top.png", side = out_ / "side.png";
  const ProgramRun result = run({"map", beams, "-o", bt.string(), "--3d", "--resolution", "0.05", "--png",
                                 top.string(), "--side-png", side.string(), "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  const Names lines = linesOf(result.out);
  ASSERT_EQ(lines.size(), 1U) << result.out;
  // A static head cannot tell elevation: the tank's walls, about 2.1 m away, are bands of about
  // ±2.1 · tan(17.5°) = ±0.66 m around the sonar's plane.
  const auto [lo, hi] = heightExtent(lines[0]);
  EXPECT_LT(lo, -0.3) << lines[0];
  EXPECT_GT(hi, 0.3) << lines[0];
  EXPECT_EQ(listDir(out_), (Names{"map.bt", "side.png", "top.png"}));

  // OctoMap reads the map and finds occupied voxels over that height.
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(bt.string()));
  double tree_lo = 1e9, tree_hi = -1e9;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    tree_lo = std::min(tree_lo, it.getZ());
    tree_hi = std::max(tree_hi, it.getZ());
  }
  EXPECT_LT(tree_lo, -0.3);
  EXPECT_GT(tree_hi, 0.3);

  for (const fs::path& png : {top, side}) {
    SCOPED_TRACE(png.filename().string());
    const cv::Mat image = readFigure(png);  // >= 800 px, a title, axes
    ASSERT_FALSE(image.empty());
    // The view (left of the legend) has many colours: heights, or depths along y; nothing is
    // drawn in the planar map's near-black.
    EXPECT_GT(colours(image).size(), 10U);
    EXPECT_EQ(pixelsOf(image, kOccupiedBgr), 0);
  }
  // The slice of the planar model shows occupied voxels near-black, no colour scale.
  const ProgramRun planar = run({"map", beams, "-o", (root_ / "planar.bt").string(), "--resolution", "0.05", "--png",
                                 (root_ / "slice.png").string(), "-q"});
  ASSERT_EQ(planar.exit_code, 0) << planar.err;
  const cv::Mat slice = readFigure(root_ / "slice.png");
  EXPECT_GT(pixelsOf(slice, kOccupiedBgr), 1000);
  EXPECT_EQ(colours(slice).size(), 0U);
  // The planar map is one layer of voxels: its extent is that layer's centre.
  const auto [planar_lo, planar_hi] = heightExtent(linesOf(planar.out).at(0));
  EXPECT_LT(std::abs(planar_lo), 0.05);  // the voxels at z = 0.025 m
  EXPECT_DOUBLE_EQ(planar_hi, planar_lo);
}

TEST_F(cli3d, SidePngWithoutThe3dModelIsAUsageError) {
  const ProgramRun result = run({"map", (root_ / "beams.csv").string(), "-o", (out_ / "map.bt").string(),
                                 "--side-png", (out_ / "side.png").string()});
  expectError(result, 2);
  EXPECT_NE(result.err.find("--3d"), std::string::npos) << result.err;
  EXPECT_EQ(listDir(out_), Names{});
  const ProgramRun help = run({"map", "--help"});
  EXPECT_NE(help.out.find("--side-png"), std::string::npos);
}

// A level head 4 m deep in quay3d (1 m over its seabed, the surface 4 m above): with the water
// surface at the navigation's depth 0 (the default) its weak returns nearer than the surface can
// be are the seabed, and the map reaches down towards it; with the surface unknown they are not
// placed. A depth that is not metres or none is a usage error.
TEST_F(cli3d, WaterSurfaceDepthLetsALevelHeadMapTheSeabed) {
  const fs::path sim = root_ / "sim";
  ASSERT_EQ(run({"simulate", "quay3d", "-o", sim.string(), "--turns", "3", "--depth", "4"}).exit_code, 0);
  const std::string beams = (sim / "beams.csv").string(), nav = (sim / "nav.csv").string();
  const Names base{"map", beams, "--nav", nav, "--3d", "--resolution", "0.1", "-q"};
  auto mapped = [&](const std::string& depth, const fs::path& bt) {
    Names args = base;
    for (const std::string& word : {std::string("--water-surface-depth"), depth, std::string("-o"), bt.string()}) {
      args.push_back(word);
    }
    const ProgramRun result = run(args);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return heightExtent(linesOf(result.out).at(0));
  };
  // Occupied voxels of the seabed: 0.6 m or more under the sonar, off the quay and the piles.
  auto seabed = [](const fs::path& bt) {
    octomap::OcTree tree(0.1);
    EXPECT_TRUE(tree.readBinary(bt.string()));
    std::size_t count = 0;
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
      // The map is ENU, the scene NWU: the scene's (x north, y west) is (map y, −map x).
      const double north = it.getY(), west = -it.getX();
      bool near_pile = false;
      for (const auto& [x, y] : {std::pair{2.0, -2.5}, std::pair{2.0, 2.5}, std::pair{-3.0, -2.5}}) {
        near_pile = near_pile || std::hypot(north - x, west - y) < 0.6;
      }
      if (tree.isNodeOccupied(*it) && it.getZ() < -4.6 && north < 3.0 && !near_pile) ++count;
    }
    return count;
  };
  mapped("0", out_ / "known.bt");
  mapped("none", out_ / "unknown.bt");
  const std::size_t known = seabed(out_ / "known.bt"), unknown = seabed(out_ / "unknown.bt");
  std::printf("seabed voxels of a level head 4 m deep: %zu with the surface at depth 0, %zu without\n", known, unknown);
  EXPECT_GT(known, unknown + 50);
  Names bad = base;
  for (const char* word : {"--water-surface-depth", "deep", "-o"}) bad.emplace_back(word);
  bad.push_back((out_ / "bad.bt").string());
  const ProgramRun result = run(bad);
  expectError(result, 2);
  EXPECT_NE(result.err.find("--water-surface-depth"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(out_ / "bad.bt"));
}

TEST_F(cli3d, DemoPrintsTwoShortScoringCommandsThatScore) {
  const fs::path dir = out_ / "demo";
  const ProgramRun result = run({"demo", "-o", dir.string(), "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  const fs::path mission = dir / "3d-mission";
  EXPECT_EQ(listDir(mission), (Names{"beams.csv", "map.bt", "map.html", "map_side.png", "map_top.png", "nav.csv",
                                     "scene.txt", "scoring.json", "truth_nav.csv"}));
  for (const char* png : {"map_top.png", "map_side.png"}) {
    const cv::Mat image = readFigure(mission / png);
    ASSERT_FALSE(image.empty()) << png;
    EXPECT_GT(colours(image).size(), 10U) << png;
    // The vehicle's loop, 4 × 3 m seen from above, a line at z = −0.5 m from the side: red.
    EXPECT_GT(pixelsOf(image, kTrackBgr), std::string(png) == "map_top.png" ? 2000 : 500) << png;
  }
  // tank summary, tank report, its scoring command, the 3D run's header, its summary, its scoring command.
  const Names lines = linesOf(result.out);
  ASSERT_EQ(lines.size(), 6U) << result.out;
  EXPECT_EQ(lines[3], "3d: micron flying the tilted-loop mission over quay3d, sonar tilted 25 deg down, mapped with "
                      "--3d at 0.05 m -> " + mission.string());
  std::size_t used = 0, skipped = 0, without_nav = 0;
  ASSERT_EQ(std::sscanf(lines[4].c_str(), "%zu beams used, %zu skipped, %zu without navigation", &used, &skipped,
                        &without_nav),
            3)
      << lines[4];
  EXPECT_GT(used, 400U);  // the beams with an obstacle: the others clear nothing in 3D
  EXPECT_NE(lines[4].find("without obstacle (clearing nothing)"), std::string::npos) << lines[4];
  EXPECT_EQ(without_nav, 0U);
  const auto [lo, hi] = heightExtent(lines[4]);
  EXPECT_LT(lo, -1.5) << "the seabed, 2 m or more below the sonar";
  EXPECT_GT(hi, lo + 1.0);
  EXPECT_NE(lines[4].find("0.05 m voxels"), std::string::npos) << lines[4];
  EXPECT_NE(lines[4].find("-> " + (mission / "map.bt").string()), std::string::npos) << lines[4];

  // Two short commands, as a user pastes them: with the output folder named "demo", each is
  // shorter than 200 characters.
  std::size_t commands = 0;
  for (const std::string& line : lines) {
    const std::size_t at = line.find("  sonarmap ");
    if (at == std::string::npos) continue;
    ++commands;
    std::string command = line.substr(at + 2);
    for (std::size_t i = command.find(dir.string()); i != std::string::npos; i = command.find(dir.string(), i)) {
      command.replace(i, dir.string().size(), "demo");
    }
    EXPECT_LT(command.size(), 200U) << command;
  }
  EXPECT_EQ(commands, 2U) << result.out;

  // The tank's command scores the tank's map against its scene.
  const Names tank_args = commandArgs(lines[2], "tank: score it:");
  EXPECT_EQ(tank_args, (Names{"eval", (dir / "tank.bt").string(), "--truth", (dir / "scene.txt").string()}));
  const ProgramRun tank = run(tank_args);
  ASSERT_EQ(tank.exit_code, 0) << tank.err;
  double tank_precision = 0.0, tank_recall = 0.0;
  ASSERT_GE(linesOf(tank.out).size(), 2U) << tank.out;
  EXPECT_EQ(std::sscanf(linesOf(tank.out)[0].c_str(), "precision %lf", &tank_precision), 1) << tank.out;
  EXPECT_EQ(std::sscanf(linesOf(tank.out)[1].c_str(), "recall %lf", &tank_recall), 1) << tank.out;
  EXPECT_GT(tank_precision, 0.5);
  EXPECT_GT(tank_recall, 0.5);

  // The 3D command scores the map with the scoring file the demo wrote beside it: against what the
  // sonar could see and against the surface its 2,000 beams heard.
  const Names scoring_args = commandArgs(lines[5], "3d: score it (docs/accuracy.md):");
  EXPECT_EQ(scoring_args,
            (Names{"eval", (mission / "map.bt").string(), "--scoring", (mission / "scoring.json").string()}));
  const ProgramRun scored = run(scoring_args);
  ASSERT_EQ(scored.exit_code, 0) << scored.err;
  const Names metrics = linesOf(scored.out);
  ASSERT_GE(metrics.size(), 8U) << scored.out;
  double precision = 0.0, recall = 0.0, heard_recall = 0.0, heard_f1 = 0.0;
  EXPECT_EQ(std::sscanf(metrics[0].c_str(), "precision %lf", &precision), 1) << metrics[0];
  EXPECT_EQ(std::sscanf(metrics[1].c_str(), "recall %lf", &recall), 1) << metrics[1];
  EXPECT_EQ(std::sscanf(metrics[2].c_str(), "heard_recall %lf", &heard_recall), 1) << metrics[2];
  EXPECT_EQ(std::sscanf(metrics[3].c_str(), "heard_f1 %lf", &heard_f1), 1) << metrics[3];
  EXPECT_NE(metrics[4].find("by the micron head, 2000 beams traced (0 without navigation)"), std::string::npos)
      << metrics[4];
  // Scores, not the model's accuracy (docs/accuracy.md and tests/eval pin that): a map on the scene.
  EXPECT_GT(precision, 0.2);
  EXPECT_GT(recall, 0.0);
  EXPECT_GT(heard_recall, 0.5);
  EXPECT_LT(heard_recall, 1.0);
  EXPECT_GT(heard_f1, 0.0);

  // The file holds eval's options: the same options given on the command line score the same.
  const nlohmann::json file = nlohmann::json::parse(readFile(mission / "scoring.json"));
  const auto number = [](const nlohmann::json& value) {  // the shortest text that reads back: "-25"
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value.get<double>());
    return std::string(text);
  };
  const auto numbers = [&](const nlohmann::json& values) {
    std::string text;
    for (const nlohmann::json& value : values) {
      if (!text.empty()) text += ',';
      text += number(value);
    }
    return text;
  };
  Names long_form{"eval", (mission / "map.bt").string(), "--truth", (mission / "scene.txt").string(),
                  "--max-range", number(file.at("max-range")), "--vertical-aperture",
                  number(file.at("vertical-aperture")), "--heard-by", (mission / "beams.csv").string(), "--nav",
                  (mission / "truth_nav.csv").string(), "--mounting", numbers(file.at("mounting")), "--sonar",
                  file.at("sonar").get<std::string>()};
  EXPECT_EQ(numbers(file.at("mounting")), "0,0,0,0,-25,0");
  EXPECT_GE(file.at("sensor-pose").size(), 20U);  // the sonar's poses along the mission (missionTruthOptions)
  for (const nlohmann::json& pose : file.at("sensor-pose")) {
    ASSERT_EQ(pose.size(), 6U) << pose;
    // One sign for the tilt: each pose of the level vehicle is pitched −25°, as --mounting writes it.
    EXPECT_NEAR(pose[4].get<double>(), -25.0, 1e-3) << pose;
    EXPECT_NEAR(pose[3].get<double>(), 0.0, 1e-3) << pose;
    long_form.push_back("--sensor-pose");
    long_form.push_back(numbers(pose));
  }
  const ProgramRun given = run(long_form);
  ASSERT_EQ(given.exit_code, 0) << given.err;
  const Names given_metrics = linesOf(given.out);
  ASSERT_EQ(given_metrics.size(), metrics.size()) << given.out;
  // Every line but the last ("scored ... in S s"), which times the run.
  EXPECT_TRUE(std::equal(metrics.begin(), metrics.end() - 1, given_metrics.begin())) << scored.out << given.out;
  // What the command line gives wins over the file.
  const ProgramRun nearer = run({"eval", (mission / "map.bt").string(), "--scoring",
                                 (mission / "scoring.json").string(), "--max-range", "3", "-q"});
  ASSERT_EQ(nearer.exit_code, 0) << nearer.err;
  EXPECT_NE(nearer.out.find(", range 3.000 m,"), std::string::npos) << nearer.out;

  // The map command docs/commands.md gives for the 3D run makes the same map and pictures from the
  // files the demo wrote.
  const std::string map_bt = readFile(mission / "map.bt"), top = readFile(mission / "map_top.png"),
                    side = readFile(mission / "map_side.png");
  const Names map_args{"map", (mission / "beams.csv").string(), "--nav", (mission / "nav.csv").string(),
                       "--mounting", "0,0,0,0,-25,0", "--3d", "--resolution", "0.05", "--beam-width", "3",
                       "--vertical-aperture", "35", "-o", (mission / "map.bt").string(), "--png",
                       (mission / "map_top.png").string(), "--side-png", (mission / "map_side.png").string(), "-q"};
  const ProgramRun remade = run(map_args);
  ASSERT_EQ(remade.exit_code, 0) << remade.err;
  EXPECT_TRUE(readFile(mission / "map.bt") == map_bt) << "the remade map differs";
  EXPECT_TRUE(readFile(mission / "map_top.png") == top) << "the remade top view differs";
  EXPECT_TRUE(readFile(mission / "map_side.png") == side) << "the remade side view differs";

  // The mission is the simulator's named mission: the command docs/commands.md gives simulates the
  // same files.
  const Names simulate_args{"simulate", "quay3d", "--sonar", "micron", "--mission", "tilted-loop", "--seed", "1",
                            "-o", (out_ / "again").string(), "-q"};
  const ProgramRun again = run(simulate_args);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  for (const char* file : {"beams.csv", "nav.csv", "truth_nav.csv", "scene.txt"}) {
    EXPECT_TRUE(readFile(out_ / "again" / file) == readFile(mission / file)) << file << " differs";
  }
}

}  // namespace
}  // namespace sonarmap::test
