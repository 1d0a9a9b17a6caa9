/// @file test_seanet_emulator.cpp
/// SeaNetEmulator alone: mtAlive unprompted, answers to each command, beams only when asked and
/// when they would be due, 4-bit packing, and malformed input ignored.

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "devices/seanet_bench.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

using seanet::MessageType;

std::vector<seanet::Packet> packetsOf(const std::vector<TimedBytes>& replies) {
  seanet::PacketParser parser;
  std::vector<seanet::Packet> packets;
  for (const TimedBytes& reply : replies) {
    for (seanet::Packet& p : parser.feed(reply.bytes)) packets.push_back(std::move(p));
  }
  return packets;
}

/// The driver's default command for 5 m over 100 bins (seanet_driver.hpp).
seanet::HeadCommand defaultCommand() {
  seanet::HeadCommand c;
  c.hd_ctrl = 0x2307;
  c.range_scale_dm = 50;
  c.left_limit = 0;
  c.right_limit = 6399;
  c.ad_span = 149;
  c.ad_low = 14;
  c.igain[0] = c.igain[1] = 84;
  c.mo_time = 25;
  c.step = 32;
  c.ad_interval = 104;
  c.nbins = 100;
  return c;
}

SeaNetEmulator micron() { return SeaNetEmulator(test::seaNetSimulator("micron"), SeaNetEmulatorOptions{"micron"}); }

TEST(SeaNetEmulator, SendsAliveEverySecondSayingItHasNoParameters) {
  SeaNetEmulator head = micron();
  const std::vector<TimedBytes> first = head.poll(0.0);
  const std::vector<TimedBytes> more = head.poll(3.5);
  ASSERT_EQ(first.size(), 1U);
  ASSERT_EQ(more.size(), 3U);
  EXPECT_DOUBLE_EQ(more[2].at_s, 3.0);
  for (const seanet::Packet& p : packetsOf(more)) {
    const auto alive = seanet::decodeAlive(p);
    ASSERT_TRUE(alive);
    EXPECT_TRUE(alive->has(seanet::AliveInfo::kNoParams));
    EXPECT_FALSE(alive->has(seanet::AliveInfo::kMotorOn));
  }
  EXPECT_EQ(seanet::decodeAlive(packetsOf(more)[2])->head_time_ms, 3000U);
  EXPECT_EQ(head.beamsSent(), 0U);
  EXPECT_EQ(head.settingsText(), "no parameters (waiting for mtHeadCommand)");
}

TEST(SeaNetEmulator, AnswersQuestionsWithItsIdentity) {
  SeaNetEmulator head(test::seaNetSimulator("seaking-30"), SeaNetEmulatorOptions{"seaking-30"});
  std::vector<std::uint8_t> asks = seanet::encodeSimpleCommand(MessageType::kSendVersion);
  const std::vector<std::uint8_t> user = seanet::encodeSimpleCommand(MessageType::kSendBBUser);
  asks.insert(asks.end(), user.begin(), user.end());
  const std::vector<TimedBytes> replies = head.receive(asks, 2.0);
  const std::vector<seanet::Packet> packets = packetsOf(replies);
  ASSERT_EQ(packets.size(), 2U);
  EXPECT_GT(replies[0].at_s, 2.0);  // 25 bytes at 115,200 Bd
  EXPECT_NEAR(replies[0].at_s, 2.0 + 25 * 10 / 115200.0, 1e-9);
  const auto version = seanet::decodeVersionData(packets[0]);
  ASSERT_TRUE(version);
  EXPECT_EQ(version->frequencyKhz(), 325.0);
  const auto bb = seanet::decodeBBUserData(packets[1]);
  ASSERT_TRUE(bb);
  EXPECT_TRUE(bb->dual_synth);
  EXPECT_THROW(SeaNetEmulator(test::seaNetSimulator("micron"), SeaNetEmulatorOptions{"ping360"}), ValueError);
}

