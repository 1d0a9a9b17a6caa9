// The trajectory `map --slam` writes is one a vehicle can fly (no two rows imply more than
// --max-speed or --max-turn-rate), and a navigation in absolute coordinates (UTM) maps about a
// local origin (--origin, or its first fix) as the same navigation near zero does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>

#include "cli_fixture.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::test {
namespace {

using cliTrack = CliTest;

const fs::path kPoolBag = fs::path(SONARMAP_SHARED_DATA) / "micron_pool_ros1.bag";

/// `bt` (a map file's bytes) without its header's origin line, and that line ("" when none).
std::pair<std::string, std::string> splitOriginLine(std::string bt) {
  const std::string prefix = "# sonarmap map origin: ";
  const std::size_t at = bt.find(prefix);
  if (at == std::string::npos) return {bt, ""};
  const std::size_t end = bt.find('\n', at) + 1;
  std::string line = bt.substr(at, end - at);
  bt.erase(at, end - at);
  return {bt, line};
}

/// The fastest speed (m/s) and turn rate (degrees/s) two consecutive rows of `track` imply.
std::pair<double, double> fastestStep(const NavTrack& track) {
  double speed_mps = 0.0, turn_deg_s = 0.0;
  for (std::size_t i = 1; i < track.size(); ++i) {
    const double dt_s = track[i].time_s - track[i - 1].time_s;
    speed_mps = std::max(speed_mps, (track[i].position_ned_m - track[i - 1].position_ned_m).head<2>().norm() / dt_s);
    const double turn_rad = std::remainder(track[i].yaw_rad - track[i - 1].yaw_rad, 2.0 * std::numbers::pi);
    turn_deg_s = std::max(turn_deg_s, std::abs(turn_rad) * 180.0 / std::numbers::pi / dt_s);
  }
  return {speed_mps, turn_deg_s};
}

TEST_F(cliTrack, ThePoolBagsSlamTrackStaysWithinTheVehiclesLimits) {
  if (!fs::exists(kPoolBag)) GTEST_SKIP() << "no " << kPoolBag;
  const fs::path trajectory = out_ / "pool.csv";
  const ProgramRun map = run({"map", kPoolBag.string(), "--slam", "--max-speed", "1", "--max-turn-rate", "20",
                              "--trajectory", trajectory.string(), "-o", (out_ / "pool.bt").string(), "-q"});
  ASSERT_EQ(map.exit_code, 0) << map.err;
  const NavTrack track = readNavCsv(trajectory.string());
  ASSERT_GT(track.size(), 18U);
  // The vehicle does move: the scans are matched.
  EXPECT_GT((track.back().position_ned_m - track.front().position_ned_m).norm(), 0.05);
  const auto [speed_mps, turn_deg_s] = fastestStep(track);
  EXPECT_LE(speed_mps, 1.0);
  EXPECT_LE(turn_deg_s, 20.0);
}

TEST_F(cliTrack, LiveReplayInUtmMapsAsNearZero) {
  if (!fs::exists(kPoolBag)) GTEST_SKIP() << "no " << kPoolBag;
  // The pool bag's vehicle moving 1 cm/s north over its 155 s, near zero and in UTM.
  for (const auto& [name, north_m] : {std::pair{"zero.csv", 0.0}, std::pair{"utm.csv", 4'600'000.0}}) {
    NavTrack track;
    for (int k = 0; k <= 170; ++k) {
      NavSample fix;
      fix.time_s = 1405709972.0 + k;
      fix.position_ned_m = Eigen::Vector3d(north_m + 0.01 * k, north_m > 0.0 ? 500'000.0 : 0.0, 0.0);
      track.push_back(fix);
    }
    writeNavCsv((root_ / name).string(), track);
  }
  const ProgramRun near = run({"live", kPoolBag.string(), "--nav", (root_ / "zero.csv").string(), "--show", "sweep",
                               "-o", (out_ / "zero.bt").string(), "-q"});
  ASSERT_EQ(near.exit_code, 0) << near.err;
  const ProgramRun far = run({"live", kPoolBag.string(), "--nav", (root_ / "utm.csv").string(), "--show", "sweep",
                              "-o", (out_ / "utm.bt").string(), "-q"});
  ASSERT_EQ(far.exit_code, 0) << far.err;
  EXPECT_EQ(far.out.rfind("origin: 4600000, 500000, 0 m (N, E, D; the first fix", 0), 0U) << far.out;
  const auto [utm_map, utm_origin] = splitOriginLine(readFile(out_ / "utm.bt"));
  EXPECT_EQ(utm_origin.rfind("# sonarmap map origin: 4600000 500000 0 m", 0), 0U) << utm_origin;
  EXPECT_EQ(utm_map, readFile(out_ / "zero.bt"));  // near zero: no origin line
}

/// A simulated harbour loop in `dir` (beams.csv, nav.csv), and its navigation moved by
/// (north_m, east_m) as `name` beside it.
class cliOrigin : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    sim_ = root_ / "sim";
    const ProgramRun sim = run({"simulate", "harbour", "--mission", "harbour-loop", "-o", sim_.string(), "-q"});
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
  }
  fs::path moved(const std::string& name, double north_m, double east_m, double north_ramp_m = 0.0) const {
    NavTrack track = readNavCsv((sim_ / "nav.csv").string());
    for (std::size_t i = 0; i < track.size(); ++i) {
      track[i].position_ned_m.x() += north_m + north_ramp_m * static_cast<double>(i) / static_cast<double>(track.size() - 1);
      track[i].position_ned_m.y() += east_m;
    }
    const fs::path path = root_ / name;
    writeNavCsv(path.string(), track);
    return path;
  }
  ProgramRun map(const fs::path& nav, const std::string& bt, Names extra = {}, const std::string& resolution_m = "0.1") const {
    Names args = {"map", (sim_ / "beams.csv").string(), "--nav", nav.string(), "--resolution", resolution_m,
                  "-o", (out_ / bt).string(), "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  }
  fs::path sim_;
};

TEST_F(cliOrigin, AUtmNavigationMapsAsTheSameNavigationNearZero) {
  const ProgramRun near = map(sim_ / "nav.csv", "near.bt");
  ASSERT_EQ(near.exit_code, 0) << near.err;
  EXPECT_EQ(near.out.find("origin:"), std::string::npos) << near.out;  // near zero: no origin moved anything

  const fs::path utm = moved("utm.csv", 4'600'000.0, 500'000.0);
  const ProgramRun given = map(utm, "given.bt", {"--origin", "4600000,500000"});
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_NE(given.out.find("origin: 4600000, 500000, 0 m (N, E, D; given)"), std::string::npos) << given.out;
  // The same voxels; the header names the origin, so the map can be placed back in UTM.
  const auto [given_map, given_origin] = splitOriginLine(readFile(out_ / "given.bt"));
  EXPECT_EQ(given_map, readFile(out_ / "near.bt"));
  EXPECT_EQ(given_origin.rfind("# sonarmap map origin: 4600000 500000 0 m", 0), 0U) << given_origin;

  // By default: the first fix, stated; the same map as the navigation near zero about its first fix.
  const NavSample first = readNavCsv((sim_ / "nav.csv").string()).front();
  const ProgramRun automatic = map(utm, "auto.bt", {"--trajectory", (out_ / "auto.csv").string()});
  ASSERT_EQ(automatic.exit_code, 0) << automatic.err;
  EXPECT_NE(automatic.out.find("origin: 46000"), std::string::npos) << automatic.out;
  EXPECT_NE(automatic.out.find("the first fix"), std::string::npos) << automatic.out;
  const ProgramRun about_first =
      map(sim_ / "nav.csv", "first.bt",
          {"--origin", std::to_string(first.position_ned_m.x()) + "," + std::to_string(first.position_ned_m.y())});
  ASSERT_EQ(about_first.exit_code, 0) << about_first.err;
  EXPECT_EQ(splitOriginLine(readFile(out_ / "auto.bt")).first, splitOriginLine(readFile(out_ / "first.bt")).first);
  // `view` draws the trajectory written in UTM on the map, moved to the origin the map's header names:
  // its first point, the first fix, is the map's zero.
  const fs::path page = out_ / "auto.html";
  const ProgramRun view = run({"view", (out_ / "auto.bt").string(), "-o", page.string(), "--trajectory",
                               (out_ / "auto.csv").string()});
  ASSERT_EQ(view.exit_code, 0) << view.err;
  const std::string html = readFile(page);
  const std::string key = "\"trajectory_m\":[";
  const std::size_t at = html.find(key);
  ASSERT_NE(at, std::string::npos);
  double east_m = 1e9, north_m = 1e9;
  ASSERT_EQ(std::sscanf(html.c_str() + at + key.size(), "%lf,%lf", &east_m, &north_m), 2);
  EXPECT_NEAR(east_m, 0.0, 1e-6);
  EXPECT_NEAR(north_m, 0.0, 1e-6);
  // The trajectory is written in the navigation's own coordinates.
  const NavTrack written = readNavCsv((out_ / "auto.csv").string());
  EXPECT_NEAR(written.front().position_ned_m.x(), 4'600'000.0 + first.position_ned_m.x(), 1e-6);
  EXPECT_NEAR(written.front().position_ned_m.y(), 500'000.0 + first.position_ned_m.y(), 1e-6);
}

TEST_F(cliOrigin, ANavigationTheMapCannotHoldNamesTheFixAndTheRemedy) {
  // 3 km north at 5 cm voxels (±1,638 m): about the first fix it does not fit, about its middle it does.
  const fs::path long_run = moved("long.csv", 4'600'000.0, 500'000.0, 3'000.0);
  ProgramRun refused = map(long_run, "long.bt", {}, "0.05");
  expectError(refused, 1);
  EXPECT_NE(refused.err.find("the navigation fix at "), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("the map holds ±1638.35 m"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--origin 4601"), std::string::npos) << refused.err;
  // Given there, it maps.
  const std::size_t at = refused.err.find("--origin ") + 9;
  const std::string middle = refused.err.substr(at, refused.err.find(' ', at) - at);
  EXPECT_EQ(map(long_run, "middle.bt", {"--origin", middle}, "0.05").exit_code, 0);

  // 10 km: no origin fits it at 5 cm; the error says what resolution does.
  refused = map(moved("longer.csv", 4'600'000.0, 500'000.0, 10'000.0), "longer.bt", {}, "0.05");
  expectError(refused, 1);
  EXPECT_NE(refused.err.find("the navigation fix at "), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("a resolution of at least 0.153 m"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("(no --origin fits it)"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("(--resolution)"), std::string::npos) << refused.err;
}

TEST_F(cliTrack, LocalizeInUtmFindsTheSameTrajectoryAsNearZero) {
  const fs::path survey = fs::path(SONARMAP_SHARED_DATA) / "stpere_marina";
  if (!fs::exists(survey / "dr_nav.csv")) GTEST_SKIP() << "no " << survey;
  NavTrack utm = readNavCsv((survey / "dr_nav.csv").string());
  for (NavSample& fix : utm) fix.position_ned_m += Eigen::Vector3d(4'600'000.0, 500'000.0, 0.0);
  writeNavCsv((root_ / "utm.csv").string(), utm);
  const std::string scans = (survey / "scans.csv.gz").string();
  const ProgramRun near = run({"localize", scans, "--nav", (survey / "dr_nav.csv").string(), "--trajectory",
                               (out_ / "near.csv").string()});
  ASSERT_EQ(near.exit_code, 0) << near.err;
  const ProgramRun far = run({"localize", scans, "--nav", (root_ / "utm.csv").string(), "--trajectory",
                              (out_ / "utm.csv").string()});
  ASSERT_EQ(far.exit_code, 0) << far.err;
  EXPECT_EQ(far.out.rfind("origin: 4600000, 500000, 0 m (N, E, D; the first fix", 0), 0U) << far.out;
  const NavTrack a = readNavCsv((out_ / "near.csv").string()), b = readNavCsv((out_ / "utm.csv").string());
  ASSERT_EQ(a.size(), b.size());
  double worst_m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst_m = std::max(worst_m, (b[i].position_ned_m - Eigen::Vector3d(4'600'000.0, 500'000.0, 0.0) - a[i].position_ned_m).norm());
  }
  EXPECT_LT(worst_m, 1e-6);  // the same localization, written in the navigation's own coordinates
}

}  // namespace
}  // namespace sonarmap::test
