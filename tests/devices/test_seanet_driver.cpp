/// @file test_seanet_driver.cpp
/// SeaNetDriver against SeaNetEmulator in-process (seanet_bench.hpp): the conversation, the beams'
/// bearings for continuous and sector scans, the settings applied, recovery from a head that lost
/// its parameters and from a dropped reply, stop, and the settings refused.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "devices/seanet_bench.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

using seanet::MessageType;
using test::SeaNetBench;

constexpr double kDeg = std::numbers::pi / 180.0;

std::uint8_t type(MessageType t) { return static_cast<std::uint8_t>(t); }

SeaNetDriverOptions options(double range_m = 5.0, int bins = 100) {
  SeaNetDriverOptions o;
  o.settings.range_m = range_m;
  o.bins = bins;
  o.time_of_day_ms = [] { return 1000U; };
  return o;
}

/// Bearing in degrees, wrapped to (−180, 180].
double degrees(double bearing_rad) {
  double d = std::fmod(bearing_rad / kDeg, 360.0);
  if (d > 180.0 + 1e-9) d -= 360.0;
  return d;
}

TEST(SeaNetDriver, TalksToTheHeadAsTheDriversDo) {
  SeaNetBench bench("micron", options());
  bench.runUntil(10.0, [&] { return bench.beams.size() >= 3; });
  ASSERT_GE(bench.beams.size(), 3U);
  ASSERT_GE(bench.host_types.size(), 5U);
  EXPECT_EQ(bench.host_types[0], type(MessageType::kReBoot));
  EXPECT_EQ(bench.host_types[1], type(MessageType::kSendVersion));
  EXPECT_EQ(bench.host_types[2], type(MessageType::kSendBBUser));
  EXPECT_EQ(bench.host_types[3], type(MessageType::kHeadCommand));
  EXPECT_EQ(bench.host_types[4], type(MessageType::kSendData));
  EXPECT_TRUE(bench.driver.heard());
  EXPECT_TRUE(bench.driver.scanning());
  EXPECT_EQ(bench.driver.headCommandsSent(), 1);
  EXPECT_EQ(bench.driver.device(), "Tritech SeaNet head, node 2, serial 1001, CPU code 0x03 (675 kHz), program 65536 bytes");
  // The head's first mtAlive comes 1 s after mtReBoot; the rest follows within a few packets.
  EXPECT_GT(bench.beam_times_s[0], 1.0);
  EXPECT_LT(bench.beam_times_s[0], 1.2);
  // One request in flight: requests = beams + the one outstanding.
  EXPECT_EQ(bench.emulator.dataRequests(), bench.beams.size() + 1);
}

TEST(SeaNetDriver, ContinuousScanStepsClockwiseFromAhead) {
  SeaNetDriverOptions o = options();
  o.settings.step_rad = 3.6 * kDeg;
  SeaNetBench bench("micron", o);
  bench.runUntil(30.0, [&] { return bench.beams.size() >= 110; });
  ASSERT_GE(bench.beams.size(), 110U);
  for (std::size_t i = 0; i < 110; ++i) {
    const double expected = std::fmod(3.6 * static_cast<double>(i), 360.0);
    EXPECT_NEAR(bench.beams[i].bearing_rad / kDeg, expected, 1e-6) << "beam " << i;
    EXPECT_EQ(bench.beams[i].intensities.size(), 100U);
    EXPECT_NEAR(bench.beams[i].bin_length_m, 5.0 / 100, 0.0005);
  }
  EXPECT_EQ(bench.driver.applied().value("step_deg"), "3.6");
  EXPECT_EQ(bench.driver.applied().value("scan"), "continuous");
  // The beams come one per reply: listening 6.7 ms + 145 bytes at 115,200 Bd + 0.25 ms motor.
  const double period_s = (bench.beam_times_s[100] - bench.beam_times_s[0]) / 100.0;
  EXPECT_GT(period_s, 0.018);
  EXPECT_LT(period_s, 0.035);  // the bench's 10 ms clock steps add up to one step a beam
}

