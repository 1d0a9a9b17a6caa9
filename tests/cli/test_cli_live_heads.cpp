/// End-to-end tests of `sonarmap live` driving a head: an emulated Ping360 (`sonarmap emulate`) over
/// UDP as a Ping360 Ethernet or BlueOS's ping proxy serves it (live sends to HOST:PORT and reads the
/// replies), an emulated Micron over a pseudo-terminal (a serial line), the settings asked for
/// reaching the head and the recording; the autopilot's navigation as MAVLink, sent by the emulator
/// and by npm's node-mavlink (a real MAVLink implementation), placing the beams, the map of the
/// recording equal to the live map; and SIGINT ending a run whole, the head told to stop.

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <numbers>
#include <regex>
#include <thread>

#include "cli_fixture.hpp"
#include "child_process.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"

// Last: <httplib.h> brings <resolv.h>, whose `_res` macro breaks Eigen's headers after it.
#include <httplib.h>

#ifndef SONARMAP_INTEROP_DIR
#error "SONARMAP_INTEROP_DIR names tests/interop (node-mavlink)"
#endif

namespace sonarmap::test {
namespace {

using namespace std::chrono_literals;

class CliLiveHeads : public CliTest {
 protected:
  /// The UDP port a child printed after "on udp://:" (an emulator) or "reading udp://:" (live).
  static int printedPort(Child& child, const std::string& before) {
    const std::regex line(before + "udp://:([0-9]+)");
    for (int i = 0; i < 2000; ++i) {
      std::smatch found;
      const std::string err = child.err();
      if (std::regex_search(err, found, line)) return std::stoi(found[1].str());
      std::this_thread::sleep_for(5ms);
    }
    ADD_FAILURE() << child.err();
    return 0;
  }
  /// A UDP port free now (bound and released): for a child that must be told where to send.
  static int freeUdpPort() {
    const int probe = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(probe, reinterpret_cast<sockaddr*>(&address), sizeof address);
    socklen_t size = sizeof address;
    ::getsockname(probe, reinterpret_cast<sockaddr*>(&address), &size);
    ::close(probe);
    return ntohs(address.sin_port);
  }
  /// Runs `live` (args) for `seconds`, then SIGINT: its run.
  ProgramRun liveFor(const Names& args, double seconds) {
    fs::create_directories(root_ / "live");
    Child live(args, root_ / "live", -1);
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    ::kill(live.pid(), SIGINT);
    return live.wait();
  }
  static std::size_t numberBefore(const std::string& text, const std::string& word) {
    std::smatch found;
    if (!std::regex_search(text, found, std::regex("([0-9]+) " + word))) return 0;
    return std::stoul(found[1].str());
  }
};

// A Ping360 reached at HOST:PORT over UDP (a Ping360 Ethernet, BlueOS's ping proxy on 9092): live
// commands it with the settings asked for, the head pings only then, and the recording holds them.
TEST_F(CliLiveHeads, DrivesAPing360AtAnUdpAddress) {
  fs::create_directories(root_ / "emu");
  Child emulator({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--duration", "60"},
                 root_ / "emu", -1);
  const int port = printedPort(emulator, "on ");
  ASSERT_GT(port, 0);
  const fs::path recording = out_ / "dive.mcap";
  const ProgramRun run = liveFor({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360", "--range",
                                  "4", "--gain", "high", "--sector", "180", "--step", "1.8", "--record",
                                  recording.string(), "-o", (out_ / "live.bt").string()},
                                 3.0);
  ::kill(emulator.pid(), SIGTERM);
  const ProgramRun emulated = emulator.wait();
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("(driving the head)"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("head: Ping360 (firmware"), std::string::npos) << run.err;
  EXPECT_TRUE(std::regex_search(run.err, std::regex("settings: Ping360: range_m 3\\.98"))) << run.err;  // 1200 samples of 4.4 µs
  EXPECT_NE(run.err.find("gain high"), std::string::npos) << run.err;
  EXPECT_GT(numberBefore(run.out, "beams used"), 20U) << run.out;
  EXPECT_GT(numberBefore(run.out, "obstacles"), 0U) << run.out;
  // What the head sent is what was asked: its gain, a bin of 4 m / 1200 samples, bearings within the
  // sector ahead (±90° of bearing 0, with a step of 2 gradians).
  const SonarLog log = readSonarLog(recording.string());
  ASSERT_GT(log.beams.size(), 20U);
  for (const Beam& beam : log.beams) {
    EXPECT_EQ(beam.gain_setting, 2);
    EXPECT_NEAR(beam.bin_length_m * static_cast<double>(beam.intensities.size()), 4.0, 0.05);
    const double from_ahead_deg = std::remainder(beam.bearing_rad, 2.0 * std::numbers::pi) * 180.0 / std::numbers::pi;
    EXPECT_LE(std::abs(from_ahead_deg), 90.0 + 1e-6);
  }
  // Told to stop: the emulated head's motor is off, and it answered every ping it was asked for.
  EXPECT_NE(emulated.err.find("pings sent"), std::string::npos) << emulated.err;
  EXPECT_GE(numberBefore(emulated.err, "pings sent"), log.beams.size());
  ASSERT_TRUE(fs::exists(out_ / "live.bt"));
  // Recorded without navigation (a head on a stand): the recording maps and is described, as the
  // summary line tells the user, and its map is the live one.
  const ProgramRun info = this->run({"info", recording.string()});
  EXPECT_EQ(info.exit_code, 0) << info.err;
  const ProgramRun batch = this->run({"map", recording.string(), "-q", "-o", (root_ / "batch.bt").string()});
  ASSERT_EQ(batch.exit_code, 0) << batch.err;
  EXPECT_TRUE(readFile(out_ / "live.bt") == readFile(root_ / "batch.bt")) << "the recording's map differs";
}

// A Tritech Micron on a serial line (a pseudo-terminal): rebooted, asked its version, configured,
// then one mtSendData per beam.
TEST_F(CliLiveHeads, DrivesAMicronOnASerialLine) {
  const fs::path line = root_ / "micron";
  fs::create_directories(root_ / "emu");
  Child emulator({"emulate", "--sonar", "micron", "--scene", "tank", "--serial", "pty:" + line.string(), "--duration",
                  "60"},
                 root_ / "emu", -1);
  for (int i = 0; i < 2000 && !fs::exists(line); ++i) std::this_thread::sleep_for(5ms);
  ASSERT_TRUE(fs::exists(line)) << emulator.err();
  const ProgramRun run = liveFor({"live", line.string(), "--format", "seanet", "--range", "5", "--gain", "45", "-o",
                                  (out_ / "live.bt").string()},
                                 5.0);
  ::kill(emulator.pid(), SIGTERM);
  emulator.wait();
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("settings: Tritech SeaNet head: range_m 5"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("gain 45%"), std::string::npos) << run.err;
  EXPECT_GT(numberBefore(run.out, "beams used"), 20U) << run.out;
  EXPECT_GT(numberBefore(run.out, "obstacles"), 0U) << run.out;
}

// The emulator flies a straight line and sends its navigation as ArduSub does: the beams are placed
// by it (none without navigation but the few before the first fix), and `map` of the recording
// gives the live map byte for byte.
TEST_F(CliLiveHeads, MavlinkNavigationPlacesTheBeamsAndTheRecordingMapsToTheLiveMap) {
  const int nav_port = freeUdpPort();
  fs::create_directories(root_ / "emu");
  Child emulator({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--speed", "0.2",
                  "--heading", "45", "--mavlink", "udp://127.0.0.1:" + std::to_string(nav_port), "--duration", "60"},
                 root_ / "emu", -1);
  const int port = printedPort(emulator, "on ");
  ASSERT_GT(port, 0);
  const fs::path recording = out_ / "dive.mcap";
  const ProgramRun run = liveFor({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360", "--range",
                                  "4", "--nav-stream", "udp://:" + std::to_string(nav_port), "--resolution", "0.05",
                                  "--record", recording.string(), "-o", (out_ / "live.bt").string()},
                                 4.0);
  ::kill(emulator.pid(), SIGTERM);
  emulator.wait();
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("MAVLink (a frame with a matching checksum)"), std::string::npos) << run.err;
  const std::size_t used = numberBefore(run.out, "beams used");
  EXPECT_GT(used, 20U) << run.out;
  // The decoder learns for a second which messages the vehicle sends before its first fix.
  EXPECT_LT(numberBefore(run.out, "without navigation"), used / 10) << run.out;
  const std::optional<RosBagNavigation> nav = readRosBagNavigation(recording.string());
  ASSERT_TRUE(nav.has_value());
  ASSERT_GT(nav->track.size(), 20U);
  const double moved_m = (nav->track.back().position_ned_m - nav->track.front().position_ned_m).norm();
  EXPECT_NEAR(moved_m, 0.2 * (nav->track.back().time_s - nav->track.front().time_s), 0.05);
  EXPECT_NEAR(nav->track.back().yaw_rad, std::numbers::pi / 4, 1e-6);
  const ProgramRun batch =
      this->run({"map", recording.string(), "--resolution", "0.05", "-q", "-o", (root_ / "batch.bt").string()});
  ASSERT_EQ(batch.exit_code, 0) << batch.err;
  EXPECT_TRUE(readFile(out_ / "live.bt") == readFile(root_ / "batch.bt")) << "the recording's map differs";
}

// A BlueROV2 without a DVL: ArduSub's MAVLink gives attitude and depth, no position (the
// emulator's --no-position). live --slam decides at its first sweep that the navigation gives the
// heading only, as `map --slam` decides on the recording, and its map is that of the recording.
TEST_F(CliLiveHeads, SlamWithAutopilotHeadingOnlyMapsAsTheRecording) {
  const int nav_port = freeUdpPort();
  fs::create_directories(root_ / "emu");
  Child emulator({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--speed", "0.1",
                  "--heading", "45", "--mavlink", "udp://127.0.0.1:" + std::to_string(nav_port), "--no-position",
                  "--time-scale", "4", "--duration", "200"},
                 root_ / "emu", -1);
  const int port = printedPort(emulator, "on ");
  ASSERT_GT(port, 0);
  const fs::path recording = out_ / "dive.mcap";
  const ProgramRun run = liveFor({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360", "--range",
                                  "4", "--nav-stream", "udp://:" + std::to_string(nav_port), "--resolution", "0.05",
                                  "--slam", "--record", recording.string(), "-o", (out_ / "live.bt").string()},
                                 8.0);
  ::kill(emulator.pid(), SIGTERM);
  emulator.wait();
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("--nav gives the heading only"), std::string::npos) << run.out;
  // How many sweeps arrive in the time depends on the machine (a sanitizer build takes fewer);
  // whatever arrived, the recording's scans are placed as live placed them.
  EXPECT_GE(numberBefore(run.out, "scans \\("), 2U) << run.out;
  const ProgramRun batch =
      this->run({"map", recording.string(), "--slam", "--resolution", "0.05", "-o", (root_ / "batch.bt").string()});
  ASSERT_EQ(batch.exit_code, 0) << batch.err;
  EXPECT_NE(batch.out.find("--nav gives the heading only"), std::string::npos) << batch.out;
  EXPECT_EQ(numberBefore(batch.out, "scans \\("), numberBefore(run.out, "scans \\(")) << run.out << batch.out;
  EXPECT_EQ(numberBefore(batch.out, "matched to the scans before them"),
            numberBefore(run.out, "matched to the scans before them"))
      << run.out << batch.out;
  EXPECT_TRUE(readFile(out_ / "live.bt") == readFile(root_ / "batch.bt")) << "the recording's map differs";
}

// BlueOS's MAVLink endpoints ("UDP Server", 14550 and 14660) send only to clients that have sent
// them a datagram, as the emulator's `--mavlink udp://:PORT` does: live's client --nav-stream
// sends HEARTBEATs and is served; the emulator heard them.
TEST_F(CliLiveHeads, ANavStreamToAServerEndpointIsServedAfterItsHeartbeats) {
  fs::create_directories(root_ / "emu");
  Child emulator({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--speed", "0.2",
                  "--heading", "45", "--mavlink", "udp://:0", "--duration", "60"},
                 root_ / "emu", -1);
  const int port = printedPort(emulator, "on ");
  const int nav_port = printedPort(emulator, "MAVLink at 10 Hz to ");
  ASSERT_GT(port, 0);
  ASSERT_GT(nav_port, 0);
  const ProgramRun run = liveFor({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360", "--range",
                                  "4", "--nav-stream", "udp://127.0.0.1:" + std::to_string(nav_port), "--resolution",
                                  "0.05", "-o", (out_ / "live.bt").string()},
                                 4.0);
  ::kill(emulator.pid(), SIGTERM);
  const ProgramRun emulated = emulator.wait();
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::size_t used = numberBefore(run.out, "beams used");
  EXPECT_GT(used, 20U) << run.out;
  EXPECT_LT(numberBefore(run.out, "without navigation"), used / 4) << run.out;
  // one HEARTBEAT a second over the 4 s
  EXPECT_GE(numberBefore(emulated.err, "datagrams received"), 3U) << emulated.err;
}

// The same against an endpoint written with node-mavlink (npm), a MAVLink implementation other than
// ours: it serves only a client whose datagram parses as a HEARTBEAT, and says whose it was.
TEST_F(CliLiveHeads, ANodeMavlinkServerEndpointParsesTheHeartbeatAndServesLive) {
  const fs::path interop(SONARMAP_INTEROP_DIR);
  if (!fs::exists(interop / "node_modules" / "node-mavlink") || std::system("node --version > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "needs node and node-mavlink: `npm ci` in tests/interop (scripts/install-deps.sh test does it)";
  }
  std::ofstream csv(root_ / "nav.csv");
  csv << "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n";
  for (int i = 0; i < 30; ++i) csv << 100.0 + 0.1 * i << "," << 0.01 * i << ",0,1.5,0,0,0.3\n";
  csv.close();
  const int nav_port = freeUdpPort();
  const std::string serve = "node " + (interop / "encode_navigation.js").string() + " " + (root_ / "nav.csv").string() +
                            " --version 2 --serve " + std::to_string(nav_port) + " > " + (root_ / "endpoint.out").string();
  int served = -1;
  std::thread endpoint([&] { served = std::system(serve.c_str()); });
  std::this_thread::sleep_for(300ms);
  fs::create_directories(root_ / "emu");
  Child emulator({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--duration", "60"},
                 root_ / "emu", -1);
  const int port = printedPort(emulator, "on ");
  fs::create_directories(root_ / "live");
  const fs::path recording = out_ / "dive.mcap";
  Child live({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360", "--range", "4", "--nav-stream",
              "udp://127.0.0.1:" + std::to_string(nav_port), "--record", recording.string(), "-o",
              (out_ / "live.bt").string()},
             root_ / "live", -1);
  endpoint.join();
  ::kill(live.pid(), SIGINT);
  const ProgramRun run = live.wait();
  ::kill(emulator.pid(), SIGTERM);
  emulator.wait();
  ASSERT_EQ(served, 0) << readFile(root_ / "endpoint.out");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // a companion computer's heartbeat: system 1, component 191, MAV_TYPE_ONBOARD_CONTROLLER, MAV_AUTOPILOT_INVALID
  EXPECT_NE(readFile(root_ / "endpoint.out").find(R"({"sysid":1,"compid":191,"type":18,"autopilot":8})"), std::string::npos)
      << readFile(root_ / "endpoint.out");
  const std::optional<RosBagNavigation> nav = readRosBagNavigation(recording.string());
  ASSERT_TRUE(nav.has_value());
  EXPECT_GE(nav->track.size(), 20U);  // UDP on loopback: all or nearly all of the 30 rows
}

// A dive whose map holds no obstacle (the head 1.5 m down in the tank, below its walls) did not map
// what it was run for: the map is written all the same, and the run fails saying so.
TEST_F(CliLiveHeads, AnEmptyMapIsWrittenAndFailsTheRun) {
  fs::create_directories(root_ / "emu");
  Child emulator({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--depth", "1.5",
                  "--duration", "60"},
                 root_ / "emu", -1);
  const int port = printedPort(emulator, "on ");
  ASSERT_GT(port, 0);
  const ProgramRun run = liveFor({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360", "--range",
                                  "4", "--sector", "90", "-o", (out_ / "live.bt").string()},
                                 3.0);
  ::kill(emulator.pid(), SIGTERM);
  emulator.wait();
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("sonarmap: error: the map is empty: no obstacle in "), std::string::npos) << run.err;
  EXPECT_TRUE(fs::exists(out_ / "live.bt"));
}

// BlueOS's ping proxy (`bridges -u 0.0.0.0:9092`) sends the head's bytes to every client it heard
// from in the last 10 s, as the emulator's UDP head does: a `--listen-only` live beside the live
// that drives the head registers by a request and maps the same pings.
TEST_F(CliLiveHeads, ListeningThroughAProxyBesideTheDriverReceivesThePings) {
  fs::create_directories(root_ / "emu");
  fs::create_directories(root_ / "driver");
  Child emulator({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--duration", "60"},
                 root_ / "emu", -1);
  const int port = printedPort(emulator, "on ");
  ASSERT_GT(port, 0);
  Child driver({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360", "--range", "4", "-o",
                (root_ / "driver" / "driver.bt").string()},
               root_ / "driver", -1);
  std::this_thread::sleep_for(500ms);
  const ProgramRun listener = liveFor({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360",
                                       "--listen-only", "-o", (out_ / "listener.bt").string()},
                                      4.0);
  ::kill(driver.pid(), SIGINT);
  const ProgramRun driven = driver.wait();
  ::kill(emulator.pid(), SIGTERM);
  emulator.wait();
  ASSERT_EQ(driven.exit_code, 0) << driven.err;
  ASSERT_EQ(listener.exit_code, 0) << listener.err;
  EXPECT_NE(listener.err.find("(listening)"), std::string::npos) << listener.err;
  EXPECT_GT(numberBefore(listener.out, "beams used"), 100U) << listener.out << listener.err;
}

// The navigation sent by node-mavlink (npm), a MAVLink implementation other than ours, from rows a
// CSV also gives: the fixes live took are those rows (to float32), and the recording maps to the live map.
TEST_F(CliLiveHeads, NodeMavlinkNavigationIsTakenAsSent) {
  const fs::path interop(SONARMAP_INTEROP_DIR);
  if (!fs::exists(interop / "node_modules" / "node-mavlink") || std::system("node --version > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "needs node and node-mavlink: `npm ci` in tests/interop (scripts/install-deps.sh test does it)";
  }
  std::ofstream csv(root_ / "nav.csv");
  csv << "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n";
  for (int i = 0; i < 40; ++i) {
    const double t = 0.1 * i;
    csv << 100.0 + t << "," << 0.1 * t << "," << -0.05 * t << ",0.5," << 0.01 << "," << -0.02 << "," << 0.3 + 0.05 * t << "\n";
  }
  csv.close();
  const int nav_port = freeUdpPort();
  fs::create_directories(root_ / "emu");
  Child emulator({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--depth", "0.5",
                  "--duration", "60"},
                 root_ / "emu", -1);
  const int port = printedPort(emulator, "on ");
  ASSERT_GT(port, 0);
  fs::create_directories(root_ / "live");
  const fs::path recording = out_ / "dive.mcap";
  // a 180° sector: passes end within the 4 s the rows take, so the map is not empty
  Child live({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360", "--range", "4", "--sector", "180",
              "--nav-stream", "udp://:" + std::to_string(nav_port), "--resolution", "0.05", "--record", recording.string(),
              "-o", (out_ / "live.bt").string()},
             root_ / "live", -1);
  std::this_thread::sleep_for(300ms);
  const std::string send = "node " + (interop / "encode_navigation.js").string() + " " + (root_ / "nav.csv").string() +
                           " --version 2 --udp 127.0.0.1:" + std::to_string(nav_port);
  ASSERT_EQ(std::system(send.c_str()), 0) << send;
  ::kill(live.pid(), SIGINT);
  const ProgramRun run = live.wait();
  ::kill(emulator.pid(), SIGTERM);
  emulator.wait();
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::optional<RosBagNavigation> nav = readRosBagNavigation(recording.string());
  ASSERT_TRUE(nav.has_value());
  ASSERT_GE(nav->track.size(), 30U);  // UDP on loopback: all or nearly all of the 40
  // Each fix is a row, in order, its values as the frames carry them (float32).
  std::size_t row = 0;
  for (const NavSample& fix : nav->track) {
    while (row < 40 && std::abs(fix.position_ned_m.x() - static_cast<float>(0.1 * 0.1 * row)) > 1e-6) ++row;
    ASSERT_LT(row, 40U) << "a fix that is no row: " << fix.position_ned_m.transpose();
    const double t = 0.1 * static_cast<double>(row);
    EXPECT_EQ(fix.position_ned_m.y(), static_cast<double>(static_cast<float>(-0.05 * t)));
    EXPECT_EQ(fix.position_ned_m.z(), static_cast<double>(0.5f));
    EXPECT_EQ(fix.roll_rad, static_cast<double>(0.01f));
    EXPECT_EQ(fix.pitch_rad, static_cast<double>(-0.02f));
    EXPECT_EQ(fix.yaw_rad, static_cast<double>(static_cast<float>(0.3 + 0.05 * t)));
  }
  const ProgramRun batch =
      this->run({"map", recording.string(), "--resolution", "0.05", "-q", "-o", (root_ / "batch.bt").string()});
  ASSERT_EQ(batch.exit_code, 0) << batch.err;
  EXPECT_TRUE(readFile(out_ / "live.bt") == readFile(root_ / "batch.bt")) << "the recording's map differs";
}

// `live --serve`: the page and what it reads while the head is driven, BlueOS's extension metadata,
// nothing that keeps it out of Cockpit's iframe, and its buttons: save writes the map, reset clears it.
TEST_F(CliLiveHeads, ServesThePageWhileItMaps) {
  fs::create_directories(root_ / "emu");
  Child emulator({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--duration", "60"},
                 root_ / "emu", -1);
  const int port = printedPort(emulator, "on ");
  ASSERT_GT(port, 0);
  fs::create_directories(root_ / "live");
  // A 90° sector: the first sweep, which calibrates the beams shown, is done within a second.
  Child live({"live", "udp://127.0.0.1:" + std::to_string(port), "--format", "ping360", "--range", "4", "--sector",
              "90", "--step", "1.8", "--serve",
              "127.0.0.1:0", "--write-every", "100", "-o", (out_ / "live.bt").string()},
             root_ / "live", -1);
  const std::regex page_line("the page is at http://127\\.0\\.0\\.1:([0-9]+)/");
  std::smatch found;
  std::string err;
  for (int i = 0; i < 2000 && !std::regex_search(err = live.err(), found, page_line); ++i) std::this_thread::sleep_for(5ms);
  ASSERT_TRUE(std::regex_search(err, found, page_line)) << err;
  httplib::Client page("127.0.0.1", std::stoi(found[1].str()));
  const httplib::Result index = page.Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_NE(index->body.find("<html"), std::string::npos);
  EXPECT_FALSE(index->has_header("X-Frame-Options"));
  const httplib::Result service = page.Get("/register_service");
  ASSERT_TRUE(service);
  EXPECT_TRUE(std::regex_search(service->body, std::regex("\"works_in_relative_paths\": *true"))) << service->body;
  std::this_thread::sleep_for(2500ms);  // beams arrive and the map is shown
  const httplib::Result state = page.Get("/state");
  ASSERT_TRUE(state);
  EXPECT_NE(state->body.find("Ping360"), std::string::npos);  // the head's settings
  const httplib::Result picture = page.Get("/map.png");
  ASSERT_TRUE(picture);
  EXPECT_EQ(picture->status, 200);
  EXPECT_EQ(picture->body.substr(1, 3), "PNG");
  const httplib::Headers acting{{"X-Sonarmap", "1"}};
  EXPECT_EQ(page.Post("/save")->status, 403);  // a page of another site cannot press the buttons
  const httplib::Result saved = page.Post("/save", acting, "", "text/plain");
  ASSERT_TRUE(saved);
  EXPECT_EQ(saved->status, 200) << saved->body;
  EXPECT_TRUE(fs::exists(out_ / "live.bt"));
  const httplib::Result reset = page.Post("/reset", acting, "", "text/plain");
  ASSERT_TRUE(reset);
  EXPECT_EQ(reset->status, 200) << reset->body;
  std::this_thread::sleep_for(1500ms);  // a sector pass after the reset: the map is not empty
  ::kill(live.pid(), SIGINT);
  const ProgramRun run = live.wait();
  ::kill(emulator.pid(), SIGTERM);
  emulator.wait();
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("the map was reset: it starts again from the next beam"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("the map was reset 1 times from the page"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace sonarmap::test
