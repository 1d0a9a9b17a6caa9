// A listening UDP ByteLink serves its peers as BlueOS's `bridges` serves a head's UDP clients
// (patrickelectric/bridges, src/socket.rs): every peer heard, the newest kUdpMaxPeers, none
// registered by an empty datagram.
#include <gtest/gtest.h>

#include <poll.h>
#include <sys/socket.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sonarmap/live/byte_link.hpp"

namespace sonarmap {
namespace {

/// The port a listening link bound ("udp://:40123").
std::string portOf(const ByteLink& link) { return link.description().substr(link.description().rfind(':') + 1); }

/// One datagram read from `link` within `timeout_ms`, or empty.
std::vector<std::uint8_t> receive(ByteLink& link, int timeout_ms) {
  pollfd waiting{link.fd(), POLLIN, 0};
  if (::poll(&waiting, 1, timeout_ms) <= 0) return {};
  std::array<std::uint8_t, 256> buffer{};
  const long got = link.read(buffer);
  if (got <= 0) return {};
  return {buffer.begin(), buffer.begin() + got};
}

const std::vector<std::uint8_t> kHello{'h', 'i'}, kReply{'o', 'k'};

TEST(liveByteLink, AListeningUdpLinkAnswersEveryPeerItHeard) {
  ByteLink server("udp://:0", 0);
  EXPECT_FALSE(server.networkClient());
  EXPECT_FALSE(server.write(kReply)) << "no peer yet";
  ByteLink a("udp://127.0.0.1:" + portOf(server), 0), b("udp://127.0.0.1:" + portOf(server), 0);
  EXPECT_TRUE(a.networkClient());
  ASSERT_TRUE(a.write(kHello));
  ASSERT_TRUE(b.write(kHello));
  EXPECT_EQ(receive(server, 1000), kHello);
  EXPECT_EQ(receive(server, 1000), kHello);
  ASSERT_TRUE(server.write(kReply));
  EXPECT_EQ(receive(a, 1000), kReply);
  EXPECT_EQ(receive(b, 1000), kReply);
}

TEST(liveByteLink, AListeningUdpLinkServesTheNewestPeersOnlyAndNoneForAnEmptyDatagram) {
  ByteLink server("udp://:0", 0);
  std::vector<std::unique_ptr<ByteLink>> clients;
  for (std::size_t i = 0; i <= ByteLink::kUdpMaxPeers; ++i) {
    clients.push_back(std::make_unique<ByteLink>("udp://127.0.0.1:" + portOf(server), 0));
    ASSERT_TRUE(clients.back()->write(kHello));
    ASSERT_EQ(receive(server, 1000), kHello);
  }
  // an empty datagram (bridges: a line break to the head) registers no one
  ByteLink silent("udp://127.0.0.1:" + portOf(server), 0);
  ASSERT_EQ(::send(silent.fd(), "", 0, 0), 0);
  receive(server, 200);
  ASSERT_TRUE(server.write(kReply));
  EXPECT_TRUE(receive(*clients.front(), 200).empty()) << "the oldest of " << clients.size() << " is dropped";
  for (std::size_t i = 1; i < clients.size(); ++i) EXPECT_EQ(receive(*clients[i], 1000), kReply) << i;
  EXPECT_TRUE(receive(silent, 200).empty());
}

}  // namespace
}  // namespace sonarmap