TEST(SeaNetDriver, SectorScanGoesBackAndForthBetweenTheLimits) {
  SeaNetDriverOptions o = options();
  o.settings.sector_width_rad = 90.0 * kDeg;
  o.settings.sector_center_rad = 0.0;
  o.settings.step_rad = 9.0 * kDeg;  // 160 × 1/16 gradian
  SeaNetBench bench("micron", o);
  bench.runUntil(20.0, [&] { return bench.beams.size() >= 33; });
  ASSERT_GE(bench.beams.size(), 33U);
  // 11 beams a pass, −45° … 45°, then back, pinging at each limit and again there.
  for (std::size_t i = 0; i < 33; ++i) {
    const std::size_t pass = i / 11;
    const std::size_t along = i % 11;
    const double expected = -45.0 + 9.0 * static_cast<double>(pass % 2 == 0 ? along : 10 - along);
    EXPECT_NEAR(degrees(bench.beams[i].bearing_rad), expected, 1e-6) << "beam " << i;
  }
  const AppliedSettings applied = bench.driver.applied();
  EXPECT_EQ(applied.value("scan"), "sector");
  EXPECT_EQ(applied.value("left_limit_grad16"), "2400");
  EXPECT_EQ(applied.value("right_limit_grad16"), "4000");
  EXPECT_EQ(applied.value("sector_width_deg"), "90");
  EXPECT_EQ(applied.value("sector_center_deg"), "0");
}

TEST(SeaNetDriver, SettingsReachTheHead) {
  SeaNetDriverOptions o = options(20.0, 250);
  o.settings.gain = "55%";
  o.settings.step_rad = 1.0 * kDeg;  // → 18 × 1/16 gradian = 1.0125°
  SeaNetBench bench("seaking-30", o);
  bench.runUntil(10.0, [&] { return bench.beams.size() >= 2; });
  ASSERT_GE(bench.beams.size(), 2U);
  const AppliedSettings a = bench.driver.applied();
  EXPECT_EQ(a.value("range_m"), "20");
  EXPECT_EQ(a.value("bins"), "250");
  EXPECT_EQ(a.value("gain"), "55%");
  EXPECT_EQ(a.value("igain"), "116/210");  // round(55 × 2.1) = 115.5 → 116
  EXPECT_EQ(a.value("step_grad16"), "18");
  EXPECT_EQ(a.value("step_deg"), "1.0125");
  EXPECT_EQ(a.value("ad_interval_ns"), "106880");  // round(2 · 20 / (1500 · 250) / 640 ns) = 167
  EXPECT_EQ(a.value("frequency_khz"), "325");
  EXPECT_TRUE(bench.sawNote("step 1° rounded to 18 × 1/16 gradian = 1.0125°"));
  EXPECT_EQ(bench.beams[0].intensities.size(), 250U);
  EXPECT_EQ(bench.beams[0].gain_setting, 116);
  EXPECT_NEAR(bench.beams[1].bearing_rad - bench.beams[0].bearing_rad, 18 * 2 * std::numbers::pi / 6400, 1e-9);
  const std::string head = bench.emulator.settingsText();
  EXPECT_NE(head.find("250 bins, ADInterval 167"), std::string::npos) << head;
  EXPECT_NE(head.find("IGain 116, ADSpan 149, ADLow 14"), std::string::npos) << head;
}

/// The mtHeadCommand RobDos/Tritech-Micron-Driver (commit c55d7470c38b21fe1d9d1ee86a7e9925c5d62649)
/// sent with its shipped configuration (config/tritech_micron_config.yaml: 200 bins, 5 m, 1500 m/s,
/// step 32, limits 6399 and 6399) to the emulator over a pty: its TritechMicronDriver built in /tmp
/// with ros/ros.h stubbed, run against sonarmap_seanet_pty_head, the bytes as that program printed
/// them.
const char* const kRobDosPtyHeadCommand =
    "40303034434c00ff02471380021d0123029999990266666605a3703d06703d0a0928003200ff18ff18510854545a007d0019203400"
    "c800e803970340060100000050510908545400005a007d00000000000a";

