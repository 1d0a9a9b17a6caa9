// End-to-end tests of `sonarmap eval`: a map scored against a scene file or a built-in scene, one
// line per metric, against the surface its log's beams heard (--heard-by), and the CLI's error
// contract.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>

#include "cli_fixture.hpp"
#include "figure_checks.hpp"
#include "sonarmap/eval/heard_surface.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/scene_file.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap::test {
namespace {

using cliEval = CliTest;

/// A 0.1 m map: water in front of a wall at x = 1.05 m, the wall mapped on rows −5…−1 one voxel
/// too near (x = 0.95 m). Seen from the origin, the wall's voxels of rows −6…5 (the known rows
/// grown by the tolerance, within the map's reach + tolerance: 1.226 m) are the surface.
fs::path writeWallMap(const fs::path& path) {
  OcTree16 map(0.1);
  auto key = [&](int i, int j) { return map.coder().keyOfChecked({(i + 0.5) * 0.1, (j + 0.5) * 0.1, 0.05}); };
  for (int j = -5; j < 5; ++j) {
    for (int i = 0; i < (j < 0 ? 9 : 10); ++i) map.updateNode(key(i, j), -2.0F);
  }
  for (int j = -5; j < 0; ++j) map.updateNode(key(9, j), 2.0F);
  writeMapFile(map, path.string());
  return path;
}

TEST_F(cliEval, ScoresAMapAgainstASceneFileLineByLine) {
  const fs::path map = writeWallMap(root_ / "wall.bt");
  const fs::path scene = root_ / "wall.scene";
  std::ofstream(scene) << "# the wall\nplane 1.05 0 0  1 0 0  0.9\n";
  const ProgramRun result = run({"eval", map.string(), "--truth", scene.string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  Names lines = linesOf(result.out);
  ASSERT_EQ(lines.size(), 9U) << result.out;
  // The summary line last: the voxels scored, the time (not compared), the map.
  EXPECT_EQ(lines.back().rfind("scored 5 occupied, 12 surface and 95 free voxels of " + map.string() + " in ", 0), 0U)
      << lines.back();
  lines.pop_back();
  EXPECT_EQ(lines,
            (Names{"precision 1.0000 (5 of 5 occupied voxels on a surface)",
                   "recall 0.5833 (7 of 12 visible surface voxels mapped)",
                   "erosion 0.0000 (0 of 12 visible surface voxels free)",
                   "free_accuracy 1.0000 (95 of 95 free voxels in the water)",
                   "wall_error_mean_m 0.1000 rms_m 0.1000 (5 occupied voxels within 0.50 m of a surface)",
                   "surface_error_median_m 0.1000 p90_m 0.1000 (over 5 occupied voxels)",
                   "surface 0 plane median_offset_m +0.1000 (5 voxels)",
                   "region z [0.050, 0.050] m, range 1.226 m, tolerance 0.173 m"}));
  // A tighter tolerance (raised to the voxel diagonal) and a sensor behind the wall.
  const ProgramRun behind =
      run({"eval", map.string(), "--truth", scene.string(), "--tolerance", "0.01", "--sensor", "2,0,0.05"});
  ASSERT_EQ(behind.exit_code, 0) << behind.err;
  lines = linesOf(behind.out);
  ASSERT_EQ(lines.size(), 9U) << behind.out;
  EXPECT_EQ(lines[6], "surface 0 plane median_offset_m -0.1000 (5 voxels)");
  EXPECT_EQ(lines[3], "free_accuracy 0.0526 (5 of 95 free voxels in the water)");  // only column 9 near the wall
}

TEST_F(cliEval, PngColoursTheOccupiedVoxelsByTheirDistanceToTheTruth) {
  const fs::path map = writeWallMap(root_ / "wall.bt");
  const fs::path scene = root_ / "wall.scene";
  std::ofstream(scene) << "plane 1.05 0 0  1 0 0  0.9\n";
  const fs::path png = out_ / "errors.png";
  const ProgramRun result = run({"eval", map.string(), "--truth", scene.string(), "--png", png.string(), "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  EXPECT_EQ(linesOf(result.out).at(0), "precision 1.0000 (5 of 5 occupied voxels on a surface)");
  EXPECT_NE(linesOf(result.out).back().find(" s -> " + png.string()), std::string::npos) << result.out;
  EXPECT_EQ(listDir(out_), Names{"errors.png"});
  const cv::Mat figure = readFigure(png);
  ASSERT_FALSE(figure.empty());
  // The five wall voxels, 0.1 m from the truth, on a scale from 0 to 2 T = 0.346 m (turbo).
  const cv::Vec3b wall = colourOnScale(cv::COLORMAP_TURBO, 0.1, 0.0, 2.0 * std::sqrt(3.0) * 0.1);
  EXPECT_GT(pixelsOf(figure, wall), 5 * 60 * 60);
  EXPECT_GT(pixelsOf(figure, kFreeBgr), 40 * 60 * 60) << "the water, known";
  EXPECT_EQ(pixelsOf(figure, kOccupiedBgr), 0);
  // Without --png nothing is written; a PNG in a missing folder is an error.
  EXPECT_EQ(run({"eval", map.string(), "--truth", scene.string()}).exit_code, 0);
  EXPECT_EQ(listDir(out_), Names{"errors.png"});
  expectError(run({"eval", map.string(), "--truth", scene.string(), "--png", (out_ / "no" / "e.png").string()}), 1);
}

TEST_F(cliEval, SensorPosesAndTheVerticalApertureLimitWhatCountsAsSeen) {
  const fs::path map = writeWallMap(root_ / "wall.bt");
  const fs::path scene = root_ / "wall.scene";
  std::ofstream(scene) << "plane 1.05 0 0  1 0 0  0.9\n";
  // A pose without an aperture: the position only, as --sensor.
  const ProgramRun pose = run({"eval", map.string(), "--truth", scene.string(), "--sensor-pose", "0,0,0,0,0,0"});
  ASSERT_EQ(pose.exit_code, 0) << pose.err;
  EXPECT_EQ(linesOf(pose.out)[1], "recall 0.5833 (7 of 12 visible surface voxels mapped)");
  // Upright with a 35° aperture: the wall's layer is seen.
  const ProgramRun level = run({"eval", map.string(), "--truth", scene.string(), "--sensor-pose", "0,0,0,0,0,0",
                                "--vertical-aperture", "35"});
  ASSERT_EQ(level.exit_code, 0) << level.err;
  EXPECT_EQ(linesOf(level.out)[1], "recall 0.5833 (7 of 12 visible surface voxels mapped)");
  // Tilted 30° down (pitch −30, as --mounting): the wall's layer, about 3° up, lies above its ±17.5°.
  const ProgramRun down = run({"eval", map.string(), "--truth", scene.string(), "--sensor-pose", "0,0,0,0,-30,0",
                               "--vertical-aperture", "35"});
  ASSERT_EQ(down.exit_code, 0) << down.err;
  EXPECT_EQ(linesOf(down.out)[1], "recall 0.0000 (0 of 0 visible surface voxels mapped)");
  // Two poses: the union.
  const ProgramRun both = run({"eval", map.string(), "--truth", scene.string(), "--sensor-pose", "0,0,0,0,-30,0",
                               "--sensor-pose", "0,0,0,0,0,0", "--vertical-aperture", "35"});
  ASSERT_EQ(both.exit_code, 0) << both.err;
  EXPECT_EQ(linesOf(both.out)[1], "recall 0.5833 (7 of 12 visible surface voxels mapped)");
}

TEST_F(cliEval, AcceptsTheThreeDimensionalBuiltInScene) {
  OcTree16 map(0.1);
  map.updateNode(map.coder().keyOfChecked({3.45, 0.05, 0.05}), 2.0F);  // on the quay's face
  map.updateNode(map.coder().keyOfChecked({2.45, 0.05, 0.05}), -2.0F);
  const fs::path path = root_ / "quay.bt";
  writeMapFile(map, path.string());
  const ProgramRun result = run({"eval", path.string(), "--truth", "quay3d"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const Names lines = linesOf(result.out);
  ASSERT_GE(lines.size(), 7U) << result.out;
  EXPECT_EQ(lines[0], "precision 1.0000 (1 of 1 occupied voxels on a surface)");
  EXPECT_EQ(lines[5], "surface_error_median_m 0.0500 p90_m 0.0500 (over 1 occupied voxels)");
  EXPECT_EQ(lines[6], "surface 2 box median_offset_m +0.0500 (1 voxels)");
}

TEST_F(cliEval, ScoresASimulatedTankAgainstTheBuiltInScene) {
  const fs::path map = root_ / "tank.ot";
  writeMapFile(mapSonarLog(simulateMsis(builtinScene("tank")).log).map(), map.string());
  const ProgramRun result = run({"eval", map.string(), "--truth", "tank", "--z-min", "0", "--z-max", "0.02"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const Names lines = linesOf(result.out);
  ASSERT_GE(lines.size(), 5U) << result.out;
  ASSERT_EQ(lines[0].rfind("precision ", 0), 0U) << lines[0];
  EXPECT_GT(std::atof(lines[0].c_str() + 10), 0.8);  // library test: 0.859
  ASSERT_EQ(lines[1].rfind("recall ", 0), 0U) << lines[1];
  EXPECT_GT(std::atof(lines[1].c_str() + 7), 0.88);  // 0.932
  EXPECT_EQ(lines[lines.size() - 2].rfind("region z [0.000, 0.020] m", 0), 0U) << lines[lines.size() - 2];
}

TEST_F(cliEval, BadArgumentsAndInputsFailWithOneLine) {
  const fs::path map = writeWallMap(root_ / "wall.bt");
  const fs::path scene = root_ / "bad.scene";
  std::ofstream(scene) << "plane 1 0 0  0 0 0  0.9\n";  // zero normal
  expectError(run({"eval", map.string()}), 2);                                            // no --truth
  expectError(run({"eval", map.string(), "--truth", "tank", "--tolerance", "0"}), 2);     // not > 0
  expectError(run({"eval", map.string(), "--truth", "tank", "--sensor", "1,2"}), 2);      // not a triple
  expectError(run({"eval", map.string(), "--truth", "tank", "--z-min", "1", "--z-max", "0"}), 2);
  expectError(run({"eval", map.string(), "--truth", "tank", "--sensor-pose", "0,0,0,0,0"}), 2);  // not six
  expectError(run({"eval", map.string(), "--truth", "tank", "--sensor-pose", "0,0,0,0,0,0", "--sensor", "0,0,0"}), 2);
  expectError(run({"eval", map.string(), "--truth", "tank", "--vertical-aperture", "35"}), 2);  // no pose
  expectError(
      run({"eval", map.string(), "--truth", "tank", "--sensor-pose", "0,0,0,0,0,0", "--vertical-aperture", "180"}), 2);
  expectError(
      run({"eval", map.string(), "--truth", "tank", "--sensor-pose", "0,0,0,0,0,0", "--vertical-aperture", "0"}), 2);
  expectError(run({"eval", (root_ / "missing.bt").string(), "--truth", "tank"}), 1);
  expectError(run({"eval", map.string(), "--truth", scene.string()}), 1);                 // invalid scene
  expectError(run({"eval", map.string(), "--truth", "lake"}), 1);                          // neither file nor name
  expectError(run({"eval", map.string(), "--truth", "tank", "--z-min", "3", "--z-max", "4"}), 1);  // nothing known
}

// A scoring file (what `demo` writes beside its 3D map) gives eval's options by their names, its
// files relative to its folder: the same scores as the options typed, the command line winning,
// and a file that cannot be read as one is a usage error.
TEST_F(cliEval, ScoringFileGivesTheOptionsItNames) {
  const fs::path folder = root_ / "mission";
  fs::create_directory(folder);
  const fs::path map = writeWallMap(folder / "wall.bt");
  std::ofstream(folder / "wall.scene") << "# the wall\nplane 1.05 0 0  1 0 0  0.9\n";
  std::ofstream(folder / "scoring.json") << R"({"truth": "wall.scene", "max-range": 0.8, "vertical-aperture": 35,
                                             "sensor-pose": [[0, 0, 0, 0, 0, 0], [0.1, 0, 0, 0, 0, 90]]})";
  const ProgramRun filed = run({"eval", map.string(), "--scoring", (folder / "scoring.json").string()});
  ASSERT_EQ(filed.exit_code, 0) << filed.err;
  const ProgramRun typed = run({"eval", map.string(), "--truth", (folder / "wall.scene").string(), "--max-range", "0.8",
                                "--vertical-aperture", "35", "--sensor-pose", "0,0,0,0,0,0", "--sensor-pose",
                                "0.1,0,0,0,0,90"});
  ASSERT_EQ(typed.exit_code, 0) << typed.err;
  Names filed_lines = linesOf(filed.out), typed_lines = linesOf(typed.out);
  ASSERT_GE(filed_lines.size(), 2U) << filed.out;
  filed_lines.pop_back();  // the summary line times the run
  typed_lines.pop_back();
  EXPECT_EQ(filed_lines, typed_lines);
  EXPECT_NE(filed.out.find("range 0.800 m"), std::string::npos) << filed.out;
  // The command line wins over the file.
  const ProgramRun nearer =
      run({"eval", map.string(), "--scoring", (folder / "scoring.json").string(), "--max-range", "0.5"});
  ASSERT_EQ(nearer.exit_code, 0) << nearer.err;
  EXPECT_NE(nearer.out.find("range 0.500 m"), std::string::npos) << nearer.out;
  // Unreadable, not an object, an unknown key, a value of the wrong kind, no truth at all.
  const auto scoring = [&](const std::string& text) {
    std::ofstream(folder / "bad.json") << text;
    return run({"eval", map.string(), "--scoring", (folder / "bad.json").string()});
  };
  expectError(run({"eval", map.string(), "--scoring", (folder / "missing.json").string()}), 2);
  expectError(scoring("[1, 2]"), 2);
  expectError(scoring(R"({"truth": "wall.scene", "range": 1})"), 2);
  expectError(scoring(R"({"truth": "wall.scene", "sensor-pose": [[0, 0, 0]]})"), 2);
  expectError(scoring(R"({"max-range": 1})"), 2);
}

/// The heard-surface lines of an eval run with --heard-by (after precision and recall), read back.
struct HeardLines {
  double recall = -1.0, f1 = -1.0, precision = -1.0, recall_again = -1.0;
  std::size_t found = 0, voxels = 0, surface_voxels = 0, beams = 0, without_nav = 0;
  std::string level;  ///< what the surface line says was heard
};

HeardLines heardLines(const Names& lines) {
  HeardLines heard;
  EXPECT_GE(lines.size(), 5U);
  if (lines.size() < 5) return heard;
  EXPECT_EQ(std::sscanf(lines[2].c_str(), "heard_recall %lf (%zu of %zu heard surface voxels mapped)", &heard.recall,
                        &heard.found, &heard.voxels),
            3)
      << lines[2];
  EXPECT_EQ(std::sscanf(lines[3].c_str(), "heard_f1 %lf (precision %lf, heard recall %lf)", &heard.f1, &heard.precision,
                        &heard.recall_again),
            3)
      << lines[3];
  const std::size_t colon = lines[4].find(": "), by = lines[4].find(" by the micron head, ");
  EXPECT_EQ(std::sscanf(lines[4].c_str(), "heard_surface %zu voxels:", &heard.surface_voxels), 1) << lines[4];
  EXPECT_NE(by, std::string::npos) << lines[4];
  if (colon == std::string::npos || by == std::string::npos) return heard;
  heard.level = lines[4].substr(colon + 2, by - colon - 2);
  EXPECT_EQ(std::sscanf(lines[4].c_str() + by, " by the micron head, %zu beams traced (%zu without navigation)",
                        &heard.beams, &heard.without_nav),
            2)
      << lines[4];
  return heard;
}

// A Micron moving through quay3d, mapped in 3D at a coarse 0.2 m (a few rays per beam: fast) and
// scored against what its beams heard: the lines beside today's, their numbers consistent, the
// heard surface the library's own from the same files, and the level deciding what counts.
TEST_F(cliEval, HeardByScoresAMapAgainstTheSurfaceItsBeamsHeard) {
  const fs::path sim = root_ / "sim";
  ASSERT_EQ(run({"simulate", "quay3d", "-o", sim.string(), "--turns", "2", "--speed", "0.1", "-q"}).exit_code, 0);
  const std::string beams = (sim / "beams.csv").string(), nav = (sim / "truth_nav.csv").string(),
                    scene = (sim / "scene.txt").string(), map = (root_ / "map.bt").string();
  ASSERT_EQ(run({"map", beams, "--nav", (sim / "nav.csv").string(), "--3d", "--resolution", "0.2", "-o", map, "-q"})
                .exit_code,
            0);
  const Names base{"eval", map, "--truth", scene, "-q"};
  const ProgramRun plain = run(base);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  Names with_heard = base;
  for (const std::string& word : Names{"--heard-by", beams, "--nav", nav}) with_heard.push_back(word);
  const ProgramRun result = run(with_heard);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  // Today's lines unchanged but for the summary's time, the three heard lines after the recall.
  Names lines = linesOf(result.out), today = linesOf(plain.out);
  ASSERT_EQ(lines.size(), today.size() + 3) << result.out;
  const HeardLines heard = heardLines(lines);
  lines.erase(lines.begin() + 2, lines.begin() + 5);
  lines.pop_back();
  today.pop_back();
  EXPECT_EQ(lines, today);

  EXPECT_EQ(heard.level, "echoes >= 0 dB over the floor");
  EXPECT_EQ(heard.beams, 400U);  // two turns of 200 beams
  EXPECT_EQ(heard.without_nav, 0U);
  EXPECT_EQ(heard.surface_voxels, heard.voxels);
  EXPECT_GT(heard.recall, 0.3);
  EXPECT_LT(heard.recall, 1.0);
  EXPECT_NEAR(heard.recall, static_cast<double>(heard.found) / static_cast<double>(heard.voxels), 1e-4);
  EXPECT_EQ(heard.recall_again, heard.recall);
  double precision = 0.0;
  ASSERT_EQ(std::sscanf(today[0].c_str(), "precision %lf", &precision), 1) << today[0];
  EXPECT_EQ(heard.precision, precision);
  EXPECT_NEAR(heard.f1, 2.0 * precision * heard.recall / (precision + heard.recall), 1e-4);

  // The library's heard surface of the same files, at the map's resolution: the same voxels.
  const SonarPreset micron = sonarPreset("micron");
  HeardSurfaceStats stats;
  heardSurfaceMap(readSonarLog(beams), readNavCsv(nav), defaultSonarToBody(), readScene(scene), micron.head,
                  micron.echo, HeardSurfaceOptions{0.2, 0.0}, &stats);
  EXPECT_EQ(heard.voxels, stats.voxels);

  // Any echo (the geometry) hears more than 0 dB, −6 dB in between.
  std::size_t previous = heard.voxels;
  for (const char* level : {"-6", "-inf", "any"}) {
    Names args = with_heard;
    for (const char* word : {"--heard-level", level}) args.emplace_back(word);
    const ProgramRun at_level = run(args);
    ASSERT_EQ(at_level.exit_code, 0) << at_level.err;
    const HeardLines more = heardLines(linesOf(at_level.out));
    EXPECT_GE(more.voxels, previous) << level;
    previous = more.voxels;
    EXPECT_EQ(more.level, std::string(level) == "-6" ? "echoes >= -6 dB over the floor" : "every surface a ray meets");
  }
  EXPECT_GT(previous, heard.voxels);

  // Navigation for the first half of the run only: the later beams are skipped and counted.
  std::ifstream full(nav);
  std::ofstream half(root_ / "half_nav.csv");
  const std::size_t fixes = readNavCsv(nav).size();
  std::string row;
  for (std::size_t i = 0; i <= fixes / 2 && std::getline(full, row); ++i) half << row << '\n';  // header + half
  half.close();
  Names args = base;
  for (const std::string& word : Names{"--heard-by", beams, "--nav", (root_ / "half_nav.csv").string()}) {
    args.push_back(word);
  }
  const ProgramRun partial = run(args);
  ASSERT_EQ(partial.exit_code, 0) << partial.err;
  const HeardLines part = heardLines(linesOf(partial.out));
  EXPECT_GT(part.without_nav, 150U);
  EXPECT_EQ(part.beams + part.without_nav, 400U);
}

// --heard-by without --nav: the log of a static sonar, at the map origin as `sonarmap map` places it.
TEST_F(cliEval, HeardByAStaticLogHearsFromTheMapOrigin) {
  const fs::path sim = root_ / "sim";
  ASSERT_EQ(run({"simulate", "tank", "-o", sim.string(), "--turns", "1", "--nav-rate", "0", "-q"}).exit_code, 0);
  const std::string beams = (sim / "beams.csv").string(), map = (root_ / "tank.bt").string();
  ASSERT_EQ(run({"map", beams, "--3d", "--resolution", "0.1", "-o", map, "-q"}).exit_code, 0);
  const ProgramRun result = run({"eval", map, "--truth", "tank", "--heard-by", beams, "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const HeardLines heard = heardLines(linesOf(result.out));
  EXPECT_EQ(heard.beams, 200U);
  EXPECT_EQ(heard.without_nav, 0U);
  EXPECT_GT(heard.recall, 0.5);  // the tank's walls, heard and mapped from the same place
  const SonarPreset micron = sonarPreset("micron");
  HeardSurfaceStats stats;
  heardSurfaceMap(readSonarLog(beams), NavTrack{}, Eigen::Isometry3d::Identity(), builtinScene("tank"), micron.head,
                  micron.echo, HeardSurfaceOptions{0.1, 0.0}, &stats);
  EXPECT_EQ(heard.voxels, stats.voxels);
}

TEST_F(cliEval, BadHeardSurfaceArgumentsAndInputsFailWithOneLine) {
  const fs::path sim = root_ / "sim";
  ASSERT_EQ(run({"simulate", "tank", "-o", sim.string(), "--turns", "1", "-q"}).exit_code, 0);
  const std::string beams = (sim / "beams.csv").string(), nav = (sim / "truth_nav.csv").string();
  const std::string map = (root_ / "tank.bt").string();
  ASSERT_EQ(run({"map", beams, "--resolution", "0.1", "-o", map, "-q"}).exit_code, 0);
  const Names base{"eval", map, "--truth", "tank", "-q"};
  const auto with = [&](const Names& more) {
    Names args = base;
    args.insert(args.end(), more.begin(), more.end());
    return run(args);
  };
  // Bad arguments: exit 2.
  for (const char* level : {"nan", "+inf", "inf", "3dB", ""}) {
    expectError(with({"--heard-by", beams, "--heard-level", level}), 2);
  }
  expectError(with({"--heard-by", beams, "--sonar", "sidescan"}), 2);              // no such preset
  expectError(with({"--heard-by", beams, "--mounting", "0,0,0,0,0,0"}), 2);      // a mounting without --nav
  expectError(with({"--heard-by", beams, "--nav", nav, "--mounting", "0,0,0,0,0"}), 2);  // five numbers
  expectError(with({"--nav", nav}), 2);                                             // no --heard-by
  expectError(with({"--sonar", "micron"}), 2);
  expectError(with({"--heard-level", "-6"}), 2);
  // Bad data: exit 1.
  expectError(with({"--heard-by", beams, "--nav", (root_ / "missing.csv").string()}), 1);
  expectError(with({"--heard-by", (root_ / "missing.csv").string()}), 1);
  const ProgramRun other_head = with({"--heard-by", beams, "--nav", nav, "--sonar", "seaking-30"});
  expectError(other_head, 1);  // 1.25 cm bins are not the SeaKing's
  EXPECT_NE(other_head.err.find("not recorded by this head"), std::string::npos) << other_head.err;
  expectError(with({"--heard-by", beams, "--nav", nav, "--heard-level", "200"}), 1);  // nothing that loud
  // The same options well formed work.
  EXPECT_EQ(with({"--heard-by", beams, "--nav", nav, "--mounting", "0,0,0,0,0,0", "--sonar", "micron"}).exit_code, 0);
}

}  // namespace
}  // namespace sonarmap::test
