// End-to-end tests of `sonarmap simulate --mission ... --dvl-scale-error ... --heading-bias ...`
// (the believed nav.csv beside the true truth_nav.csv), of `sonarmap eval-trajectory` and of
// `sonarmap localize` on point scans.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cli_fixture.hpp"
#include "formats/vehicle_log_fixture.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::test {
namespace {

using cliTrajectory = CliTest;

/// The `key value` lines of eval-trajectory's output as a map.
std::map<std::string, std::string> metricsOf(const std::string& out) {
  std::map<std::string, std::string> metrics;
  for (const std::string& line : linesOf(out)) {
    const std::size_t space = line.find(' ');
    metrics[line.substr(0, space)] = space == std::string::npos ? "" : line.substr(space + 1);
  }
  return metrics;
}

TEST_F(cliTrajectory, MissionWithDeadReckoningErrorsAndItsEvaluation) {
  const fs::path dir = out_ / "loop";
  const ProgramRun sim = run({"simulate", "harbour", "--mission", "harbour-loop", "--dvl-scale-error", "0.02",
                              "--heading-bias", "1", "-o", dir.string(), "-q"});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const Names lines = linesOf(sim.out);
  ASSERT_EQ(lines.size(), 4U) << sim.out;
  // 34 m at 0.25 m/s and three quarter turns at 0.5 rad/s: 145.4 s, 17 turns of 8.6 s.
  EXPECT_EQ(lines[0].rfind("micron: 3400 beams in 17 turns, 1463 nav fixes", 0), 0U) << lines[0];
  EXPECT_EQ(lines[1], "mission harbour-loop: 1 lap(s), 34.0 m in 145.4 s");
  EXPECT_EQ(lines[2].rfind("nav.csv: dead reckoning, ", 0), 0U) << lines[2];
  // The map command: the believed navigation and the mission's mounting (upright and aligned).
  EXPECT_EQ(lines[3], "map it:  sonarmap map " + (dir / "beams.csv").string() + " --nav " + (dir / "nav.csv").string() +
                          " --mounting 0,0,0,0,0,0 --beam-width 3 --vertical-aperture 35 -o " + (dir / "map.bt").string());
  EXPECT_EQ(listDir(dir), (Names{"beams.csv", "nav.csv", "scene.txt", "truth_nav.csv"}));
  const std::string nav = readFile(dir / "nav.csv"), truth = readFile(dir / "truth_nav.csv");
  EXPECT_NE(nav, truth);
  EXPECT_EQ(linesOf(nav).size(), linesOf(truth).size());
  // The first fix: at the truth's place (its heading biased by 1 degree).
  const std::string first = linesOf(nav)[1], first_truth = linesOf(truth)[1];
  EXPECT_EQ(first.substr(0, first.rfind(',')), first_truth.substr(0, first_truth.rfind(',')));
  EXPECT_NE(first, first_truth);

  // The beams are those of the same run without the errors.
  const fs::path plain = out_ / "plain";
  ASSERT_EQ(run({"simulate", "harbour", "--mission", "harbour-loop", "-o", plain.string(), "-q"}).exit_code, 0);
  EXPECT_EQ(readFile(plain / "beams.csv"), readFile(dir / "beams.csv"));
  EXPECT_EQ(readFile(plain / "truth_nav.csv"), truth);
  EXPECT_EQ(readFile(plain / "nav.csv"), truth);

  const ProgramRun drift = run({"eval-trajectory", (dir / "nav.csv").string(), "--truth", (dir / "truth_nav.csv").string()});
  ASSERT_EQ(drift.exit_code, 0) << drift.err;
  EXPECT_EQ(drift.err, "");
  std::map<std::string, std::string> m = metricsOf(drift.out);
  for (const char* key : {"poses", "distance_m", "ate_rmse_m", "ate_max_m", "ate_start_rmse_m", "rpe_segments", "rpe_rmse_m",
                          "rpe_yaw_rmse_deg", "final_drift_m", "final_drift_pct"}) {
    EXPECT_EQ(m.count(key), 1U) << key << " in " << drift.out;
  }
  EXPECT_EQ(m["poses"], "1463");
  EXPECT_NEAR(std::atof(m["distance_m"].c_str()), 34.0, 0.01);
  EXPECT_GT(std::atof(m["ate_rmse_m"].c_str()), 0.05);  // 2 % of a 16 m side, not aligned away
  EXPECT_NEAR(std::atof(m["rpe_rmse_m"].c_str()), 0.2, 0.05);  // 2 % of 10 m
  EXPECT_LT(std::atof(m["final_drift_pct"].c_str()), 0.5);  // constant errors: the loop closes on itself

  const ProgramRun same = run({"eval-trajectory", (dir / "truth_nav.csv").string(), "--truth",
                               (dir / "truth_nav.csv").string(), "--se3", "--segment", "5"});
  ASSERT_EQ(same.exit_code, 0) << same.err;
  m = metricsOf(same.out);
  EXPECT_EQ(m["ate_rmse_m"], "0.0000");
  EXPECT_EQ(m["ate_start_rmse_m"], "0.0000");
  EXPECT_EQ(m["final_drift_m"], "0.0000");
}

// A vehicle without a DVL (--no-position): the believed track is the dead reckoning's heading,
// attitude and depth at north and east 0, the truth and the beams are the run's, and `map --slam`
// takes it as heading only. Without navigation (--nav-rate 0) there is nothing to strip: refused.
TEST_F(cliTrajectory, NoPositionKeepsTheHeadingAtNorthAndEastZero) {
  const fs::path dir = out_ / "compass", full = out_ / "full";
  const std::vector<std::string> common{"simulate", "harbour", "--speed", "0.2", "--heading", "30", "--turns", "3",
                                        "--heading-bias", "1", "-q"};
  std::vector<std::string> args = common;
  args.insert(args.end(), {"--no-position", "-o", dir.string()});
  ASSERT_EQ(run(args).exit_code, 0);
  args = common;
  args.insert(args.end(), {"-o", full.string()});
  ASSERT_EQ(run(args).exit_code, 0);
  EXPECT_EQ(readFile(dir / "beams.csv"), readFile(full / "beams.csv"));
  EXPECT_EQ(readFile(dir / "truth_nav.csv"), readFile(full / "truth_nav.csv"));
  const NavTrack compass = readNavCsv((dir / "nav.csv").string()), believed = readNavCsv((full / "nav.csv").string());
  ASSERT_EQ(compass.size(), believed.size());
  ASSERT_GT(compass.size(), 100U);
  double moved_m = 0.0;
  for (std::size_t i = 0; i < compass.size(); ++i) {
    EXPECT_EQ(compass[i].position_ned_m.head<2>(), Eigen::Vector2d::Zero()) << i;
    EXPECT_EQ(compass[i].position_ned_m.z(), believed[i].position_ned_m.z()) << i;
    EXPECT_EQ(compass[i].yaw_rad, believed[i].yaw_rad) << i;
    moved_m = std::max(moved_m, believed[i].position_ned_m.head<2>().norm());
  }
  EXPECT_GT(moved_m, 2.0);
  const ProgramRun slam = run({"map", (dir / "beams.csv").string(), "--nav", (dir / "nav.csv").string(), "--slam", "-o",
                               (dir / "map.bt").string()});
  ASSERT_EQ(slam.exit_code, 0) << slam.err;
  EXPECT_NE(slam.out.find("--nav gives the heading only"), std::string::npos) << slam.out;
  const ProgramRun none = run({"simulate", "harbour", "--no-position", "--nav-rate", "0", "-o", (out_ / "none").string(), "-q"});
  EXPECT_NE(none.exit_code, 0);
  EXPECT_EQ(linesOf(none.err).size(), 1U) << none.err;
  EXPECT_NE(none.err.find("--no-position shapes the navigation"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(out_ / "none" / "beams.csv"));
}

// A head on a tripod scanning a 90° sector back and forth (each pass a scan), no navigation: the
// passes see the same quay, so nothing proves a motion and the track stays at its start.
TEST_F(cliTrajectory, ASectorScanningStillHeadStaysStill) {
  const fs::path dir = out_ / "sector";
  ASSERT_EQ(run({"simulate", "harbour", "--sonar", "ping360-5m", "--sector", "90", "--turns", "16", "-o", dir.string(), "-q"})
                .exit_code,
            0);
  const ProgramRun slam = run({"map", (dir / "beams.csv").string(), "--slam", "--trajectory", (dir / "t.csv").string(),
                               "-o", (dir / "map.bt").string()});
  ASSERT_EQ(slam.exit_code, 0) << slam.err;
  EXPECT_NE(slam.out.find("slam: 16 scans"), std::string::npos) << slam.out;
  EXPECT_NE(slam.out.find("15 matched to the scans before them"), std::string::npos) << slam.out;
  const NavTrack track = readNavCsv((dir / "t.csv").string());
  ASSERT_GE(track.size(), 16U);
  for (const NavSample& fix : track) {
    EXPECT_LT(fix.position_ned_m.head<2>().norm(), 0.05) << fix.time_s;
    EXPECT_LT(std::abs(fix.yaw_rad), 0.01) << fix.time_s;
  }
}

TEST_F(cliTrajectory, EvalTrajectoryReadsTumToo) {
  writeFile(root_ / "truth.csv", "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n0,0,0,0,0,0,0\n1,1,0,0,0,0,0\n"
                                 "2,2,0,0,0,0,0\n3,3,0,0,0,0,0\n");
  writeFile(root_ / "est.tum", "# time x y z qx qy qz qw\n0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n"
                               "3 3.3 0 0 0 0 0 1\n");
  const ProgramRun result = run({"eval-trajectory", (root_ / "est.tum").string(), "--truth",
                                 (root_ / "truth.csv").string(), "--segment", "1"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::map<std::string, std::string> m = metricsOf(result.out);
  EXPECT_EQ(m["poses"], "4");
  EXPECT_EQ(m["final_drift_m"], "0.3000");
  EXPECT_EQ(m["final_drift_pct"], "10.0000");
}

TEST_F(cliTrajectory, ErrorsExitNonZeroWithOneLine) {
  writeFile(root_ / "truth.csv", "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n0,0,0,0,0,0,0\n1,1,0,0,0,0,0\n"
                                 "2,2,0,0,0,0,0\n");
  writeFile(root_ / "bad.tum", "0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0\n");
  const std::string truth = (root_ / "truth.csv").string();
  expectError(run({"eval-trajectory", (root_ / "bad.tum").string(), "--truth", truth}), 1);
  expectError(run({"eval-trajectory", (root_ / "missing.csv").string(), "--truth", truth}), 1);
  expectError(run({"eval-trajectory", truth, "--truth", truth, "--segment", "0"}), 2);
  expectError(run({"eval-trajectory", truth}), 2);  // no --truth
  writeFile(root_ / "late.csv", "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n10,0,0,0,0,0,0\n11,1,0,0,0,0,0\n"
                                "12,2,0,0,0,0,0\n");
  expectError(run({"eval-trajectory", (root_ / "late.csv").string(), "--truth", truth}), 1);  // no common time
  const std::string dir = (out_ / "x").string();
  expectError(run({"simulate", "hull", "--mission", "harbour-loop", "-o", dir}), 2);  // the mission's scene is harbour
  expectError(run({"simulate", "harbour", "--mission", "lake-loop", "-o", dir}), 2);
  expectError(run({"simulate", "harbour", "--laps", "2", "-o", dir}), 2);  // --laps without --mission
  expectError(run({"simulate", "harbour", "--dvl-noise", "-1", "-o", dir}), 2);
  expectError(run({"simulate", "harbour", "--dvl-scale-error", "-1", "-o", dir}), 2);
  EXPECT_EQ(listDir(out_), Names{});
}

TEST_F(cliTrajectory, HelpNamesTheUnits) {
  const ProgramRun help = run({"simulate", "--help"});
  ASSERT_EQ(help.exit_code, 0);
  for (const char* text : {"--mission", "harbour-loop", "hull-loop", "--laps", "--dvl-noise", "m/s",
                           "--dvl-scale-error", "--heading-bias", "degrees", "--gyro-walk", "deg/sqrt(s)"}) {
    EXPECT_NE(help.out.find(text), std::string::npos) << text;
  }
  const ProgramRun eval_help = run({"eval-trajectory", "--help"});
  ASSERT_EQ(eval_help.exit_code, 0);
  for (const char* text : {"--truth", "--se3", "--segment", "TUM"}) {
    EXPECT_NE(eval_help.out.find(text), std::string::npos) << text;
  }
}

// `map --slam` on a drifting mission: the summary says what the localization did, the trajectory
// is written (TUM here) and beats the dead reckoning it started from; nothing is written when the
// options are wrong.
TEST_F(cliTrajectory, MapWithSlamCorrectsTheDeadReckoning) {
  const fs::path dir = out_ / "loop";
  ASSERT_EQ(run({"simulate", "harbour", "--mission", "harbour-loop", "--dvl-scale-error", "0.03", "--heading-bias", "2",
                 "--gyro-walk", "0.02", "-o", dir.string(), "-q"})
                .exit_code,
            0);
  const fs::path tum = out_ / "slam.tum";
  const ProgramRun mapped = run({"map", (dir / "beams.csv").string(), "--nav", (dir / "nav.csv").string(), "--slam",
                                 "-o", (out_ / "slam.bt").string(), "--trajectory", tum.string(), "-q"});
  ASSERT_EQ(mapped.exit_code, 0) << mapped.err;
  const Names lines = linesOf(mapped.out);
  ASSERT_EQ(lines.size(), 2U) << mapped.out;
  EXPECT_EQ(lines[1].rfind("slam: 17 scans", 0), 0U) << lines[1];
  EXPECT_NE(lines[1].find("loop closures accepted"), std::string::npos) << lines[1];
  EXPECT_EQ(readFile(tum).rfind("# ", 0), 0U);  // TUM's comment header
  const auto ate = [&](const fs::path& estimate) {
    const ProgramRun eval = run({"eval-trajectory", estimate.string(), "--truth", (dir / "truth_nav.csv").string()});
    EXPECT_EQ(eval.exit_code, 0) << eval.err;
    return std::atof(metricsOf(eval.out)["ate_rmse_m"].c_str());
  };
  const double dead_reckoning_m = ate(dir / "nav.csv"), slam_m = ate(tum);
  EXPECT_GT(dead_reckoning_m, 0.1);
  EXPECT_LT(slam_m, dead_reckoning_m / 2.0);

  // A trajectory is asked of a static log: one line, nothing written.
  const ProgramRun refused = run({"map", (dir / "beams.csv").string(), "-o", (out_ / "static.bt").string(),
                                  "--trajectory", (out_ / "static.csv").string()});
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_EQ(linesOf(refused.err).size(), 1U) << refused.err;
  EXPECT_FALSE(fs::exists(out_ / "static.bt"));
  EXPECT_FALSE(fs::exists(out_ / "static.csv"));
}

// The true track given as the navigation: stated as such (--nav-class absolute) --slam leaves it
// within millimetres; under the default class (a DVL with an AHRS, 3 % of the distance) the scans
// move it by centimetres. Bad values are refused in one line, nothing written.
TEST_F(cliTrajectory, MapWithSlamLeavesGoodNavigationStatedAsSuch) {
  const fs::path dir = out_ / "loop";
  ASSERT_EQ(run({"simulate", "harbour", "--mission", "harbour-loop", "-o", dir.string(), "-q"}).exit_code, 0);
  const std::string beams = (dir / "beams.csv").string(), truth = (dir / "truth_nav.csv").string();
  const auto ateWith = [&](const std::string& nav_class) {
    const fs::path trajectory = out_ / (nav_class + ".csv");
    const ProgramRun mapped = run({"map", beams, "--nav", truth, "--slam", "--nav-class", nav_class, "-o",
                                   (out_ / (nav_class + ".bt")).string(), "--trajectory", trajectory.string(), "-q"});
    EXPECT_EQ(mapped.exit_code, 0) << mapped.err;
    const ProgramRun eval = run({"eval-trajectory", trajectory.string(), "--truth", truth});
    EXPECT_EQ(eval.exit_code, 0) << eval.err;
    return std::atof(metricsOf(eval.out)["ate_rmse_m"].c_str());
  };
  // Measured: 0.0022 m (absolute), 0.0052 m (dvl-ins), 0.0249 m (dvl-ahrs).
  const double absolute_m = ateWith("absolute"), ins_m = ateWith("dvl-ins"), ahrs_m = ateWith("dvl-ahrs");
  EXPECT_LT(absolute_m, 0.005);
  EXPECT_LT(ins_m, 0.01);
  EXPECT_GT(ahrs_m, 2.0 * ins_m);

  const Names written = listDir(out_);
  const std::string bt = (out_ / "bad.bt").string();
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"--slam", "--nav-class", "submarine"}, {"--slam", "--nav-scale-sigma", "-1"},
        {"--slam", "--nav-gyro-walk", "nan"}, {"--nav-class", "dvl-ins"}}) {
    std::vector<std::string> arguments{"map", beams, "--nav", truth, "-o", bt};
    arguments.insert(arguments.end(), bad.begin(), bad.end());
    const ProgramRun refused = run(arguments);
    EXPECT_EQ(refused.exit_code, 2) << bad.back();
    EXPECT_EQ(linesOf(refused.err).size(), 1U) << refused.err;
  }
  EXPECT_EQ(listDir(out_), written);
}

// A BlueROV2 without a DVL: its telemetry log has ATTITUDE messages and no position, so north and
// east stay 0. map --slam takes the position from the scans by itself and says so; with the
// navigation stated as a DVL's with an AHRS, the vehicle is believed still.
TEST_F(cliTrajectory, MapWithSlamTakesThePositionOfAHeadingOnlyFlightLogFromTheScans) {
  const fs::path dir = out_ / "hull";
  ASSERT_EQ(run({"simulate", "hull", "--mission", "hull-loop", "--sonar", "seaking-30", "-o", dir.string(), "-q"}).exit_code, 0);
  const std::uint64_t boot_utc_us = 1723630500000000ULL;  // the log's 0 is boot + 5 s
  std::string tlog;
  for (const NavSample& fix : readNavCsv((dir / "truth_nav.csv").string())) {
    const auto boot_ms = static_cast<std::uint32_t>(std::llround(fix.time_s * 1000.0) + 5000);
    tlog += tlogRecord(boot_utc_us + boot_ms * 1000ULL,
                       attitudeFrame(boot_ms, static_cast<float>(fix.roll_rad), static_cast<float>(fix.pitch_rad),
                                     static_cast<float>(fix.yaw_rad)));
  }
  writeFile(out_ / "flight.tlog", tlog);
  const auto mapWith = [&](const std::string& name, const std::vector<std::string>& more) {
    std::vector<std::string> arguments{"map", (dir / "beams.csv").string(), "--nav", (out_ / "flight.tlog").string(),
                                       "--nav-time-offset=-1723630505", "--slam", "-o", (out_ / (name + ".bt")).string(),
                                       "--trajectory", (out_ / (name + ".csv")).string()};
    arguments.insert(arguments.end(), more.begin(), more.end());
    const ProgramRun mapped = run(arguments);
    EXPECT_EQ(mapped.exit_code, 0) << mapped.err;
    const ProgramRun eval = run({"eval-trajectory", (out_ / (name + ".csv")).string(), "--truth", (dir / "truth_nav.csv").string()});
    EXPECT_EQ(eval.exit_code, 0) << eval.err;
    return std::make_pair(mapped.out, std::atof(metricsOf(eval.out)["ate_rmse_m"].c_str()));
  };
  const auto [found_out, found_m] = mapWith("found", {});
  EXPECT_NE(found_out.find("no position or depth"), std::string::npos) << found_out;
  EXPECT_NE(found_out.find("--nav gives the heading only"), std::string::npos) << found_out;
  const auto [believed_out, believed_m] = mapWith("believed", {"--nav-class", "dvl-ahrs"});
  EXPECT_EQ(believed_out.find("heading only"), std::string::npos) << believed_out;
  // Measured: 27.2 m believed still, 5.3 m from the scans.
  EXPECT_GT(believed_m, 20.0);
  EXPECT_LT(found_m, 0.3 * believed_m);
}

// Point scans of a 6 × 4 m rectangle of walls seen from a still vehicle, six scans, each echo listed
// as two bins (the second 5 cm behind, left out): localized with and without navigation, the
// trajectory written; broken input refused in one line, nothing written.
TEST_F(cliTrajectory, LocalizeWritesTheTrajectoryOfPointScans) {
  const fs::path scans = out_ / "scans.csv", nav = out_ / "nav.csv";
  {
    std::ofstream csv(scans);
    csv << "scan,time_s,x_m,y_m\n";
    for (int scan = 0; scan < 6; ++scan) {
      for (int k = 0; k < 180; ++k) {
        const double a = k * 2.0 * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
        const double r = std::min(std::abs(c) > 1e-9 ? (c > 0 ? 4.0 : 2.0) / std::abs(c) : 1e9,
                                  std::abs(s) > 1e-9 ? (s > 0 ? 1.5 : 2.5) / std::abs(s) : 1e9);
        csv << scan << ',' << 10.0 * scan + 0.05 * k << ',' << r * c << ',' << r * s << '\n';
        csv << scan << ',' << 10.0 * scan + 0.05 * k << ',' << (r + 0.05) * c << ',' << (r + 0.05) * s << '\n';
      }
    }
    std::ofstream track(nav);
    track << "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n";
    for (int k = 0; k <= 70; ++k) track << k << ",0,0,1,0,0,0\n";
  }
  const ProgramRun alone = run({"localize", scans.string(), "--trajectory", (out_ / "alone.csv").string()});
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  EXPECT_EQ(alone.out.rfind("slam: 6 scans (6 with features; 1080 points behind their echo's leading edge left out)", 0), 0U)
      << alone.out;
  EXPECT_NE(alone.out.find("no --nav"), std::string::npos) << alone.out;
  const ProgramRun with_nav = run({"localize", scans.string(), "--nav", nav.string(), "--trajectory",
                                   (out_ / "corrected.tum").string(), "-q"});
  ASSERT_EQ(with_nav.exit_code, 0) << with_nav.err;
  EXPECT_EQ(with_nav.out, "");
  std::size_t poses = 0;
  for (const std::string& line : linesOf(readFile(out_ / "corrected.tum"))) poses += line.rfind('#', 0) == 0 ? 0 : 1;
  EXPECT_EQ(poses, 71U);  // every fix of the navigation, corrected
  const ProgramRun scored = run({"eval-trajectory", (out_ / "corrected.tum").string(), "--truth", nav.string()});
  ASSERT_EQ(scored.exit_code, 0) << scored.err;
  EXPECT_LT(std::atof(metricsOf(scored.out)["ate_start_rmse_m"].c_str()), 0.03);  // the still vehicle stays put

  {
    std::ofstream broken(out_ / "broken.csv");
    broken << "scan,time_s,x_m,y_m\n1,0,1,1\n0,1,1,1\n";
  }
  const ProgramRun refused = run({"localize", (out_ / "broken.csv").string(), "--trajectory", (out_ / "no.csv").string()});
  expectError(refused, 1);
  EXPECT_NE(refused.err.find("line 3: scan 0 after scan 1"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(out_ / "no.csv"));
  const ProgramRun usage = run({"localize", scans.string(), "--trajectory", (out_ / "no.csv").string(), "--range-sigma", "0"});
  expectError(usage, 2);
  EXPECT_NE(usage.err.find("--range-sigma"), std::string::npos) << usage.err;
  const ProgramRun unknown = run({"localize", scans.string(), "--nav", nav.string(), "--trajectory",
                                  (out_ / "no.csv").string(), "--nav-class", "submarine"});
  expectError(unknown, 2);
  EXPECT_NE(unknown.err.find("dvl-ahrs, dvl-ins, absolute, ahrs"), std::string::npos) << unknown.err;
  EXPECT_FALSE(fs::exists(out_ / "no.csv"));
  EXPECT_FALSE(fs::exists(out_ / "no.csv"));
}

// The vehicle's limits without navigation (--max-speed): the same rectangle from a vehicle moving
// 0.4 m forward every 10 s (0.04 m/s). Within the default limit the scans give the motion; under
// a limit of 0.02 m/s the matches that need more are refused and counted in the summary, and the
// track never moves faster than the limit.
TEST_F(cliTrajectory, LocalizeRefusesMatchesFasterThanTheMaxSpeed) {
  const fs::path scans = out_ / "moving.csv";
  {
    std::ofstream csv(scans);
    csv << "scan,time_s,x_m,y_m\n";
    for (int scan = 0; scan < 6; ++scan) {
      const double forward_m = 0.4 * scan;
      for (int k = 0; k < 180; ++k) {
        const double a = k * 2.0 * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
        const double r = std::min(std::abs(c) > 1e-9 ? (c > 0 ? 4.0 - forward_m : 2.0 + forward_m) / std::abs(c) : 1e9,
                                  std::abs(s) > 1e-9 ? (s > 0 ? 1.5 : 2.5) / std::abs(s) : 1e9);
        csv << scan << ',' << 10.0 * scan + 0.05 * k << ',' << r * c << ',' << r * s << '\n';
      }
    }
  }
  // The trajectory's rows as (time_s, north_m, east_m).
  const auto rowsOf = [](const fs::path& path) {
    std::vector<Eigen::Vector3d> rows;
    for (const std::string& line : linesOf(readFile(path))) {
      if (line.rfind("time_s", 0) == 0) continue;
      double t = 0.0, x = 0.0, y = 0.0;
      if (std::sscanf(line.c_str(), "%lf,%lf,%lf", &t, &x, &y) == 3) rows.emplace_back(t, x, y);
    }
    return rows;
  };
  const ProgramRun found = run({"localize", scans.string(), "--trajectory", (out_ / "found.csv").string()});
  ASSERT_EQ(found.exit_code, 0) << found.err;
  EXPECT_EQ(found.out.find("refused as faster"), std::string::npos) << found.out;
  ASSERT_FALSE(rowsOf(out_ / "found.csv").empty());
  EXPECT_NEAR(rowsOf(out_ / "found.csv").back().y(), 2.0, 0.05);
  const ProgramRun held = run({"localize", scans.string(), "--trajectory", (out_ / "held.csv").string(), "--max-speed", "0.02"});
  ASSERT_EQ(held.exit_code, 0) << held.err;
  EXPECT_NE(held.out.find("refused as faster than --max-speed"), std::string::npos) << held.out;
  const std::vector<Eigen::Vector3d> rows = rowsOf(out_ / "held.csv");
  ASSERT_EQ(rows.size(), 18U);  // three rows per scan: its start, reference time and end
  for (std::size_t i = 4; i < rows.size(); i += 3) {  // from one scan's reference time to the next's
    EXPECT_LE((rows[i].tail<2>() - rows[i - 3].tail<2>()).norm(), 0.02 * (rows[i].x() - rows[i - 3].x()) + 1e-6) << i;
  }
  EXPECT_LT(rows.back().y(), 0.5);
  const ProgramRun zero = run({"localize", scans.string(), "--trajectory", (out_ / "no.csv").string(), "--max-turn-rate", "0"});
  expectError(zero, 2);
  EXPECT_NE(zero.err.find("--max-turn-rate expects DEGREES/s > 0"), std::string::npos) << zero.err;
  const ProgramRun without_slam = run({"map", scans.string(), "-o", (out_ / "no.bt").string(), "--max-speed", "1"});
  expectError(without_slam, 2);
  EXPECT_NE(without_slam.err.find("give --slam"), std::string::npos) << without_slam.err;
  EXPECT_FALSE(fs::exists(out_ / "no.csv"));
}

}  // namespace
}  // namespace sonarmap::test
