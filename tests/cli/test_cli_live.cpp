/// End-to-end tests of `sonarmap live`: a simulated tank run encoded byte by byte as a raw SeaNet
/// capture and as a Ping360 stream (wire_fixture.hpp), with line noise and a final frame cut short,
/// is replayed over a pseudo-terminal (a serial device), loopback UDP and standard input, and the
/// shared logs' bytes; the final map equals `sonarmap map` of the same bytes byte for byte, with
/// each beam shown as it arrives (the default) or not (--show sweep). Navigation on a second stream
/// places the beams. SIGTERM mid-stream ends the run with exit 0 and a readable map; bad usage is
/// one error line.

#include "live_fixture.hpp"

namespace sonarmap::test {
namespace {

TEST_F(CliLive, StandardInputGivesTheBatchMapByteForByte) {
  const std::string batch = batchMap();
  int pipe_fds[2];
  ASSERT_EQ(::pipe2(pipe_fds, O_CLOEXEC), 0);  // the child inherits only its stdin
  Child child(liveArgs("-"), root_, pipe_fds[0]);
  ::close(pipe_fds[0]);
  writeAll(pipe_fds[1], tankCapture(), 1000);
  ::close(pipe_fds[1]);
  const ProgramRun run = child.wait();
  expectFinished(run);
  EXPECT_TRUE(readFile(out_ / "live.bt") == batch) << "live map differs from `sonarmap map`";
  EXPECT_NE(run.err.find("sonarmap: live: reading standard input"), std::string::npos) << run.err;
  // The final status line: from a read to the map as shown and to the committed map.
  EXPECT_TRUE(std::regex_search(run.err, std::regex("latency median [0-9.]+ ms shown, [0-9.]+ ms committed, 99th "
                                                    "percentile [0-9.]+ ms shown, [0-9.]+ ms committed")))
      << run.err;
}

// --slam without navigation on a static head: the scans say the vehicle stayed put, the map is
// written, and so is the trajectory.
TEST_F(CliLive, SlamOnAStaticHeadKeepsItPutAndWritesTheTrajectory) {
  int pipe_fds[2];
  ASSERT_EQ(::pipe2(pipe_fds, O_CLOEXEC), 0);
  Names args = liveArgs("-");
  args.insert(args.end(), {"--slam", "--trajectory", (out_ / "trajectory.csv").string()});
  Child child(args, root_, pipe_fds[0]);
  ::close(pipe_fds[0]);
  writeAll(pipe_fds[1], tankCapture(), 1000);
  ::close(pipe_fds[1]);
  const ProgramRun run = child.wait();
  EXPECT_EQ(run.exit_code, 0) << run.err;
  ASSERT_EQ(linesOf(run.out).size(), 2u) << run.out;  // the map's summary, then the localization's
  EXPECT_EQ(linesOf(run.out)[1].rfind("slam: 4 scans", 0), 0u) << run.out;
  EXPECT_GT(fs::file_size(out_ / "live.bt"), 1000u);
  const NavTrack trajectory = readNavCsv((out_ / "trajectory.csv").string());
  ASSERT_FALSE(trajectory.empty());
  for (const NavSample& fix : trajectory) EXPECT_LT(fix.position_ned_m.norm(), 0.05);
}

TEST_F(CliLive, APseudoTerminalIsReadAsASerialDevice) {
  const std::string batch = batchMap();
  const ProgramRun run = replayOverPty(tankCapture(), "seanet");
  expectFinished(run);
  EXPECT_TRUE(readFile(out_ / "live.bt") == batch) << "live map differs from `sonarmap map`";
  EXPECT_NE(run.err.find("at 115200 baud"), std::string::npos) << run.err;
}

TEST_F(CliLive, Ping360OverAPseudoTerminalGivesTheBatchMapShowingSweepsOnly) {
  const std::string batch = batchMap(tankPing360Capture(), "ping360");
  const ProgramRun run = replayOverPty(tankPing360Capture(), "ping360", "sweep");
  expectFinished(run);
  EXPECT_TRUE(readFile(out_ / "live.bt") == batch) << "live map differs from `sonarmap map`";
}

// The shared SeaNet log's packets as its head sent them (`sonarmap convert` to a .seanet capture),
// over UDP: the map of the log itself.
TEST_F(CliLive, SharedSeaNetLogPacketsGiveTheLogsMap) {
  const fs::path log = fs::path(SONARMAP_SHARED_DATA) / "seanet_sector_target.V4LOG";
  if (!fs::exists(log)) GTEST_SKIP() << "shared data absent: " << log;
  ASSERT_EQ(run({"convert", log.string(), "-o", (root_ / "sector.seanet").string()}).exit_code, 0);
  ASSERT_EQ(run({"map", log.string(), "-q", "-o", (root_ / "log.bt").string()}).exit_code, 0);
  const ProgramRun live = replayOverUdp(readFile(root_ / "sector.seanet"), "seanet");
  expectFinished(live);
  EXPECT_TRUE(readFile(out_ / "live.bt") == readFile(root_ / "log.bt")) << "live map differs from the log's";
}

// A shared Ping Viewer log whose range changed seven times, as the bytes its head sent read from a
// capture file, and the shared ROS bag replayed: `live` ends on the map `sonarmap map` makes of the
// same input (at a given resolution: live cannot know which range scale most beams will use).
TEST_F(CliLive, SharedLogsEndOnTheBatchMapByteForByte) {
  const fs::path harbour = fs::path(SONARMAP_SHARED_DATA) / "ping360_harbour_range_changes.bin";
  const fs::path pool = fs::path(SONARMAP_SHARED_DATA) / "micron_pool_ros1.bag";
  if (!fs::exists(harbour) || !fs::exists(pool)) GTEST_SKIP() << "shared data absent: " << harbour << ", " << pool;
  const std::string capture = (root_ / "harbour.bin").string();
  ASSERT_EQ(run({"convert", harbour.string(), "-o", capture}).exit_code, 0);
  ASSERT_EQ(run({"map", capture, "--format", "ping360", "--resolution", "0.1", "-q", "-o", (root_ / "harbour.bt").string()})
                .exit_code,
            0);
  const ProgramRun live = run({"live", capture, "--format", "ping360", "--resolution", "0.1", "-q", "-o",
                               (out_ / "harbour.bt").string()});
  ASSERT_EQ(live.exit_code, 0) << live.err;
  EXPECT_TRUE(readFile(out_ / "harbour.bt") == readFile(root_ / "harbour.bt")) << "live map differs from `sonarmap map`";
  ASSERT_EQ(run({"map", pool.string(), "-q", "-o", (root_ / "pool.bt").string()}).exit_code, 0);
  ASSERT_EQ(run({"live", pool.string(), "-q", "-o", (out_ / "pool.bt").string()}).exit_code, 0);
  EXPECT_TRUE(readFile(out_ / "pool.bt") == readFile(root_ / "pool.bt")) << "replayed map differs from `sonarmap map`";
}

/// "N beams used, M skipped" of a summary line: {N, M}; {-1, -1} when there is none.
std::pair<long, long> beamCounts(const std::string& summary) {
  std::smatch counts;
  if (!std::regex_search(summary, counts, std::regex("([0-9]+) beams used, ([0-9]+) skipped"))) return {-1, -1};
  return {std::stol(counts[1].str()), std::stol(counts[2].str())};
}

// The shared Ping Viewer log given as it is (not converted to a raw capture): `live` reads it as
// `map` does (its records' time stamps and lengths are not the sonar's bytes), with --format
// ping360 or by its name, uses and skips the same beams, says why it skipped what it skipped, and
// ends on `map`'s map at a given resolution.
TEST_F(CliLive, APingViewerLogIsReadAsMapReadsIt) {
  const fs::path basin = fs::path(SONARMAP_SHARED_DATA) / "ping360_basin.bin";
  if (!fs::exists(basin)) GTEST_SKIP() << "shared data absent: " << basin;
  const ProgramRun batch = run({"map", basin.string(), "--resolution", "0.1", "-q", "-o", (root_ / "map.bt").string()});
  ASSERT_EQ(batch.exit_code, 0) << batch.err;
  const auto [used, skipped] = beamCounts(batch.out);
  ASSERT_GT(used, 0) << batch.out;
  for (const Names& format : {Names{"--format", "ping360"}, Names{}}) {
    Names args{"live", basin.string(), "--resolution", "0.1", "-q", "-o", (out_ / "live.bt").string()};
    args.insert(args.end(), format.begin(), format.end());
    const ProgramRun live = run(args);
    ASSERT_EQ(live.exit_code, 0) << live.err;
    EXPECT_EQ(beamCounts(live.out), std::make_pair(used, skipped)) << "live: " << live.out << "map: " << batch.out;
    EXPECT_TRUE(readFile(out_ / "live.bt") == readFile(root_ / "map.bt")) << "live map differs from `sonarmap map`";
    // What was skipped is said in the summary, with why (the reader's line: its byte offset).
    for (const ProgramRun* said : {&batch, &live}) {
      if (skipped == 0) continue;
      const std::string note = "skipped " + std::to_string(skipped) + " by the reader";
      const std::size_t at = said->out.find(note);
      ASSERT_NE(at, std::string::npos) << said->out;
      EXPECT_NE(said->out.find("byte", at), std::string::npos) << said->out;
    }
  }
}

// A replayed log is surveyed before its first beam, so `live` maps it with `map`'s options at the
// automatic resolution too: the basin's 10 m scale, which most of its beams use (5 cm), not the 20 m
// one it ends with (a head's stream would be coarsened to 10 cm); the harbour's 60 m from its start.
TEST_F(CliLive, AReplayedLogGivesMapsMapAtTheAutomaticResolution) {
  for (const char* name : {"ping360_basin.bin", "ping360_harbour_range_changes.bin"}) {
    const fs::path log = fs::path(SONARMAP_SHARED_DATA) / name;
    if (!fs::exists(log)) GTEST_SKIP() << "shared data absent: " << log;
    const ProgramRun batch = run({"map", log.string(), "-q", "-o", (root_ / "auto.bt").string()});
    ASSERT_EQ(batch.exit_code, 0) << batch.err;
    const ProgramRun live = run({"live", log.string(), "-q", "-o", (out_ / "auto.bt").string()});
    ASSERT_EQ(live.exit_code, 0) << live.err;
    EXPECT_TRUE(readFile(out_ / "auto.bt") == readFile(root_ / "auto.bt"))
        << name << ": live map differs from `sonarmap map`\nlive: " << live.out << "map: " << batch.out;
  }
}

// A Ping Viewer log is a file, not the bytes a sonar sends: on a stream it is refused with advice,
// not decoded into a fraction of its beams.
TEST_F(CliLive, APingViewerLogOnAStreamIsRefused) {
  const fs::path basin = fs::path(SONARMAP_SHARED_DATA) / "ping360_basin.bin";
  if (!fs::exists(basin)) GTEST_SKIP() << "shared data absent: " << basin;
  const int log = ::open(basin.c_str(), O_RDONLY | O_CLOEXEC);
  ASSERT_GE(log, 0);
  Child child({"live", "-", "--format", "ping360", "-q", "-o", (out_ / "live.bt").string()}, root_, log);
  ::close(log);
  const ProgramRun refused = child.wait();
  expectError(refused, 1);
  EXPECT_NE(refused.err.find("Ping Viewer log"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(out_ / "live.bt"));
}

TEST_F(CliLive, LoopbackUdpDatagramsGiveTheBatchMap) {
  const std::string batch = batchMap();
  const ProgramRun run = replayOverUdp(tankCapture(), "seanet");
  expectFinished(run);
  EXPECT_TRUE(readFile(out_ / "live.bt") == batch) << "live map differs from `sonarmap map`";
}

// A Ping360's messages over UDP: the map of the same bytes read by `sonarmap map --format ping360`.
TEST_F(CliLive, Ping360OverUdpGivesTheBatchMap) {
  const std::string batch = batchMap(tankPing360Capture(), "ping360");
  ASSERT_GT(batch.size(), 1000u);
  const ProgramRun run = replayOverUdp(tankPing360Capture(), "ping360");
  expectFinished(run);
  EXPECT_TRUE(readFile(out_ / "live.bt") == batch) << "live map differs from `sonarmap map`";
}

// Navigation rows on a second UDP stream place the beams: a vehicle held 5.013 m north of the origin
// (off the voxel grid: the interpolation's rounding cannot move the sonar across a voxel border)
// gives the map of `sonarmap map --nav` with that pose (its clock does not matter for a constant
// pose), not the static one; a malformed row is skipped with a warning.
TEST_F(CliLive, NavigationStreamPlacesTheBeams) {
  const std::string static_map = batchMap();
  writeFile(root_ / "nav.csv", "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n-1,5.013,0,0,0,0,0\n100000,5.013,0,0,0,0,0\n");
  ASSERT_EQ(run({"map", (root_ / "capture.raw").string(), "--format", "seanet", "--nav", (root_ / "nav.csv").string(),
                 "-q", "-o", (root_ / "moved.bt").string()})
                .exit_code,
            0);
  const std::string moved_map = readFile(root_ / "moved.bt");
  ASSERT_NE(moved_map, static_map);
  const Names args = liveWithNavStreamArgs();
  Child child(args, root_, -1);
  const auto [sonar_port, nav_port] = boundPorts(child);
  ASSERT_TRUE(sonar_port > 0 && nav_port > 0);
  sendUdp(nav_port, "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n0,5.013,0,0,0,0,0\n1,5.013,0,oops,0,0,0\n");
  std::this_thread::sleep_for(50ms);  // the first fix comes before the first beam
  sendUdp(nav_port, "100000,5.013,0,0,0,0,0\n");
  std::this_thread::sleep_for(50ms);
  sendUdp(sonar_port, tankCapture());
  const ProgramRun run = child.wait();
  expectFinished(run);
  EXPECT_NE(run.out.find("0 without navigation"), std::string::npos) << run.out;
  EXPECT_TRUE(readFile(out_ / "live.bt") == moved_map) << "live map differs from `sonarmap map --nav`";
  EXPECT_NE(run.err.find("1 navigation rows or frames skipped (navigation CSV rows)"), std::string::npos) << run.err;
}

// A recorded ROS bag replayed: beams with their own stamps and the bag's own navigation, the map of
// `sonarmap map` on the bag byte for byte, each beam shown as it arrives or not (--show sweep).
TEST_F(CliLive, AReplayedRosBagGivesTheBatchMapWithItsNavigation) {
  MsisSimulationOptions options;
  options.turns = 2;
  NavSample start;
  start.position_ned_m = Eigen::Vector3d(-0.8, -0.4, 0.0);
  options.trajectory = constantVelocityTrajectory(start, Eigen::Vector3d(0.1, 0.0, 0.0));
  MsisSimulation run_moving = simulateMsis(builtinScene("tank"), options);
  for (Beam& beam : run_moving.log.beams) beam.time_s += 1.4e9;  // ROS stamps: seconds since 1970
  for (NavSample& fix : run_moving.nav) fix.time_s += 1.4e9;
  const fs::path bag = root_ / "run.bag";
  writeRosBag(bag.string(), run_moving.log, run_moving.nav);
  const ProgramRun batch = run({"map", bag.string(), "-q", "-o", (root_ / "batch.bt").string()});
  ASSERT_EQ(batch.exit_code, 0) << batch.err;
  const ProgramRun replay = run({"live", bag.string(), "--show", "beam", "-q", "-o", (out_ / "live.bt").string()});
  ASSERT_EQ(replay.exit_code, 0) << replay.err;
  EXPECT_NE(replay.out.find("navigation /odometry (nav_msgs/Odometry"), std::string::npos) << replay.out;
  EXPECT_NE(replay.out.find("0 without navigation"), std::string::npos) << replay.out;
  EXPECT_TRUE(readFile(out_ / "live.bt") == readFile(root_ / "batch.bt")) << "replayed map differs from `sonarmap map`";
  const ProgramRun sweeps = run({"live", bag.string(), "--show", "sweep", "-q", "-o", (out_ / "sweeps.bt").string()});
  ASSERT_EQ(sweeps.exit_code, 0) << sweeps.err;
  EXPECT_TRUE(readFile(out_ / "sweeps.bt") == readFile(root_ / "batch.bt")) << "replayed map differs from `sonarmap map`";
  expectError(run({"live", bag.string(), "--nav-stream", "udp://:0", "-o", (out_ / "m.bt").string()}), 2);
  // With --slam: `map --slam`'s map and trajectory, byte for byte (its stamps are not 0.1 s apart to
  // the last digit: the odometry's period comes from the fixes, in both).
  ASSERT_EQ(run({"map", bag.string(), "--slam", "--trajectory", (root_ / "batch.csv").string(), "-q", "-o",
                 (root_ / "batch_slam.bt").string()})
                .exit_code,
            0);
  const ProgramRun slam = run({"live", bag.string(), "--slam", "--trajectory", (out_ / "live.csv").string(), "-q", "-o",
                               (out_ / "live_slam.bt").string()});
  ASSERT_EQ(slam.exit_code, 0) << slam.err;
  EXPECT_TRUE(readFile(out_ / "live_slam.bt") == readFile(root_ / "batch_slam.bt")) << "live --slam map differs";
  EXPECT_TRUE(readFile(out_ / "live.csv") == readFile(root_ / "batch.csv")) << "live --slam trajectory differs";
}

// SIGTERM (a service stopped) and SIGHUP (the SSH session or terminal closed) end the run as Ctrl-C.
class CliLiveStopped : public CliLive, public ::testing::WithParamInterface<int> {};

TEST_P(CliLiveStopped, MidStreamWritesTheMapAndExitsZero) {
  const int signal = GetParam();
  int pipe_fds[2];
  ASSERT_EQ(::pipe2(pipe_fds, O_CLOEXEC), 0);  // the child inherits only its stdin
  Names args = liveArgs("-");
  args.insert(args.end(), {"--write-every", "0.1"});
  Child child(args, root_, pipe_fds[0]);
  ::close(pipe_fds[0]);
  const std::string& capture = tankCapture();
  writeAll(pipe_fds[1], capture.substr(0, capture.size() / 2));  // two turns; the pipe stays open
  for (int i = 0; i < 1000 && !fs::exists(out_ / "live.bt"); ++i) std::this_thread::sleep_for(5ms);
  ASSERT_TRUE(fs::exists(out_ / "live.bt")) << "no periodic write: " << child.err();
  EXPECT_FALSE(readMapFile((out_ / "live.bt").string()).empty());  // a whole map between writes
  ::kill(child.pid(), signal);
  const ProgramRun run = child.wait();
  ::close(pipe_fds[1]);
  expectFinished(run);
  EXPECT_FALSE(readMapFile((out_ / "live.bt").string()).empty());
  EXPECT_EQ(listDir(out_), Names{"live.bt"});  // no temporary file left
}

INSTANTIATE_TEST_SUITE_P(Signals, CliLiveStopped, ::testing::Values(SIGTERM, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& info) { return info.param == SIGHUP ? "sighup" : "sigterm"; });

// A periodic write that fails (the folder removed mid-dive) is said once, as is its recovery; the
// run goes on and its final write succeeds.
TEST_F(CliLive, AFailingPeriodicWriteIsSaidOnceAndItsRecovery) {
  int pipe_fds[2];
  ASSERT_EQ(::pipe2(pipe_fds, O_CLOEXEC), 0);
  const fs::path folder = out_ / "maps";
  fs::create_directories(folder);
  Names args{"live", "-", "--format", "seanet", "--write-every", "0.1", "-o", (folder / "live.bt").string()};
  Child child(args, root_, pipe_fds[0]);
  ::close(pipe_fds[0]);
  const std::string& capture = tankCapture();
  writeAll(pipe_fds[1], capture.substr(0, capture.size() / 2));
  for (int i = 0; i < 1000 && !fs::exists(folder / "live.bt"); ++i) std::this_thread::sleep_for(5ms);
  ASSERT_TRUE(fs::exists(folder / "live.bt")) << "no periodic write: " << child.err();
  fs::remove_all(folder);
  std::this_thread::sleep_for(600ms);  // several failed writes
  fs::create_directories(folder);
  std::this_thread::sleep_for(600ms);
  ::kill(child.pid(), SIGTERM);
  const ProgramRun run = child.wait();
  ::close(pipe_fds[1]);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = run.err.find(what); at != std::string::npos; at = run.err.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("the periodic map write failed (the last good map stays): cannot write"), 1U) << run.err;
  EXPECT_EQ(count("the periodic map writes work again"), 1U) << run.err;
  EXPECT_FALSE(readMapFile((folder / "live.bt").string()).empty());
}

// An output that cannot be written is said before the head is read or driven (a dive's map is
// written at its end), in one line, as --record's is.
TEST_F(CliLive, AnUnwritableOutputIsRefusedBeforeAnyBeam) {
  const std::string missing = (out_ / "no such folder" / "dive.bt").string();
  const ProgramRun run = this->run({"live", "-", "--format", "seanet", "-o", missing});
  expectError(run, 1);
  EXPECT_NE(run.err.find("cannot write '" + missing + "': cannot create a temporary file in its folder"), std::string::npos)
      << run.err;
  const ProgramRun trajectory = this->run({"live", "-", "--format", "seanet", "--slam", "--trajectory",
                                           (out_ / "gone" / "t.csv").string(), "-o", (out_ / "x.bt").string()});
  expectError(trajectory, 1);
  EXPECT_TRUE(listDir(out_).empty());
}

TEST_F(CliLive, RejectsAFileFormatAndNoBeamIsAnError) {
  expectError(run({"live", "-", "--format", "mat", "-o", (out_ / "m.bt").string()}), 2);
  expectError(run({"live", "-", "--format", "seanet", "--show", "turn", "-o", (out_ / "m.bt").string()}), 2);
  expectError(run({"live", "-", "--format", "seanet", "--integrate", "sweep", "-o", (out_ / "m.bt").string()}), 2);
  expectError(run({"live", "udp://127.0.0.1", "--format", "seanet", "-o", (out_ / "m.bt").string()}), 1);
  expectError(run({"live", "-", "--format", "ping360", "-q", "-o", (out_ / "m.bt").string()}), 1);  // /dev/null: no beam
  EXPECT_TRUE(listDir(out_).empty());
}

}  // namespace
}  // namespace sonarmap::test