TEST(SeaNetDriver, HeadCommandAgreesWithRobDosForTheSameSettings) {
  seanet::PacketParser parser;
  std::vector<std::uint8_t> robdos_bytes;
  for (std::size_t i = 0; kRobDosPtyHeadCommand[i] != 0; i += 2) {
    robdos_bytes.push_back(static_cast<std::uint8_t>(std::stoi(std::string(kRobDosPtyHeadCommand + i, 2), nullptr, 16)));
  }
  const auto robdos = seanet::decodeHeadCommand(parser.feed(robdos_bytes).at(0));
  ASSERT_TRUE(robdos);
  SeaNetDriverOptions o = options(5.0, 200);
  o.settings.step_rad = 1.8 * kDeg;
  SeaNetBench bench("micron", o);
  bench.runUntil(5.0, [&] { return bench.emulator.hasParameters(); });
  EXPECT_EQ(seanet::encodeHeadCommand(*robdos), robdos_bytes);
  // Field by field against the driver's command, as the emulator reports it applied and as the
  // driver lists it.
  EXPECT_NE(bench.emulator.settingsText().find("range 5.0 m (50 dm), 200 bins, ADInterval 52"), std::string::npos)
      << bench.emulator.settingsText();
  EXPECT_EQ(robdos->range_scale_dm, 50);
  EXPECT_EQ(robdos->nbins, 200);
  EXPECT_EQ(robdos->ad_interval, 52);  // the rule the driver uses (mcgill would send 53)
  EXPECT_EQ(bench.driver.applied().value("ad_interval_ns"), "33280");  // 52 × 640 ns
  EXPECT_EQ(robdos->step, 32);
  EXPECT_EQ(bench.driver.applied().value("step_grad16"), "32");
  // What the driver sends alike: V3B block, head type 2, TxN/RxN of 325 and 675 kHz, slopes 90
  // and 125, MoTime 25, MaxADBuf 1000, MinorAxisDir 1600, MajorAxisPan 1.
  EXPECT_TRUE(robdos->v3b);
  EXPECT_EQ(robdos->head_type, 2);
  EXPECT_EQ(robdos->tx_n[0], seanet::frequencyWord(325e3));
  EXPECT_EQ(robdos->rx_n[1], seanet::frequencyWord(1130e3));
  EXPECT_EQ(robdos->slope[0], 90);
  EXPECT_EQ(robdos->slope[1], 125);
  EXPECT_EQ(robdos->mo_time, 25);
  EXPECT_EQ(robdos->max_ad_buf, 1000);
  EXPECT_EQ(robdos->minor_axis_dir, 1600);
  EXPECT_EQ(robdos->major_axis_pan, 1);
  // Where they differ by choice (seanet_driver.hpp): RobDos asks a full turn with LeftLim =
  // RightLim and no cont bit, the driver with cont and scanright; ADSpan 81 / ADLow 8 against the
  // V4LOG's 149 / 14; IGain 84 (40%) alike.
  EXPECT_EQ(robdos->hd_ctrl, 0x2301);
  EXPECT_EQ(robdos->left_limit, robdos->right_limit);
  EXPECT_EQ(robdos->igain[0], 84);
  EXPECT_EQ(bench.driver.applied().value("igain"), "84/210");
}

TEST(SeaNetDriver, FrequencyChoosesTheNearestChannelOfATwoChannelHead) {
  SeaNetDriverOptions o = options();
  o.settings.frequency_khz = 700.0;
  SeaNetBench seaking("seaking-30", o);
  seaking.runUntil(5.0, [&] { return seaking.beams.size() >= 1; });
  EXPECT_EQ(seaking.driver.applied().value("frequency_khz"), "675");
  EXPECT_EQ(seaking.driver.applied().value("channel"), "2");
  EXPECT_NE(seaking.emulator.settingsText().find("channel 2"), std::string::npos);
  // A single-channel head keeps its frequency and says so.
  o.settings.frequency_khz = 325.0;
  SeaNetBench micron("micron", o);
  micron.runUntil(5.0, [&] { return micron.beams.size() >= 1; });
  EXPECT_EQ(micron.driver.applied().value("frequency_khz"), "675");
  EXPECT_EQ(micron.driver.applied().value("channel"), "1");
  EXPECT_TRUE(micron.sawNote("frequency 325 kHz ignored: the head has one channel, at 675 kHz"));
}

TEST(SeaNetDriver, AHeadThatLostItsParametersGetsTheCommandAgain) {
  SeaNetBench bench("micron", options());
  bench.runUntil(10.0, [&] { return bench.beams.size() >= 5; });
  ASSERT_EQ(bench.driver.headCommandsSent(), 1);
  // The head reboots by itself (a power dip): it forgets its parameters.
  bench.emulator.receive(seanet::encodeSimpleCommand(MessageType::kReBoot), bench.now_s);
  ASSERT_FALSE(bench.emulator.hasParameters());
  const std::size_t before = bench.beams.size();
  bench.runUntil(bench.now_s + 10.0, [&] { return bench.beams.size() >= before + 5; });
  EXPECT_EQ(bench.driver.headCommandsSent(), 2);
  EXPECT_TRUE(bench.emulator.hasParameters());
  EXPECT_GE(bench.beams.size(), before + 5);
  EXPECT_TRUE(bench.sawNote("the head reports no parameters"));
}

