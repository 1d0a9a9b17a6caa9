#pragma once
/// @file live_fixture.hpp
/// The fixture of `sonarmap live`'s end-to-end tests: a simulated tank run encoded byte by byte as a
/// raw SeaNet capture and as a Ping360 stream (wire_fixture.hpp), with line noise and a final frame
/// cut short, and the ways of feeding it to `live` (a pseudo-terminal, loopback UDP, standard input).

#include <gtest/gtest.h>

#include "sonarmap/nav/navigation.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <termios.h>

#include <utility>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <regex>
#include <thread>

#include "cli_fixture.hpp"
#include "child_process.hpp"
#include "formats/wire_fixture.hpp"
#include "sonarmap/formats/ros_bag_writer.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap::test {
namespace {  // each test file has its own copy

using namespace std::chrono_literals;

/// The simulated run both captures encode: a static head turning 4 times in the built-in tank.
const MsisSimulation& tankRun() {
  static const MsisSimulation run = [] {
    MsisSimulationOptions options;
    options.turns = 4;
    options.nav_rate_hz = 0.0;
    return simulateMsis(builtinScene("tank"), options);
  }();
  return run;
}

/// The run, each beam an mtHeadData packet (8-bit bins), with noise (a false '@' among it) after
/// every 150th packet and the stream cut inside a last packet.
const std::string& tankCapture() {
  static const std::string capture = [] {
    const MsisSimulation& run = tankRun();
    std::string out;
    for (std::size_t i = 0; i < run.log.beams.size(); ++i) {
      const Beam& beam = run.log.beams[i];
      SeaNetHeadPacket packet;
      const long units = std::lround(beam.bearing_rad / (2.0 * std::numbers::pi) * 6400.0);
      packet.bearing = static_cast<std::uint16_t>((6400 - units % 6400) % 6400);
      packet.ad_interval = static_cast<std::uint16_t>(std::lround(beam.bin_length_m * 2.0 / 1500.0 / 640e-9));
      packet.data = beam.intensities;
      out += seanetHeadData(packet);
      if (i % 150 == 7) out += std::string("\x13\x37@00zz noise \xff", 15);
    }
    return out + seanetHeadData(SeaNetHeadPacket{}).substr(0, 20);
  }();
  return capture;
}

/// The same run as Ping360 device_data messages (1 gradian bearings, 25 ns sample periods), with
/// noise (a false 'BR') after every 150th message and the stream cut inside a last message.
const std::string& tankPing360Capture() {
  static const std::string capture = [] {
    const MsisSimulation& run = tankRun();
    std::string out;
    for (std::size_t i = 0; i < run.log.beams.size(); ++i) {
      const Beam& beam = run.log.beams[i];
      Ping360Data message;
      const long units = std::lround(beam.bearing_rad / (2.0 * std::numbers::pi) * 400.0);
      message.angle = static_cast<std::uint16_t>((400 - units % 400) % 400);
      message.sample_period = static_cast<std::uint16_t>(std::lround(beam.bin_length_m * 2.0 / 1500.0 / 25e-9));
      message.data = beam.intensities;
      out += ping360Message(message);
      if (i % 150 == 7) out += std::string("\x13\x37" "BRzz noise \xff");  // a false start among noise
    }
    return out + ping360Message(Ping360Data{}).substr(0, 12);
  }();
  return capture;
}

/// Writes all of `bytes` to `fd` in chunks of `chunk` bytes.
void writeAll(int fd, const std::string& bytes, std::size_t chunk = 4096) {
  for (std::size_t at = 0; at < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + at, std::min(chunk, bytes.size() - at));
    ASSERT_GT(n, 0) << std::strerror(errno);
    at += static_cast<std::size_t>(n);
  }
}

