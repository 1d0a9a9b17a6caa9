// End-to-end tests of `sonarmap info LOG [--format F] [--nav NAV.csv] [--json]`: a simulated log
// (beam CSV and navigation CSV written by the library) is described as the library summarizes it,
// the JSON parses with the same facts, errors follow the CLI's contract, and the shared real logs
// (skipped without ../shared/data) give the range scales and beams their readers give.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"
#include "formats/vehicle_log_fixture.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/ros_bag_writer.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sonar/log_summary.hpp"
#include "sonarmap/sonar/range_scales.hpp"

namespace sonarmap::test {
namespace {

/// A screen: the text output of one log, whatever it holds.
constexpr std::size_t kMaxTextLines = 30;

/// printf into a string.
std::string formatted(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

class cliInfo : public CliTest {
 protected:
  /// Two turns of the simulated Micron in the tank from a vehicle moving north: root/beams.csv and
  /// root/nav.csv (navigation from the first beam to the last).
  void SetUp() override {
    CliTest::SetUp();
    MsisSimulationOptions options;
    options.turns = 2;
    options.trajectory = constantVelocityTrajectory(NavSample{}, Eigen::Vector3d(0.1, 0.0, 0.0));
    run_ = simulateMsis(builtinScene("tank"), options);
    beams_ = root_ / "beams.csv";
    nav_ = root_ / "nav.csv";
    writeBeamCsv(beams_.string(), run_.log);
    writeNavCsv(nav_.string(), run_.nav);
  }

  /// The JSON object `info --json ARGS...` prints, after checking the run succeeded quietly.
  nlohmann::json infoJson(Names args) const {
    args.insert(args.begin(), "info");
    args.push_back("--json");
    const ProgramRun result = run(args);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.err, "");
    return nlohmann::json::parse(result.out);  // throws (failing the test) when it is not JSON
  }

  MsisSimulation run_;
  fs::path beams_, nav_;
};

TEST_F(cliInfo, TextGivesTheBeamsTheSweepsAndTheRangeScaleOnOneScreen) {
  const LogSummary expected = summarizeLog(readBeamCsv(beams_.string()));
  ASSERT_EQ(expected.settings.size(), 1U);
  const ProgramRun result = run({"info", beams_.string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  const Names lines = linesOf(result.out);
  EXPECT_LE(lines.size(), kMaxTextLines) << result.out;
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0].rfind("beams.csv: csv log", 0), 0U) << lines[0];
  for (const std::string& part :
       {std::to_string(expected.beams) + " over " + formatted("%.1f s", expected.duration_s),
        std::to_string(expected.full_turns) + " full turns of " + std::to_string(expected.beams_per_turn) + " beams",
        formatted("%.2f m", expected.settings[0].reach_m), formatted("%.3f mm", expected.settings[0].setting.bin_length_m * 1000),
        std::string("1 head setting, 1 range scale"), std::string("skipped     none"),
        std::string("navigation  none given")}) {
    EXPECT_NE(result.out.find(part), std::string::npos) << "'" << part << "' missing from:\n" << result.out;
  }
  EXPECT_EQ(expected.beams, 400U);  // the Micron's 200 beams per turn
  EXPECT_EQ(expected.full_turns, 2U);
}

TEST_F(cliInfo, JsonHoldsTheSameFacts) {
  const LogSummary expected = summarizeLog(readBeamCsv(beams_.string()));
  const nlohmann::json info = infoJson({beams_.string()});
  EXPECT_EQ(info["file"], beams_.string());
  EXPECT_EQ(info["format"], "csv");
  EXPECT_DOUBLE_EQ(info["nominal_beam"]["width_deg"].get<double>(), 3.0);
  EXPECT_EQ(info["beams"], 400);
  EXPECT_EQ(info["skipped_beams"], 0);
  EXPECT_TRUE(info["skip_reasons"].empty());
  EXPECT_NEAR(info["time"]["duration_s"].get<double>(), expected.duration_s, 1e-9);
  ASSERT_TRUE(info["beam_rate_hz"].is_number());
  EXPECT_NEAR(info["beam_rate_hz"].get<double>(), *expected.beam_rate_hz, 1e-9);
  EXPECT_TRUE(info["bearings"]["full_circle"].get<bool>());
  EXPECT_NEAR(info["bearings"]["step_deg"].get<double>(), 1.8, 1e-6);
  const nlohmann::json& sweeps = info["sweeps"];
  EXPECT_EQ(sweeps["count"], 2);
  EXPECT_EQ(sweeps["full_turns"], 2);
  EXPECT_EQ(sweeps["sector_passes"], 0);
  EXPECT_EQ(sweeps["beams_per_turn"], 200);
  ASSERT_EQ(sweeps["list"].size(), 2U);
  EXPECT_EQ(sweeps["list"][0]["kind"], "full turn");
  ASSERT_EQ(info["head_settings"].size(), 1U);
  const nlohmann::json& setting = info["head_settings"][0];
  EXPECT_DOUBLE_EQ(setting["bin_length_m"].get<double>(), expected.settings[0].setting.bin_length_m);
  EXPECT_TRUE(setting["gain_setting"].is_null());
  EXPECT_EQ(setting["bins"], expected.settings[0].bins);
  EXPECT_EQ(setting["beams"], 400);
  EXPECT_EQ(setting["first_beam"], 0);
  EXPECT_NEAR(setting["reach_m"].get<double>(), expected.settings[0].reach_m, 1e-12);
  ASSERT_EQ(info["range_scales"].size(), 1U);
  EXPECT_EQ(info["auto_resolution_scale"]["beams"], 400);
  EXPECT_TRUE(info["navigation"].is_null());
}

TEST_F(cliInfo, NavigationIsDescribedWithItsCoverage) {
  const nlohmann::json info = infoJson({beams_.string(), "--nav", nav_.string()});
  const nlohmann::json& nav = info["navigation"];
  ASSERT_TRUE(nav.is_object()) << info.dump();
  EXPECT_EQ(nav["fixes"], run_.nav.size());
  EXPECT_EQ(nav["beams_outside"], 0);
  EXPECT_TRUE(nav["covers_beams"].get<bool>());
  const double duration_s = run_.nav.back().time_s - run_.nav.front().time_s;
  EXPECT_NEAR(nav["distance_m"].get<double>(), 0.1 * duration_s, 1e-6);  // 0.1 m/s straight north

  // A track that ends half-way leaves the later beams outside it.
  NavTrack half(run_.nav.begin(), run_.nav.begin() + static_cast<std::ptrdiff_t>(run_.nav.size() / 2));
  const fs::path short_nav = root_ / "half.csv";
  writeNavCsv(short_nav.string(), half);
  const ProgramRun result = run({"info", beams_.string(), "--nav", short_nav.string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::size_t outside = summarizeLog(readBeamCsv(beams_.string()), half).nav->beams_outside;
  EXPECT_GT(outside, 100U);
  EXPECT_NE(result.out.find(std::to_string(outside) + " of 400 beams outside it"), std::string::npos) << result.out;
}

// A ROS bag with its own navigation: info lists its topics and says which it reads; map places the
// beams with the bag's navigation as it does with the same track given as a CSV, and --nav none
// maps the head static.
TEST_F(cliInfo, ARosBagsTopicsAreListedAndItsNavigationIsUsed) {
  SonarLog log = run_.log;
  NavTrack nav = run_.nav;
  for (Beam& beam : log.beams) beam.time_s += 1.4e9;  // ROS stamps: seconds since 1970
  for (NavSample& fix : nav) fix.time_s += 1.4e9;
  const fs::path bag = root_ / "run.bag";
  writeRosBag(bag.string(), log, nav);
  const nlohmann::json info = infoJson({bag.string()});
  ASSERT_EQ(info["topics"].size(), 2U) << info.dump();
  EXPECT_EQ(info["topics"][0]["topic"], "/sonar/scan_line");
  EXPECT_EQ(info["topics"][0]["messages"], 400);
  EXPECT_NE(info["topics"][0]["use"].get<std::string>().find("sonar"), std::string::npos);
  EXPECT_EQ(info["topics"][1]["type"], "nav_msgs/Odometry");
  EXPECT_NE(info["topics"][1]["use"].get<std::string>().find("navigation"), std::string::npos);
  EXPECT_EQ(info["navigation"]["fixes"], nav.size());
  EXPECT_TRUE(info["navigation"]["covers_beams"].get<bool>());

  const ProgramRun from_bag = run({"map", bag.string(), "-o", (root_ / "bag.bt").string(), "-q"});
  ASSERT_EQ(from_bag.exit_code, 0) << from_bag.err;
  EXPECT_NE(from_bag.out.find("navigation /odometry (nav_msgs/Odometry, ENU (REP 103), turned into NED) of run.bag: " +
                              std::to_string(nav.size()) + " fixes"),
            std::string::npos) << from_bag.out;
  EXPECT_NE(from_bag.out.find("0 without navigation"), std::string::npos) << from_bag.out;
  const ProgramRun from_csv = run({"map", beams_.string(), "--nav", nav_.string(), "-o", (root_ / "csv.bt").string(), "-q"});
  ASSERT_EQ(from_csv.exit_code, 0) << from_csv.err;
  auto obstacles = [](const std::string& out) { return std::stoul(out.substr(out.find(" sweeps, ") + 9)); };
  EXPECT_NEAR(static_cast<double>(obstacles(from_bag.out)), static_cast<double>(obstacles(from_csv.out)),
              0.02 * static_cast<double>(obstacles(from_csv.out)));

  const ProgramRun still = run({"map", bag.string(), "--nav", "none", "-o", (root_ / "still.bt").string(), "-q"});
  ASSERT_EQ(still.exit_code, 0) << still.err;
  EXPECT_EQ(still.out.find("navigation"), std::string::npos) << still.out;
  EXPECT_EQ(still.out.find("without navigation"), std::string::npos) << still.out;
  // A topic named that is not in the bag is a one-line error.
  const ProgramRun wrong = run({"map", bag.string(), "--nav-topic", "/odom", "-o", (root_ / "wrong.bt").string()});
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find("no topic /odom"), std::string::npos) << wrong.err;
  EXPECT_FALSE(fs::exists(root_ / "wrong.bt"));
}

// A bag whose /tf_static mounts the sonar: map places the beams with that mounting as `map
// --mounting` does with the same numbers; --mounting given overrides it.
TEST_F(cliInfo, ABagsTfStaticMountsTheSonar) {
  SonarLog log = run_.log;
  NavTrack nav = run_.nav;
  for (Beam& beam : log.beams) beam.time_s += 1.4e9;
  for (NavSample& fix : nav) fix.time_s += 1.4e9;
  const std::vector<double> numbers{0.3, 0.1, 0.2, 0.0, 0.0, 30.0};  // X,Y,Z m, roll, pitch, yaw deg
  const fs::path bag = root_ / "mounted.bag";
  writeRosBag(bag.string(), log, nav, {.sonar_to_body = sonarToBodyOfMounting(numbers)});
  const ProgramRun from_bag = run({"map", bag.string(), "-o", (root_ / "bag.bt").string(), "-q"});
  ASSERT_EQ(from_bag.exit_code, 0) << from_bag.err;
  EXPECT_NE(from_bag.out.find("mounting from /tf_static: base_link -> sonar (sonar at 0.300, 0.100, 0.200 m"),
            std::string::npos) << from_bag.out;
  const ProgramRun from_csv = run({"map", beams_.string(), "--nav", nav_.string(), "--mounting", "0.3,0.1,0.2,0,0,30",
                                   "-o", (root_ / "csv.bt").string(), "-q"});
  ASSERT_EQ(from_csv.exit_code, 0) << from_csv.err;
  auto obstacles = [](const std::string& out) { return std::stoul(out.substr(out.find(" sweeps, ") + 9)); };
  EXPECT_NEAR(static_cast<double>(obstacles(from_bag.out)), static_cast<double>(obstacles(from_csv.out)),
              0.02 * static_cast<double>(obstacles(from_csv.out)));
  const ProgramRun told = run({"map", bag.string(), "--mounting", "0,0,0,0,0,0", "-o", (root_ / "told.bt").string(), "-q"});
  ASSERT_EQ(told.exit_code, 0) << told.err;
  EXPECT_EQ(told.out.find("mounting from /tf_static"), std::string::npos) << told.out;
}

// A BlueROV2's telemetry log beside a sonar log without a clock: its UTC clock cannot meet the
// log's, so info prints both spans and map refuses with both; --nav-time-offset joins them and the
// map matches the one made with the same track as a CSV.
TEST_F(cliInfo, ABlueRov2TelemetryLogIsJoinedByItsTimeOffset) {
  const std::uint64_t boot_utc_us = 1723630500000000ULL;  // 2024-08-14 10:15:00 UTC; the log's 0 is boot + 5 s
  std::string tlog;
  for (const NavSample& fix : run_.nav) {
    const auto boot_ms = static_cast<std::uint32_t>(std::llround(fix.time_s * 1000.0) + 5000);
    const std::uint64_t received = boot_utc_us + boot_ms * 1000ULL;
    tlog += tlogRecord(received, attitudeFrame(boot_ms, static_cast<float>(fix.roll_rad), static_cast<float>(fix.pitch_rad),
                                               static_cast<float>(fix.yaw_rad)));
    tlog += tlogRecord(received, localPositionNedFrame(boot_ms, static_cast<float>(fix.position_ned_m.x()),
                                                       static_cast<float>(fix.position_ned_m.y()),
                                                       static_cast<float>(fix.position_ned_m.z())));
  }
  const fs::path nav = root_ / "flight.tlog";
  writeFile(nav, tlog);
  const nlohmann::json apart = infoJson({beams_.string(), "--nav", nav.string()});
  EXPECT_FALSE(apart["navigation"]["covers_beams"].get<bool>()) << apart.dump();
  EXPECT_EQ(apart["navigation"]["clock_utc_s"], 0.0);
  EXPECT_TRUE(apart["time"]["clock_utc_s"].is_null());
  const ProgramRun text = run({"info", beams_.string(), "--nav", nav.string()});
  EXPECT_NE(text.out.find("navigation  2024-08-14 10:15:05.000 UTC .. "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("the sonar log does not say when it started"), std::string::npos) << text.out;

  const ProgramRun refused = run({"map", beams_.string(), "--nav", nav.string(), "-o", (root_ / "apart.bt").string()});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("no beam within the navigation's time span"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--nav-time-offset"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(root_ / "apart.bt"));

  const ProgramRun joined = run({"map", beams_.string(), "--nav", nav.string(), "--nav-time-offset=-1723630505",
                                 "-o", (root_ / "tlog.bt").string(), "-q"});
  ASSERT_EQ(joined.exit_code, 0) << joined.err;
  EXPECT_NE(joined.out.find("navigation MAVLink telemetry flight.tlog (attitude ATTITUDE, position LOCAL_POSITION_NED): " +
                            std::to_string(run_.nav.size()) + " fixes"),
            std::string::npos) << joined.out;
  EXPECT_NE(joined.out.find("0 without navigation"), std::string::npos) << joined.out;
  const ProgramRun from_csv = run({"map", beams_.string(), "--nav", nav_.string(), "-o", (root_ / "csv.bt").string(), "-q"});
  ASSERT_EQ(from_csv.exit_code, 0) << from_csv.err;
  auto obstacles = [](const std::string& out) { return std::stoul(out.substr(out.find(" sweeps, ") + 9)); };
  EXPECT_NEAR(static_cast<double>(obstacles(joined.out)), static_cast<double>(obstacles(from_csv.out)),
              0.02 * static_cast<double>(obstacles(from_csv.out)));
}

TEST_F(cliInfo, FormatNamesTheReaderOfAnyFileName) {
  const fs::path renamed = root_ / "capture.raw";
  fs::copy_file(beams_, renamed);
  EXPECT_EQ(infoJson({renamed.string(), "--format", "csv"})["beams"], 400);
}

TEST_F(cliInfo, ErrorsAreOneLine) {
  expectError(run({"info", (root_ / "missing.mat").string()}), 1);         // unreadable log
  expectError(run({"info", (root_ / "log.unknown").string()}), 1);         // unknown extension
  writeFile(root_ / "bad.csv", "not,a,beam,csv\n");
  expectError(run({"info", (root_ / "bad.csv").string()}), 1);             // malformed log
  expectError(run({"info", beams_.string(), "--nav", (root_ / "none.csv").string()}), 1);
  expectError(run({"info", beams_.string(), "--format", "nonsense"}), 2);  // bad usage
  expectError(run({"info"}), 2);
  expectError(run({"info", beams_.string(), "--no-such-flag"}), 2);
}

// The shared real logs (../shared/data/README.md): the range scales and beams their readers give.
struct RealLog {
  const char* name;
  std::size_t range_scales;  ///< 0: not asserted beyond the library's count
};

class cliInfoReal : public CliTest, public ::testing::WithParamInterface<RealLog> {};

TEST_P(cliInfoReal, RangeScalesAndBeamsAreTheReadersOnOneScreen) {
  const fs::path path = fs::path(SONARMAP_SHARED_DATA) / GetParam().name;
  if (!fs::exists(path)) {
    GTEST_SKIP() << "shared data absent: " << path;
  }
  const SonarLog log = readSonarLog(path.string());
  const std::vector<RangeScale> scales = rangeScales(log);
  if (GetParam().range_scales > 0) {
    EXPECT_EQ(scales.size(), GetParam().range_scales);
  }

  const ProgramRun json_run = run({"info", path.string(), "--json"});
  ASSERT_EQ(json_run.exit_code, 0) << json_run.err;
  const nlohmann::json info = nlohmann::json::parse(json_run.out);
  EXPECT_EQ(info["beams"], log.beams.size());
  EXPECT_EQ(info["skipped_beams"], log.skipped_beams);
  ASSERT_EQ(info["range_scales"].size(), scales.size());
  for (std::size_t i = 0; i < scales.size(); ++i) {
    EXPECT_DOUBLE_EQ(info["range_scales"][i]["bin_length_m"].get<double>(), scales[i].bin_length_m);
    EXPECT_EQ(info["range_scales"][i]["beams"], scales[i].beams);
  }
  std::size_t setting_beams = 0;
  for (const nlohmann::json& setting : info["head_settings"]) {
    setting_beams += setting["beams"].get<std::size_t>();
    // a Ping360 records each ping's pulse (its transmit duration); Tritech logs do not
    const bool ping360 = log.beams.front().pulse_length_m.has_value();
    EXPECT_EQ(setting["pulse_length_m"].is_number(), ping360) << setting;
    if (ping360) {
      EXPECT_GT(setting["pulse_length_m"].get<double>(), 0.0);
    }
  }
  EXPECT_EQ(setting_beams, log.beams.size());
  EXPECT_EQ(info["auto_resolution_scale"]["bin_length_m"], mostUsedRangeScale(scales)->bin_length_m);

  const ProgramRun text_run = run({"info", path.string()});
  ASSERT_EQ(text_run.exit_code, 0) << text_run.err;
  EXPECT_LE(linesOf(text_run.out).size(), kMaxTextLines) << text_run.out;
  EXPECT_NE(text_run.out.find("beams       " + std::to_string(log.beams.size()) + " over"), std::string::npos)
      << text_run.out;
  const std::string scales_text = std::to_string(scales.size()) + " range scale" + (scales.size() == 1 ? "" : "s");
  EXPECT_NE(text_run.out.find(scales_text), std::string::npos) << text_run.out;
}

INSTANTIATE_TEST_SUITE_P(SharedData, cliInfoReal,
                         ::testing::Values(RealLog{"ping360_harbour_range_changes.bin", 7}, RealLog{"ping360_basin.bin", 3},
                                           RealLog{"cras_micron_tank_static.mat", 1},
                                           RealLog{"seanet_sector_target.V4LOG", 1}),
                         [](const ::testing::TestParamInfo<RealLog>& info) {
                           std::string name = info.param.name;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace sonarmap::test
