// End-to-end tests of `sonarmap map --nav NAV.csv [--mounting ...]`: a simulated moving run (beam
// CSV and navigation CSV written by the library) maps to the very octree the library builds, beams
// outside the navigation are reported, and the CLI's error contract holds. No shared data needed.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "cli_fixture.hpp"
#include "figure_checks.hpp"
#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/formats/beam_csv.hpp"

namespace sonarmap::test {
namespace {

/// The figures of a --nav summary line.
struct NavSummary {
  std::size_t used = 0, skipped = 0, without_nav = 0, sweeps = 0;
};

NavSummary parseNavSummary(const ProgramRun& result) {
  NavSummary s;
  const Names lines = linesOf(result.out);
  EXPECT_EQ(lines.size(), 1U) << result.out;
  if (lines.empty()) return s;
  EXPECT_EQ(std::sscanf(lines[0].c_str(), "%zu beams used, %zu skipped, %zu without navigation, %zu sweeps", &s.used,
                        &s.skipped, &s.without_nav, &s.sweeps),
            4)
      << lines[0];
  return s;
}

class cliNav : public CliTest {
 protected:
  /// Two turns of the simulated tank from a vehicle moving north at 0.1 m/s: root/beams.csv and
  /// root/nav.csv (navigation from the first beam to the last).
  void SetUp() override {
    CliTest::SetUp();
    MsisSimulationOptions options;
    options.turns = 2;
    NavSample start;
    start.position_ned_m = Eigen::Vector3d(-0.8, -0.4, 0.0);
    options.trajectory = constantVelocityTrajectory(start, Eigen::Vector3d(0.1, 0.0, 0.0));
    run_ = simulateMsis(builtinScene("tank"), options);
    beams_ = root_ / "beams.csv";
    nav_ = root_ / "nav.csv";
    writeBeamCsv(beams_.string(), run_.log);
    writeNavCsv(nav_.string(), run_.nav);
  }

  /// The .bt the library writes for the beam CSV (as the CLI reads it) with `nav` and `sonar_to_body`,
  /// in the default map frame.
  std::string libraryMap(const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body) const {
    const fs::path bt = root_ / "library.bt";
    writeMapFileInFrame(mapSonarLog(readBeamCsv(beams_.string()), nav, sonar_to_body).map(), bt.string(),
                        kDefaultMapFrame);
    return readFile(bt);
  }

