/// @file test_seanet_protocol.cpp
/// The SeaNet protocol (seanet_protocol.hpp): the host's commands byte for byte as open drivers
/// send them, the head's replies round trip, the parser on chunks and noise.
///
/// Where the expected bytes come from:
///  - mcgill-robotics/ros-tritech-micron at commit 4722dd60d5bea2131f844ec26635a5f2c38b1442: its
///    own code (`src/tritech_micron/sonar.py`, `commands.py`) run under Python 2.7.18 with Debian's
///    python3-bitstring 3.1.7 and python3-serial 3.5 on the path and rospy, tf and the ROS message
///    modules stubbed (in /tmp, not kept): TritechMicron's `send()`, `__set_parameters(force=True)`
///    with its defaults and with continuous=False, range=5, nbins=200, step=MEDIUM, gain=0.4,
///    limits 2400 and 4000, and `_ping()` at 12:34:56.789; the printed hex is below.
///  - RobDos/Tritech-Micron-Driver at commit c55d7470c38b21fe1d9d1ee86a7e9925c5d62649
///    (`include/micron_driver_ros/message_types.h`): its byte arrays mtRebootMsg,
///    mtSendVersionMsg, mtSendBBUserMsg, mtSendDataMsg and the mtHeadCommand template of
///    mtHeadCommandMsg::construct() (a SeaNet Pro command) filled as construct() fills it for its
///    defaults (200 bins, 10 m, 1500 m/s, step 32, limits 1 and 6399), copied as data.
///  - rock-drivers/drivers-sonar_tritech at commit 8c33dca1c98d0809e9040cfcaf74b7dd6a288d00: not
///    run (it needs Rock's iodrivers_base); its createPaket and SeaNetProfiling's TxN/RxN formula
///    were read and give the same header bytes and frequency words.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"
#include "sonarmap/formats/wire_encoder.hpp"

