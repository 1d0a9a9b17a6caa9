// `sonarmap emulate`: a Ping360 served on a pseudo-terminal and on UDP answers ping-protocol as the
// head would (its identity, a ping with the scene's wall), ends cleanly on SIGTERM with a summary,
// and refuses arguments it cannot serve with one line and exit code 2.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <regex>
#include <thread>

#include "child_process.hpp"
#include "sonarmap/formats/ping_protocol.hpp"

namespace sonarmap::test {
namespace {

namespace pp = ping_protocol;
using namespace std::chrono_literals;
using CliEmulate = CliTest;

/// The first message `fd` gives within `timeout`, read with `read_some`.
template <class Read>
std::optional<pp::Message> nextMessage(int fd, Read read_some, pp::MessageParser& parser,
                                       std::chrono::milliseconds timeout = 5000ms) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::uint8_t buffer[4096];
  while (std::chrono::steady_clock::now() < deadline) {
    pollfd ready{fd, POLLIN, 0};
    if (::poll(&ready, 1, 50) <= 0) continue;
    const long got = read_some(buffer, sizeof buffer);
    if (got <= 0) continue;
    std::vector<pp::Message> messages = parser.feed(std::span(buffer, static_cast<std::size_t>(got)));
    if (!messages.empty()) return messages.front();
  }
  return std::nullopt;
}

pp::Transducer ping(int angle) { return {1, 1, static_cast<std::uint16_t>(angle), 27, 222, 750, 1200, 1, 0}; }

TEST_F(CliEmulate, APing360OnAPseudoTerminal) {
  const fs::path link = root_ / "ping360";
  Child child({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--serial", "pty:" + link.string(), "--duration",
               "30"},
              root_, -1);
  for (int i = 0; i < 2000 && !fs::exists(link); ++i) std::this_thread::sleep_for(5ms);
  ASSERT_TRUE(fs::exists(link)) << child.err();
  const int fd = ::open(link.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  ASSERT_GE(fd, 0);
  termios raw{};
  ASSERT_EQ(::tcgetattr(fd, &raw), 0);
  ::cfmakeraw(&raw);
  ASSERT_EQ(::tcsetattr(fd, TCSANOW, &raw), 0);
  const auto read_some = [fd](std::uint8_t* buffer, std::size_t size) { return static_cast<long>(::read(fd, buffer, size)); };
  pp::MessageParser parser;

  // ping-python connects with a break and an autobaud 'U': ignored.
  const std::vector<std::uint8_t> hello = {0, 'U'};
  ASSERT_EQ(::write(fd, hello.data(), hello.size()), 2);
  const std::vector<std::uint8_t> request = pp::encode(pp::GeneralRequest{pp::kDeviceInformation});
  ASSERT_EQ(::write(fd, request.data(), request.size()), static_cast<ssize_t>(request.size()));
  const std::optional<pp::Message> info = nextMessage(fd, read_some, parser);
  ASSERT_TRUE(info) << child.err();
  ASSERT_EQ(info->id, pp::kDeviceInformation);
  EXPECT_EQ(pp::decode<pp::DeviceInformation>(*info)->device_type, 2);

  // The tank's north wall 2.1 m ahead: 5 m in 1200 samples of 222 ticks, the wall near sample 504.
  const std::vector<std::uint8_t> command = pp::encode(ping(0));
  ASSERT_EQ(::write(fd, command.data(), command.size()), static_cast<ssize_t>(command.size()));
  const std::optional<pp::Message> reply = nextMessage(fd, read_some, parser);
  ASSERT_TRUE(reply) << child.err();
  const std::optional<pp::DeviceData> data = pp::decode<pp::DeviceData>(*reply);
  ASSERT_TRUE(data);
  EXPECT_EQ(data->angle_grad, 0);
  ASSERT_EQ(data->data.size(), 1200u);
  EXPECT_GT(*std::max_element(data->data.begin() + 480, data->data.begin() + 540), 150);
  ::close(fd);

  ::kill(child.pid(), SIGTERM);
  const ProgramRun run = child.wait();
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("sonarmap: emulate: ping360-5m in tank (built for 5 m) on pty " + link.string()), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find(": 1 pings sent; last settings: range 4.995 m (1200 samples of 222 ticks), gain 1, angle 0 grad"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(link));  // the link to the pty is removed on exit
}

TEST_F(CliEmulate, APing360OnUdpAnswersTheLastPeer) {
  Child child({"emulate", "--sonar", "ping360-5m", "--scene", "tank", "--udp", "udp://:0", "--duration", "30"}, root_, -1);
  int port = 0;
  const std::regex bound_line("on udp://:([0-9]+)");
  for (int i = 0; i < 2000 && port == 0; ++i) {
    std::smatch bound;
    const std::string err = child.err();
    if (std::regex_search(err, bound, bound_line)) port = std::stoi(bound[1].str());
    std::this_thread::sleep_for(5ms);
  }
  ASSERT_GT(port, 0) << child.err();
  const int socket_fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(socket_fd, reinterpret_cast<sockaddr*>(&to), sizeof to), 0);
  const auto read_some = [socket_fd](std::uint8_t* buffer, std::size_t size) {
    return static_cast<long>(::recv(socket_fd, buffer, size, 0));
  };
  pp::MessageParser parser;
  const std::vector<std::uint8_t> command = pp::encode(ping(100));
  ASSERT_EQ(::send(socket_fd, command.data(), command.size(), 0), static_cast<ssize_t>(command.size()));
  const std::optional<pp::Message> reply = nextMessage(socket_fd, read_some, parser);
  ASSERT_TRUE(reply) << child.err();
  const std::optional<pp::DeviceData> data = pp::decode<pp::DeviceData>(*reply);
  ASSERT_TRUE(data);
  EXPECT_EQ(data->angle_grad, 100);
  EXPECT_EQ(data->data.size(), 1200u);
  ::close(socket_fd);
  ::kill(child.pid(), SIGINT);
  const ProgramRun run = child.wait();
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find(": 1 pings sent"), std::string::npos) << run.err;
}

TEST_F(CliEmulate, ArgumentsItCannotServeAreRefused) {
  ProgramRun run = this->run({"emulate", "--sonar", "imagenex-881a", "--udp", "udp://:0"});
  expectError(run, 2);
  EXPECT_NE(run.err.find("--sonar imagenex-881a cannot be emulated: expected one of ping360, ping360-2m, ping360-5m, "
                         "micron, seaking-30, seaking-50"),
            std::string::npos)
      << run.err;
  run = this->run({"emulate", "--udp", "udp://:0", "--time-scale", "1000"});
  expectError(run, 2);
  run = this->run({"emulate", "--udp", "udp://:0", "--no-position"});
  expectError(run, 2);
  run = this->run({"emulate"});
  expectError(run, 2);
  EXPECT_NE(run.err.find("no link to serve the head on"), std::string::npos) << run.err;
  run = this->run({"emulate", "--scene", (root_ / "nowhere.txt").string(), "--udp", "udp://:0"});
  expectError(run, 2);
  EXPECT_NE(run.err.find("is neither a built-in scene"), std::string::npos) << run.err;
  run = this->run({"emulate", "--serial", "pty:", "--duration", "1"});
  expectError(run, 1);
  EXPECT_NE(run.err.find("expected pty:PATH"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace sonarmap::test