  MsisSimulation run_;
  fs::path beams_, nav_;
};

TEST_F(cliNav, MovingRunMapsToTheLibrarysOctreeAndReportsNoBeamWithoutNavigation) {
  const fs::path bt = out_ / "moving.bt";
  const ProgramRun result = run({"map", beams_.string(), "--nav", nav_.string(), "-o", bt.string(), "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  const NavSummary summary = parseNavSummary(result);
  EXPECT_EQ(summary.used + summary.skipped, 400U);
  EXPECT_EQ(summary.without_nav, 0U);
  EXPECT_EQ(summary.sweeps, 2U);
  EXPECT_EQ(readFile(bt), libraryMap(run_.nav, defaultSonarToBody()));
  // Without --nav the same log maps differently: the motion is ignored.
  const fs::path still = out_ / "still.bt";
  ASSERT_EQ(run({"map", beams_.string(), "-o", still.string(), "-q"}).exit_code, 0);
  EXPECT_NE(readFile(still), readFile(bt));
}

TEST_F(cliNav, PngDrawsTheSonarsTrack) {
  const fs::path moving = out_ / "moving.png", still = out_ / "still.png";
  ASSERT_EQ(run({"map", beams_.string(), "--nav", nav_.string(), "-o", (out_ / "m.bt").string(), "--png",
                 moving.string(), "-q"})
                .exit_code,
            0);
  ASSERT_EQ(run({"map", beams_.string(), "-o", (out_ / "s.bt").string(), "--png", still.string(), "-q"}).exit_code, 0);
  const cv::Mat with_track = readFigure(moving), dot = readFigure(still);
  ASSERT_FALSE(with_track.empty());
  ASSERT_FALSE(dot.empty());
  // 1.7 m north (map +x) from (−0.8, 0.4) m, 2 px wide, and a circle at its start; the static
  // sonar is a dot of radius 5 px. Both have the legend's 18 × 2 px line beside them.
  const int track = pixelsOf(with_track, kTrackBgr), sonar = pixelsOf(dot, kTrackBgr);
  EXPECT_GT(track, 600);
  EXPECT_GT(sonar, 60);
  EXPECT_LT(sonar, 200);
}

TEST_F(cliNav, BeamsOutsideTheNavigationAreCountedInTheSummary) {
  NavTrack part;  // fixes from 3 s to 10 s of the 17.2 s run
  for (const NavSample& fix : run_.nav) {
    if (fix.time_s >= 3.0 - 1e-9 && fix.time_s <= 10.0 + 1e-9) part.push_back(fix);
  }
  const fs::path part_csv = root_ / "part.csv";
  writeNavCsv(part_csv.string(), part);
  std::size_t outside = 0;
  for (const Beam& beam : run_.log.beams) outside += beam.time_s < part.front().time_s || beam.time_s > part.back().time_s;
  ASSERT_GT(outside, 100U);
  const fs::path bt = out_ / "part.bt";
  const ProgramRun result = run({"map", beams_.string(), "--nav", part_csv.string(), "-o", bt.string(), "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const NavSummary summary = parseNavSummary(result);
  EXPECT_EQ(summary.without_nav, outside);
  EXPECT_EQ(summary.used + summary.skipped + summary.without_nav, 400U);
  EXPECT_EQ(readFile(bt), libraryMap(part, defaultSonarToBody()));
}

TEST_F(cliNav, MountingIsMetresThenZyxEulerDegrees) {
  // Sonar 0.5 m forward of the body origin, upright (roll 0°) and turned 90° to starboard.
  const fs::path bt = out_ / "mounted.bt";
  const ProgramRun result =
      run({"map", beams_.string(), "--nav", nav_.string(), "--mounting", "0.5,0,0,0,0,90", "-o", bt.string(), "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  NavSample mounting;
  mounting.position_ned_m = Eigen::Vector3d(0.5, 0.0, 0.0);
  mounting.yaw_rad = 90.0 * std::numbers::pi / 180.0;
  EXPECT_EQ(readFile(bt), libraryMap(run_.nav, bodyToNed(mounting)));
  EXPECT_NE(readFile(bt), libraryMap(run_.nav, defaultSonarToBody()));
}

TEST_F(cliNav, ZerosMountAlignedAsTheDefaultDoes) {
  // A simulated run of the harbour heading east: typed "mounted straight" (all zeros), the map is
  // the default's, byte for byte, and it lies on the scene (not mirrored about the track).
  const fs::path dir = root_ / "east";
  ASSERT_EQ(run({"simulate", "harbour", "-o", dir.string(), "--turns", "2", "--speed", "0.3", "--heading", "90", "-q"})
                .exit_code,
            0);
  const std::string beams = (dir / "beams.csv").string(), nav = (dir / "nav.csv").string();
  const fs::path by_default = out_ / "default.bt", zeros = out_ / "zeros.bt";
  ASSERT_EQ(run({"map", beams, "--nav", nav, "-o", by_default.string(), "-q"}).exit_code, 0);
  const ProgramRun mapped = run({"map", beams, "--nav", nav, "--mounting", "0,0,0,0,0,0", "-o", zeros.string(), "-q"});
  ASSERT_EQ(mapped.exit_code, 0) << mapped.err;
  EXPECT_TRUE(readFile(zeros) == readFile(by_default)) << "--mounting 0,0,0,0,0,0 maps differently from the default";
  const ProgramRun scored = run({"eval", zeros.string(), "--truth", (dir / "scene.txt").string()});
  ASSERT_EQ(scored.exit_code, 0) << scored.err;
  const Names lines = linesOf(scored.out);
  ASSERT_GE(lines.size(), 2U) << scored.out;
  double precision = 0.0, recall = 0.0;
  ASSERT_EQ(std::sscanf(lines[0].c_str(), "precision %lf", &precision), 1) << lines[0];
  ASSERT_EQ(std::sscanf(lines[1].c_str(), "recall %lf", &recall), 1) << lines[1];
  EXPECT_GT(precision, 0.95);  // 0.998 (0.000 when zeros meant upside down)
  EXPECT_GT(recall, 0.6);      // 0.759 in two turns
}

TEST_F(cliNav, BadMountingIsAUsageErrorAndBadNavigationADataError) {
  const std::string bt = (out_ / "x.bt").string();
  const std::string beams = beams_.string(), nav = nav_.string();
  expectError(run({"map", beams, "--nav", nav, "--mounting", "1,2,3", "-o", bt}), 2);            // too few values
  expectError(run({"map", beams, "--nav", nav, "--mounting", "0,0,0,0,0,nan", "-o", bt}), 2);  // not finite
  expectError(run({"map", beams, "--mounting", "0,0,0,0,0,0", "-o", bt}), 2);                    // without --nav
  expectError(run({"map", beams, "--nav", (root_ / "missing.csv").string(), "-o", bt}), 1);
  const fs::path broken = root_ / "broken.csv";
  writeFile(broken, "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n0,0,0,0,0,0,0\n0,1,0,0,0,0,0\n");  // time repeats
  expectError(run({"map", beams, "--nav", broken.string(), "-o", bt}), 1);
  EXPECT_TRUE(fs::is_empty(out_));
}

TEST_F(cliNav, HelpDocumentsNavAndMounting) {
  const ProgramRun result = run({"map", "--help"});
  ASSERT_EQ(result.exit_code, 0);
  // The units in one line; the frames, default and the tilt's sign in docs/commands.md.
  for (const char* part : {"--nav", "--mounting", "X,Y,Z (m)", "ROLL,PITCH,YAW (deg)"}) {
    EXPECT_NE(result.out.find(part), std::string::npos) << "'" << part << "' missing from: " << result.out;
  }
}

}  // namespace
}  // namespace sonarmap::test