TEST(SeaNetDriver, ADroppedReplyIsAskedForAgain) {
  SeaNetBench bench("micron", options());
  int head_data = 0;
  bench.drop = [&](const seanet::Packet& p) {
    return p.type == type(MessageType::kHeadData) && ++head_data == 3;  // the third beam is lost
  };
  bench.runUntil(20.0, [&] { return bench.beams.size() >= 6; });
  EXPECT_EQ(bench.dropped, 1U);
  EXPECT_GE(bench.beams.size(), 6U);
  EXPECT_TRUE(bench.sawNote("mtHeadData overdue: mtSendData repeated"));
  EXPECT_EQ(bench.driver.headCommandsSent(), 1);
  // The lost beam's bearing is skipped (the head stepped), the rest follow on.
  EXPECT_NEAR(bench.beams[2].bearing_rad - bench.beams[1].bearing_rad, 2 * 1.8 * kDeg, 1e-9);
}

TEST(SeaNetDriver, UnansweredQuestionsAreRepeated) {
  SeaNetBench bench("micron", options());
  bench.drop = [&](const seanet::Packet& p) {
    return p.type == type(MessageType::kVersionData) && bench.now_s < 2.0;  // the first answers are lost
  };
  bench.runUntil(10.0, [&] { return bench.beams.size() >= 1; });
  EXPECT_GE(bench.dropped, 1U);
  std::size_t versions = 0;
  for (const std::uint8_t t : bench.host_types) versions += t == type(MessageType::kSendVersion);
  EXPECT_GE(versions, 2U);
  EXPECT_EQ(bench.beams.size(), 1U);
}

TEST(SeaNetDriver, IgnoresItsOwnCommandsEchoedOnTheLine) {
  SeaNetDriver driver(options());
  const DriverOutput first = driver.start(0.0);
  // A half-duplex line hands the host its own mtReBoot back: not the head's mtAlive.
  const DriverOutput echoed = driver.receive(first.send, 0.1);
  EXPECT_TRUE(echoed.send.empty());
  EXPECT_FALSE(driver.heard());
  seanet::AliveInfo alive;
  alive.head_info = seanet::AliveInfo::kNoParams;
  const DriverOutput next = driver.receive(seanet::encodeAlive(alive), 0.2);
  EXPECT_TRUE(driver.heard());
  EXPECT_EQ(next.send, seanet::encodeSimpleCommand(MessageType::kSendVersion));
}

TEST(SeaNetDriver, StopRebootsTheHeadAndFallsSilent) {
  SeaNetBench bench("micron", options());
  bench.runUntil(10.0, [&] { return bench.beams.size() >= 2; });
  const std::vector<std::uint8_t> stop = bench.driver.stop();
  EXPECT_EQ(stop, seanet::encodeSimpleCommand(MessageType::kReBoot));
  bench.emulator.receive(stop, bench.now_s);
  const std::size_t sent = bench.host_types.size();
  bench.runUntil(bench.now_s + 5.0);
  EXPECT_EQ(bench.host_types.size(), sent);
  EXPECT_FALSE(bench.emulator.hasParameters());
}

TEST(SeaNetDriver, BadSettingsAreRefusedNamingTheOption) {
  auto refused = [](SeaNetDriverOptions o, const std::string& text) {
    try {
      SeaNetDriver driver(std::move(o));
      ADD_FAILURE() << "accepted, expected an error with '" << text << "'";
    } catch (const ValueError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  SeaNetDriverOptions o = options();
  o.settings.range_m = -1.0;
  refused(o, "range -1 m is out of range; expected 0.1 to 1638.3 m");
  o = options();
  o.settings.gain = "loud";
  refused(o, "gain 'loud' is not a percentage; expected 0 to 100");
  o.settings.gain = "120%";
  refused(o, "gain '120%'");
  o = options();
  o.settings.step_rad = 20.0 * kDeg;
  refused(o, "step 20° is out of range; expected 0.05625° to 14.34°");
  o.settings.step_rad = 0.0;
  refused(o, "step 0° is out of range");
  o = options();
  o.settings.sector_width_rad = 1.0 * kDeg;
  refused(o, "sector width 1.0125° holds no step of 1.8°");
  o = options();
  o.bins = 2000;
  refused(o, "bins 2000 is out of range; expected 1 to 1500");
  o = options(0.5, 1500);
  refused(o, "gives ADInterval 0.694444 × 640 ns; expected 5 to 65535");
  o = options();
  o.settings.sound_speed_m_s = 0.0;
  refused(o, "sound_speed_m_s 0 is out of range; expected 1000 to 2000 m/s");
  o = options();
  o.settings.frequency_khz = -5.0;
  refused(o, "frequency -5 kHz is out of range");
  EXPECT_NO_THROW(SeaNetDriver{options()});
  o = options();
  o.settings.gain = " 40 % ";
  EXPECT_EQ(SeaNetDriver(o).applied().value("gain"), "40%");
}

}  // namespace
}  // namespace sonarmap