TEST(SeaNetEmulator, PingsOnlyWhenAskedAndWhenDue) {
  SeaNetEmulator head = micron();
  head.poll(0.0);
  // No parameters: mtSendData is ignored.
  EXPECT_TRUE(head.receive(seanet::encodeSendData(0), 0.5).empty());
  const std::vector<seanet::Packet> ack = packetsOf(head.receive(seanet::encodeHeadCommand(defaultCommand()), 1.0));
  ASSERT_EQ(ack.size(), 1U);
  const auto alive = seanet::decodeAlive(ack[0]);
  ASSERT_TRUE(alive);
  EXPECT_FALSE(alive->has(seanet::AliveInfo::kNoParams));
  EXPECT_TRUE(alive->has(seanet::AliveInfo::kSentConfig));
  EXPECT_TRUE(head.hasParameters());
  // Nothing unprompted but mtAlive.
  for (const seanet::Packet& p : packetsOf(head.poll(5.0))) EXPECT_EQ(p.type, static_cast<std::uint8_t>(MessageType::kAlive));
  // Two requests at once: two beams, the second after the first.
  std::vector<std::uint8_t> two = seanet::encodeSendData(0);
  two.insert(two.end(), two.begin(), two.end());
  const std::vector<TimedBytes> beams = head.receive(two, 5.0);
  ASSERT_EQ(beams.size(), 2U);
  const double listen_s = 100 * 104 * 640e-9;
  const double transfer_s = (100 + 45) * 10 / 115200.0;
  EXPECT_NEAR(beams[0].at_s, 5.0 + 25 * 10e-6 + listen_s + transfer_s, 1e-9);
  EXPECT_NEAR(beams[1].at_s - beams[0].at_s, 25 * 10e-6 + listen_s + transfer_s, 1e-9);
  const std::vector<seanet::Packet> packets = packetsOf(beams);
  const seanet::HeadDataReply first = seanet::decodeHeadData(packets[0], 1500.0);
  ASSERT_TRUE(first.beam) << first.problem;
  EXPECT_EQ(first.beam->intensities.size(), 100U);
  EXPECT_DOUBLE_EQ(first.beam->bearing_rad, 0.0);  // continuous: from ahead
  EXPECT_EQ(first.fields->device_type, 0x11);
  EXPECT_EQ(head.beamsSent(), 2U);
  EXPECT_EQ(head.dataRequests(), 3U);
  EXPECT_NE(head.settingsText().find("range 5.0 m (50 dm), 100 bins, ADInterval 104"), std::string::npos)
      << head.settingsText();
}

TEST(SeaNetEmulator, PacksFourBitBinsWhenAdc8IsOff) {
  SeaNetEmulator head = micron();
  seanet::HeadCommand command = defaultCommand();
  command.hd_ctrl &= static_cast<std::uint16_t>(~seanet::hdctrl::kAdc8On);
  head.receive(seanet::encodeHeadCommand(command), 0.0);
  const std::vector<seanet::Packet> packets = packetsOf(head.receive(seanet::encodeSendData(0), 0.1));
  ASSERT_EQ(packets.size(), 1U);
  EXPECT_EQ(packets[0].size(), 50U + 45U);
  const seanet::HeadDataReply reply = seanet::decodeHeadData(packets[0], 1500.0);
  ASSERT_TRUE(reply.beam);
  EXPECT_EQ(reply.beam->intensities.size(), 100U);
  for (const std::uint8_t value : reply.beam->intensities) EXPECT_EQ(value % 17, 0);
}

TEST(SeaNetEmulator, GainFoldsIntoTheEchoModel) {
  auto meanOf = [](std::uint8_t igain) {
    SeaNetEmulator head = micron();
    seanet::HeadCommand command = defaultCommand();
    command.igain[0] = command.igain[1] = igain;
    head.receive(seanet::encodeHeadCommand(command), 0.0);
    double sum = 0.0;
    for (int i = 0; i < 20; ++i) {
      const auto packets = packetsOf(head.receive(seanet::encodeSendData(0), 0.1 * i));
      const seanet::HeadDataReply reply = seanet::decodeHeadData(packets.at(0), 1500.0);
      for (const std::uint8_t v : reply.beam.value().intensities) sum += v;
    }
    return sum;
  };
  EXPECT_GT(meanOf(150), meanOf(84));
  EXPECT_GT(meanOf(84), meanOf(20));
}

TEST(SeaNetEmulator, IgnoresMalformedInput) {
  SeaNetEmulator head = micron();
  std::mt19937 random(5);
  for (int i = 0; i < 200; ++i) {
    std::vector<std::uint8_t> bytes(1 + random() % 80);
    for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(random());
    if (i % 3 == 0) bytes[0] = '@';
    EXPECT_NO_THROW(head.receive(bytes, 0.01 * i));
  }
  // A head command cut to 40 bytes of payload, one of 0 bins: ignored.
  head = micron();
  seanet::Packet cut = seanet::makePacket(MessageType::kHeadCommand, std::vector<std::uint8_t>(40, 7));
  EXPECT_TRUE(head.receive(seanet::encodePacket(cut), 3.0).empty());
  seanet::HeadCommand zero = defaultCommand();
  zero.nbins = 0;
  EXPECT_TRUE(head.receive(seanet::encodeHeadCommand(zero), 3.0).empty());
  seanet::HeadCommand huge = defaultCommand();
  huge.nbins = 2000;  // past rock's 1500
  EXPECT_TRUE(head.receive(seanet::encodeHeadCommand(huge), 3.0).empty());
  huge.nbins = 1500;
  huge.ad_interval = 65535;  // 47 km
  EXPECT_TRUE(head.receive(seanet::encodeHeadCommand(huge), 3.0).empty());
  EXPECT_FALSE(head.hasParameters());
  EXPECT_EQ(head.headCommands(), 0U);
  // A command for another node is not for this head.
  EXPECT_TRUE(head.receive(seanet::encodeHeadCommand(defaultCommand(), 5), 3.0).empty());
}

}  // namespace
}  // namespace sonarmap