class CliLive : public CliTest {
 protected:
  /// `sonarmap map` of the capture: the map live must give.
  std::string batchMap(const std::string& capture = tankCapture(), const std::string& format = "seanet") {
    writeFile(root_ / "capture.raw", capture);
    const ProgramRun run = this->run({"map", (root_ / "capture.raw").string(), "--format", format, "-q", "-o",
                                      (root_ / "batch.bt").string()});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return readFile(root_ / "batch.bt");
  }
  /// `live` on `source` in its default integration, or `--show show`.
  Names liveArgs(const std::string& source, const std::string& format = "seanet", const std::string& show = "") const {
    Names args{"live", source, "--format", format, "-o", (out_ / "live.bt").string()};
    if (!show.empty()) args.insert(args.end(), {"--show", show});
    return args;
  }
  /// The UDP port `child` printed after `what` ("reading", "navigation from"), or 0 when it did not.
  static int boundPort(Child& child, const std::string& what) {
    std::smatch bound;
    const std::regex bound_line(what + " udp://:([0-9]+)");
    for (int i = 0; i < 1000; ++i) {  // the port `live` bound (port 0: the system's choice)
      const std::string err = child.err();
      if (std::regex_search(err, bound, bound_line)) return std::stoi(bound[1].str());
      std::this_thread::sleep_for(5ms);
    }
    ADD_FAILURE() << child.err();
    return 0;
  }
  /// `live` on udp://:0 with its navigation on a second UDP port, ending after 2 s of silence;
  /// `extra` follows.
  Names liveWithNavStreamArgs(const Names& extra = {}) const {
    Names args = liveArgs("udp://:0");
    args.insert(args.end(), {"--idle-timeout", "2", "--nav-stream", "udp://:0"});
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  /// The sonar's and the navigation's UDP ports `child` (liveWithNavStreamArgs) bound.
  static std::pair<int, int> boundPorts(Child& child) {
    const int sonar_port = boundPort(child, "reading"), nav_port = boundPort(child, "navigation from");
    EXPECT_GT(sonar_port, 0);
    EXPECT_GT(nav_port, 0);
    return {sonar_port, nav_port};
  }
  /// `bytes` to 127.0.0.1:`port` in datagrams of at most 1400 bytes, paced: none is dropped.
  static void sendUdp(int port, const std::string& bytes) {
    const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(static_cast<std::uint16_t>(port));
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    for (std::size_t at = 0, sent = 0; at < bytes.size(); ++sent) {
      const std::size_t n = std::min<std::size_t>(1400, bytes.size() - at);
      EXPECT_EQ(::sendto(sender, bytes.data() + at, n, 0, reinterpret_cast<sockaddr*>(&to), sizeof to),
                static_cast<ssize_t>(n));
      at += n;
      if (sent % 4 == 3) std::this_thread::sleep_for(1ms);  // about 5 MB/s
    }
    ::close(sender);
  }
  /// `live` on a pseudo-terminal (a serial device at 115200 baud) fed `capture`, then hung up.
  ProgramRun replayOverPty(const std::string& capture, const std::string& format, const std::string& show = "") {
    const int master = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    EXPECT_GE(master, 0);
    EXPECT_EQ(::grantpt(master), 0);
    EXPECT_EQ(::unlockpt(master), 0);
    const std::string slave_path = ::ptsname(master);
    // The test holds the slave open too, raw from the start: bytes written before `live` sets it
    // raw are not cooked, and the line is not hung up before `live` opens it.
    const int slave = ::open(slave_path.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
    EXPECT_GE(slave, 0);
    termios raw{};
    EXPECT_EQ(::tcgetattr(slave, &raw), 0);
    ::cfmakeraw(&raw);
    EXPECT_EQ(::tcsetattr(slave, TCSANOW, &raw), 0);
    Names args = liveArgs(slave_path, format, show);
    args.insert(args.end(), {"--baud", "115200", "--listen-only"});  // the capture is another program's head
    Child child(args, root_, -1);
    writeAll(master, capture, 512);
    // `live` has read every byte: then hang up. A written byte passes through the pty's flip buffer
    // (emptied by a kernel worker) before the line discipline counts it, so an empty input queue
    // is believed only once it has stayed empty for 250 ms.
    for (int empty_polls = 0; empty_polls < 125;) {
      int unread = 0;
      EXPECT_EQ(::ioctl(slave, FIONREAD, &unread), 0);
      empty_polls = unread > 0 ? 0 : empty_polls + 1;
      std::this_thread::sleep_for(2ms);
    }
    ::close(master);
    ProgramRun run = child.wait();
    ::close(slave);
    return run;
  }
  /// `live` on udp://:0 fed `capture` over UDP: its final run.
  ProgramRun replayOverUdp(const std::string& capture, const std::string& format) {
    Names args = liveArgs("udp://:0", format);
    args.insert(args.end(), {"--idle-timeout", "2"});
    Child child(args, root_, -1);
    if (const int port = boundPort(child, "reading"); port > 0) sendUdp(port, capture);
    return child.wait();
  }
  static void expectFinished(const ProgramRun& run) {
    EXPECT_EQ(run.signal, 0);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("beams used"), std::string::npos) << run.out;
    EXPECT_EQ(linesOf(run.out).size(), 1u) << run.out;
  }
};

}  // namespace
}  // namespace sonarmap::test