namespace sonarmap::seanet {
namespace {

std::vector<std::uint8_t> fromHex(const std::string& hex) {
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) bytes.push_back(static_cast<std::uint8_t>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  return bytes;
}

// mcgill tritech_micron, run as the file's comment says.
const std::string kMcgillReboot = "40303030380800ff02031080020a";
const std::string kMcgillSendVersion = "40303030380800ff02031780020a";
const std::string kMcgillSendBBUser = "40303030380800ff02031880020a";
const std::string kMcgillSendData = "40303030430c00ff02071980028029b3020a";  // 12:34:56 → 45,296,000 ms
const std::string kMcgillHeadCommandDefault =
    "40303033433c00ff023713800201072311000000000000000000000000000000000000640060099f0fff00696900000000192035009001"
    "f40164004006010000000a";
const std::string kMcgillHeadCommandSector =
    "40303033433c00ff023713800201052311000000000000000000000000000000000000320060099f0fff0054540000000019103500c800"
    "f40164004006010000000a";

// RobDos message_types.h.
const std::vector<std::uint8_t> kRobDosReboot = {0x40, 0x30, 0x30, 0x30, 0x38, 0x08, 0x00, 0xFF, 0x02, 0x03, 0x10, 0x80, 0x02, 0x0A};
const std::vector<std::uint8_t> kRobDosSendVersion = {0x40, 0x30, 0x30, 0x30, 0x38, 0x08, 0x00, 0xFF, 0x02, 0x03, 0x17, 0x80, 0x02, 0x0A};
const std::vector<std::uint8_t> kRobDosSendBBUser = {0x40, 0x30, 0x30, 0x30, 0x38, 0x08, 0x00, 0xFF, 0x02, 0x03, 0x18, 0x80, 0x02, 0x0A};
const std::vector<std::uint8_t> kRobDosSendData = {0x40, 0x30, 0x30, 0x30, 0x43, 0x0C, 0x00, 0xFF, 0x02,
                                                   0x07, 0x19, 0x80, 0x02, 0x00, 0x00, 0x00, 0x00, 0x0A};
/// The template with construct()'s defaults written in: range 100 dm (bytes 35–36), limits 1 and
/// 6399 (37–40), step 32 (50), ADInterval 104 (51–52), 200 bins (53–54).
const std::vector<std::uint8_t> kRobDosHeadCommand = {
    0x40, 0x30, 0x30, 0x34, 0x43, 0x4C, 0x00, 0xFF, 0x02, 0x47, 0x13, 0x80, 0x02, 0x1D, 0x01, 0x23, 0x02,
    0x99, 0x99, 0x99, 0x02, 0x66, 0x66, 0x66, 0x05, 0xA3, 0x70, 0x3D, 0x06, 0x70, 0x3D, 0x0A, 0x09, 0x28,
    0x00, 0x64, 0x00, 0x01, 0x00, 0xFF, 0x18, 0x51, 0x08, 0x54, 0x54, 0x5A, 0x00, 0x7D, 0x00, 0x19, 0x20,
    0x68, 0x00, 0xC8, 0x00, 0xE8, 0x03, 0x97, 0x03, 0x40, 0x06, 0x01, 0x00, 0x00, 0x00, 0x50, 0x51, 0x09,
    0x08, 0x54, 0x54, 0x00, 0x00, 0x5A, 0x00, 0x7D, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0A};

/// mcgill's command fields: no V3B block, head type 0x11 (DST), TxN/RxN and TxPulseLen 0, ADSpan
/// 255 and ADLow 0 (0…80 dB), slope 0, MoTime 25, MaxADBuf 500, Lockout 100.
HeadCommand mcgillCommand(std::uint16_t hd_ctrl, std::uint16_t range_dm, std::uint8_t gain, std::uint8_t step,
                          std::uint16_t nbins) {
  HeadCommand c;
  c.v3b = false;
  c.hd_ctrl = hd_ctrl;
  c.head_type = 0x11;
  c.range_scale_dm = range_dm;
  c.left_limit = 2400;
  c.right_limit = 3999;  // mcgill truncates to_sonar_angles(to_radians(4000)) to 3999
  c.ad_span = 255;
  c.ad_low = 0;
  c.igain[0] = c.igain[1] = gain;
  c.mo_time = 25;
  c.step = step;
  c.ad_interval = 53;  // mcgill: 2·R/c/bins/640 ns = 52.08, made even upwards
  c.nbins = nbins;
  c.max_ad_buf = 500;
  c.lockout = 100;
  c.minor_axis_dir = 1600;
  c.major_axis_pan = 1;
  return c;
}

TEST(SeaNetProtocol, SimpleCommandsAreTheDriversBytes) {
  EXPECT_EQ(encodeSimpleCommand(MessageType::kReBoot), fromHex(kMcgillReboot));
  EXPECT_EQ(encodeSimpleCommand(MessageType::kReBoot), kRobDosReboot);
  EXPECT_EQ(encodeSimpleCommand(MessageType::kSendVersion), fromHex(kMcgillSendVersion));
  EXPECT_EQ(encodeSimpleCommand(MessageType::kSendVersion), kRobDosSendVersion);
  EXPECT_EQ(encodeSimpleCommand(MessageType::kSendBBUser), fromHex(kMcgillSendBBUser));
  EXPECT_EQ(encodeSimpleCommand(MessageType::kSendBBUser), kRobDosSendBBUser);
  // mtStopAlives: type 66 in the same frame.
  EXPECT_EQ(encodeSimpleCommand(MessageType::kStopAlive),
            std::vector<std::uint8_t>({0x40, 0x30, 0x30, 0x30, 0x38, 0x08, 0x00, 0xFF, 0x02, 0x03, 0x42, 0x80, 0x02, 0x0A}));
}

TEST(SeaNetProtocol, SendDataCarriesTheTimeOfDay) {
  EXPECT_EQ(encodeSendData(45'296'000), fromHex(kMcgillSendData));
  EXPECT_EQ(encodeSendData(0), kRobDosSendData);
  PacketParser parser;
  const std::vector<Packet> packets = parser.feed(fromHex(kMcgillSendData));
  ASSERT_EQ(packets.size(), 1U);
  EXPECT_EQ(decodeSendData(packets[0]), 45'296'000U);
}

TEST(SeaNetProtocol, HeadCommandWithoutV3BIsMcgillsBytes) {
  EXPECT_EQ(encodeHeadCommand(mcgillCommand(0x2307, 100, 105, 32, 400)), fromHex(kMcgillHeadCommandDefault));
  EXPECT_EQ(encodeHeadCommand(mcgillCommand(0x2305, 50, 84, 16, 200)), fromHex(kMcgillHeadCommandSector));
}

TEST(SeaNetProtocol, HeadCommandWithV3BRoundTripsRobDosTemplate) {
  PacketParser parser;
  const std::vector<Packet> packets = parser.feed(kRobDosHeadCommand);
  ASSERT_EQ(packets.size(), 1U);
  const std::optional<HeadCommand> command = decodeHeadCommand(packets[0]);
  ASSERT_TRUE(command);
  EXPECT_TRUE(command->v3b);
  EXPECT_EQ(command->hd_ctrl, 0x2301);
  EXPECT_EQ(command->head_type, 2);
  EXPECT_EQ(command->range_scale_dm, 100);
  EXPECT_EQ(command->left_limit, 1);
  EXPECT_EQ(command->right_limit, 6399);
  EXPECT_EQ(command->ad_span, 81);
  EXPECT_EQ(command->ad_low, 8);
  EXPECT_EQ(command->igain[0], 84);
  EXPECT_EQ(command->mo_time, 25);
  EXPECT_EQ(command->step, 32);
  EXPECT_EQ(command->ad_interval, 104);
  EXPECT_EQ(command->nbins, 200);
  EXPECT_EQ(command->max_ad_buf, 1000);
  EXPECT_EQ(command->minor_axis_dir, 1600);
  EXPECT_EQ(command->ad_span_ch[0], 80);
  EXPECT_EQ(command->slope_ch[1], 125);
  // SeaNet Pro's frequency words: 325 and 675 kHz, receivers 455 kHz above (rock's formula).
  EXPECT_EQ(command->tx_n[0], frequencyWord(325e3));
  EXPECT_EQ(command->tx_n[1], frequencyWord(675e3));
  EXPECT_EQ(command->rx_n[0], frequencyWord(780e3));
  EXPECT_EQ(command->rx_n[1], frequencyWord(1130e3));
  EXPECT_NEAR(frequencyOfWord(command->tx_n[0]), 325e3, 1.0);
  EXPECT_EQ(encodeHeadCommand(*command), kRobDosHeadCommand);
}

TEST(SeaNetProtocol, RepliesRoundTrip) {
  AliveInfo alive;
  alive.head_time_ms = 123456;
  alive.motor_position = 3200;
  alive.head_info = AliveInfo::kNoParams | AliveInfo::kCentred;
  VersionInfo version;
  version.frequency_code = 3;
  version.serial_number = 1001;
  version.program_length = 70000;
  BBUserInfo user;
  user.dual_synth = true;
  user.has_motor = true;
  std::vector<std::uint8_t> stream = encodeAlive(alive);
  const std::vector<std::uint8_t> v = encodeVersionData(version);
  const std::vector<std::uint8_t> u = encodeBBUserData(user);
  EXPECT_EQ(stream.size(), 22U);  // rock's sizes
  EXPECT_EQ(v.size(), 25U);
  EXPECT_EQ(u.size(), 264U);
  stream.insert(stream.end(), v.begin(), v.end());
  stream.insert(stream.end(), u.begin(), u.end());
  PacketParser parser;
  const std::vector<Packet> packets = parser.feed(stream);
  ASSERT_EQ(packets.size(), 3U);
  EXPECT_EQ(packets[0].tx_node, kSonarNode);
  EXPECT_EQ(packets[0].rx_node, kHostNode);
  EXPECT_EQ(packets[0].byte_count, 22 - 6 - 5);  // mcgill's check: length − 5
  const auto a = decodeAlive(packets[0]);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->head_time_ms, 123456U);
  EXPECT_EQ(a->motor_position, 3200);
  EXPECT_TRUE(a->has(AliveInfo::kNoParams));
  EXPECT_FALSE(a->has(AliveInfo::kSentConfig));
  EXPECT_EQ(a->describe(), "centred, no params");
  const auto vv = decodeVersionData(packets[1]);
  ASSERT_TRUE(vv);
  EXPECT_EQ(vv->serial_number, 1001);
  EXPECT_EQ(vv->program_length, 70000U);
  EXPECT_EQ(vv->frequencyKhz(), 675.0);
  const auto uu = decodeBBUserData(packets[2]);
  ASSERT_TRUE(uu);
  EXPECT_TRUE(uu->long_layout);
  EXPECT_TRUE(uu->dual_synth);
  EXPECT_TRUE(uu->has_motor);
  EXPECT_EQ(uu->full_duplex, true);
  EXPECT_FALSE(decodeAlive(packets[1]));
  EXPECT_FALSE(decodeVersionData(packets[0]));
}

TEST(SeaNetProtocol, HeadDataGoesThroughTheOneDecoder) {
  HeadDataFields fields;
  fields.ad_interval = 33;
  fields.bearing = 3200 + 1600;  // 90° clockwise from ahead
  fields.ad_span = 149;
  fields.gain = 84;
  const std::vector<std::uint8_t> data = {0, 10, 200, 255};
  PacketParser parser;
  const std::vector<Packet> packets = parser.feed(encodeHeadData(fields, data));
  ASSERT_EQ(packets.size(), 1U);
  EXPECT_EQ(packets[0].size(), data.size() + 45);
  const HeadDataReply reply = decodeHeadData(packets[0], 1500.0);
  ASSERT_TRUE(reply.beam) << reply.problem;
  EXPECT_NEAR(reply.beam->bearing_rad, 3.14159265358979 / 2, 1e-9);
  EXPECT_NEAR(reply.beam->bin_length_m, 33 * 640e-9 * 1500 / 2, 1e-12);
  EXPECT_EQ(reply.beam->intensities, data);
  ASSERT_TRUE(reply.fields);
  EXPECT_EQ(reply.fields->bearing, 4800);
  EXPECT_EQ(reply.fields->gain, 84);
  // The capture encoder writes the same packets.
  Beam beam = *reply.beam;
  EXPECT_EQ(encodeSeaNetCapture({beam}).size(), data.size() + 45);
  const HeadDataReply empty = decodeHeadData(parser.feed(encodeHeadData(fields, {}))[0], 1500.0);
  EXPECT_FALSE(empty.beam);
  EXPECT_EQ(empty.problem, "mtHeadData with no data bytes");
}

TEST(SeaNetProtocol, ParserTakesAnyChunksAndSkipsNoise) {
  std::vector<std::uint8_t> stream = {'x', '@', 'Z', 0x0A};  // noise, a false start
  const std::vector<std::uint8_t> reboot = encodeSimpleCommand(MessageType::kReBoot);
  const std::vector<std::uint8_t> data = encodeSendData(7);
  for (int i = 0; i < 20; ++i) {
    stream.insert(stream.end(), reboot.begin(), reboot.end());
    stream.insert(stream.end(), data.begin(), data.end());
    if (i % 5 == 0) stream.insert(stream.end(), {'@', '0', '0'});  // a packet cut by a bad byte
  }
  std::mt19937 random(3);
  for (int trial = 0; trial < 20; ++trial) {
    PacketParser parser;
    std::vector<Packet> packets;
    std::size_t at = 0;
    while (at < stream.size()) {
      const std::size_t chunk = std::min<std::size_t>(stream.size() - at, 1 + random() % 30);
      for (Packet& p : parser.feed(std::span(stream).subspan(at, chunk))) packets.push_back(std::move(p));
      at += chunk;
    }
    ASSERT_EQ(packets.size(), 40U);
    EXPECT_EQ(packets[0].type, static_cast<std::uint8_t>(MessageType::kReBoot));
    EXPECT_EQ(packets[0].offset, 4U);
    EXPECT_EQ(decodeSendData(packets[39]), 7U);
    EXPECT_GE(parser.skippedRuns(), 1U);
    EXPECT_FALSE(parser.takeSkipped().empty());
    EXPECT_TRUE(parser.takeSkipped().empty());
  }
}

TEST(SeaNetProtocol, ParserNeverThrowsOnRandomBytes) {
  std::mt19937 random(11);
  PacketParser parser;
  for (int i = 0; i < 200; ++i) {
    std::vector<std::uint8_t> bytes(1 + random() % 64);
    for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(random() % 4 == 0 ? "@0123456789ABCDEF\n"[random() % 18] : random());
    EXPECT_NO_THROW(parser.feed(bytes));
  }
  EXPECT_EQ(parser.bytesFed() > 0, true);
}

TEST(SeaNetProtocol, EncoderRefusesOversizedPayloads) {
  Packet packet;
  packet.payload.resize(kMaxPayloadBytes + 1);
  EXPECT_THROW(encodePacket(packet), ValueError);
  EXPECT_THROW(encodeHeadData({}, std::vector<std::uint8_t>(65001)), ValueError);
  EXPECT_EQ(messageTypeName(4), "mtAlive");
  EXPECT_EQ(messageTypeName(77), "message type 77");
}

}  // namespace
}  // namespace sonarmap::seanet
