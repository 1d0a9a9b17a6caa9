// Ping360Driver against Ping360Emulator in-process (ping360_bench.hpp, no I/O): the identity asked
// as ping-python asks it, beams at the angles of full turns and of a sector scanned back and
// forth, the settings applied, a command repeated after its reply was lost, nacks as notes,
// motor_off on stop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "devices/ping360_bench.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

namespace pp = ping_protocol;
using test::hexBytes;
using test::Ping360Bench;

constexpr double kGradian = std::numbers::pi / 200.0;

int gradiansOf(const Beam& beam) { return static_cast<int>(std::lround(beam.bearing_rad / kGradian)); }

bool hasNote(const std::vector<std::string>& notes, const std::string& words) {
  return std::any_of(notes.begin(), notes.end(), [&](const std::string& note) { return note.find(words) != std::string::npos; });
}

TEST(devicesPing360Driver, AsksForTheIdentityThenPingsAtTheFirstAngle) {
  HeadSettings settings;
  settings.sector_center_rad = 133 * kGradian;  // full turns from 133 grad
  Ping360Driver driver(settings);
  const DriverOutput first = driver.start(0.0);
  // ping-python's general_request(protocol_version) and general_request(device_information) bytes
  // (tests/formats/test_ping_protocol.cpp says how they were made).
  EXPECT_EQ(first.send, hexBytes("42520200060000000500a100" "42520200060000000400a000"));
  EXPECT_FALSE(driver.heard());
  // Unanswered, the requests are repeated every 0.5 s.
  EXPECT_TRUE(driver.poll(0.4).send.empty());
  const DriverOutput again = driver.poll(0.5);
  EXPECT_EQ(again.send, first.send);
  ASSERT_EQ(again.notes.size(), 1u);
  EXPECT_EQ(again.notes[0], "no device_information from the Ping360 after 1 request: asking again");

  const DriverOutput found = driver.receive(pp::encode(pp::DeviceInformation{2, 67, 3, 1, 1, 0}, 2, 0), 0.6);
  EXPECT_TRUE(driver.heard());
  EXPECT_EQ(driver.device(), "Ping360 (firmware 3.1.1)");
  EXPECT_TRUE(hasNote(found.notes, "found Ping360 (firmware 3.1.1)"));
  // The first transducer command at the default settings (20 m, normal gain, 750 kHz), as
  // ping-python packs transducer(mode=1, gain_setting=1, angle=133, transmit_duration=107,
  // sample_period=888, transmit_frequency=750, number_of_samples=1200, transmit=1, reserved=0).
  EXPECT_EQ(found.send, hexBytes("42520e00290a0000010185006b007803ee02b0040100e703"));
}

TEST(devicesPing360Driver, FullTurnsAgainstTheEmulator) {
  Ping360Bench bench(HeadSettings{}, test::tankPing360());
  bench.start();
  bench.runUntilBeams(420, 120.0);
  ASSERT_EQ(bench.beams().size(), 420u);
  for (std::size_t i = 0; i < bench.beams().size(); ++i) {
    const Beam& beam = bench.beams()[i];
    ASSERT_EQ(gradiansOf(beam), static_cast<int>(i % 400)) << i;
    ASSERT_EQ(beam.intensities.size(), 1200u);
    EXPECT_DOUBLE_EQ(beam.bin_length_m, 888 * 25e-9 * 1500.0 / 2.0);
    EXPECT_EQ(beam.gain_setting, 1);
    EXPECT_DOUBLE_EQ(*beam.pulse_length_m, 107e-6 * 1500.0 / 2.0);
  }
  EXPECT_EQ(bench.driver().device(), "Ping360 (firmware 3.3.1)");
  EXPECT_EQ(bench.driver().repeats(), 0u);
  // The next command went out with the last beam: its ping is under way.
  EXPECT_EQ(bench.emulator().beamsSent(), 421u);
  // A ping every 6 ms (1 gradian) + 26.6 ms (listening) + 106 ms (1224 bytes at 115,200 Bd).
  const double period_s = (bench.beamTimes().back() - bench.beamTimes()[20]) / 399.0;
  EXPECT_NEAR(period_s, 0.006 + 1200 * 888 * 25e-9 + 1224 * 10.0 / 115200.0, 1e-3);
  const AppliedSettings applied = bench.driver().applied();
  EXPECT_EQ(applied.value("range_m"), "19.98");
  EXPECT_EQ(applied.value("gain"), "normal");
  EXPECT_EQ(applied.value("transmit_duration_us"), "107");
  EXPECT_EQ(applied.value("samples"), "1200");
  EXPECT_EQ(bench.emulator().state().angle_grad, 20);  // the ping under way, 420 mod 400
}

TEST(devicesPing360Driver, ASectorBackAndForthWithItsSettings) {
  HeadSettings settings;
  settings.range_m = 5.0;
  settings.gain = "low";
  settings.sector_width_rad = 18.0 * std::numbers::pi / 180.0;  // 20 gradians
  settings.sector_center_rad = 0.0;
  settings.step_rad = 2 * kGradian;
  settings.frequency_khz = 800.0;
  Ping360Bench bench(settings, test::tankPing360(0), 0);
  bench.start();
  bench.runUntilBeams(45, 30.0);
  ASSERT_EQ(bench.beams().size(), 45u);
  // ±10 gradians about 0: 390, 392, ..., 398, 0, ..., 10, then back 8, ..., 390, then on again.
  std::vector<int> expected;
  for (int i = 0; i < 45; ++i) {
    const int k = i % 20;
    expected.push_back((390 + 2 * (k <= 10 ? k : 20 - k)) % 400);
  }
  std::vector<int> got;
  for (const Beam& beam : bench.beams()) got.push_back(gradiansOf(beam));
  EXPECT_EQ(got, expected);
  const ping_protocol::DeviceData head = bench.emulator().state();
  EXPECT_EQ(head.gain_setting, 0);
  EXPECT_EQ(head.transmit_frequency_khz, 800);
  EXPECT_EQ(head.sample_period_ticks, 222);
  EXPECT_EQ(head.number_of_samples, 1200);
  EXPECT_EQ(head.transmit_duration_us, 27);
  EXPECT_EQ(bench.driver().applied().value("sector_deg"), "18");
  EXPECT_EQ(bench.beams().front().gain_setting, 0);
}

TEST(devicesPing360Driver, ALostReplyIsAskedForAgain) {
  Ping360Bench bench(HeadSettings{}, test::tankPing360());
  int device_data = 0;
  bench.drop = [&](const pp::Message& message) { return message.id == pp::kDeviceData && ++device_data == 3; };
  bench.start();
  bench.runUntilBeams(10, 30.0);
  ASSERT_EQ(bench.beams().size(), 10u);
  for (std::size_t i = 0; i < 10; ++i) EXPECT_EQ(gradiansOf(bench.beams()[i]), static_cast<int>(i));
  EXPECT_EQ(bench.driver().repeats(), 1u);
  EXPECT_TRUE(hasNote(bench.notes(), "no device_data for 2 grad from the Ping360 in time (0.34 s; head silent for "));
  EXPECT_TRUE(hasNote(bench.notes(), "): command sent again (1 in a row, 1 in all)"));
  // The wait was the command's timeout: travel, listening, transfer and 200 ms.
  EXPECT_NEAR(bench.driver().replyTimeout_s(1), 0.01 + 0.02664 + 107e-6 + 1224 * 10.0 / 115200 + 0.2, 1e-9);
  EXPECT_NEAR(bench.driver().replyTimeout_s(200), 2.0 + 0.02664 + 107e-6 + 1224 * 10.0 / 115200 + 0.2, 1e-9);
  EXPECT_EQ(bench.emulator().beamsSent(), 12u);  // the lost one twice, and the next under way
}

// A head that stops answering: every command is sent again at its timeout, and said at the 1st,
// 2nd, 4th, 8th... unanswered one, with how long the head has been silent (not at every repeat).
TEST(devicesPing360Driver, ASilentHeadIsSaidAtDoublingRepeats) {
  Ping360Bench bench(HeadSettings{}, test::tankPing360());
  bool silent = false;
  bench.drop = [&](const pp::Message& message) { return silent && message.id == pp::kDeviceData; };
  bench.start();
  bench.runUntilBeams(5, 10.0);
  silent = true;
  bench.runFor(12.0);
  std::size_t said = 0;
  for (const std::string& note : bench.notes()) said += note.find("command sent again") != std::string::npos ? 1 : 0;
  const std::size_t repeats = bench.driver().repeats();
  EXPECT_GT(repeats, 20U);  // every 0.34 s for 12 s
  EXPECT_EQ(said, static_cast<std::size_t>(std::floor(std::log2(static_cast<double>(repeats)))) + 1);
  EXPECT_TRUE(hasNote(bench.notes(), "head silent for "));
  EXPECT_TRUE(hasNote(bench.notes(), "command sent again (16 in a row, 16 in all)"));
}

// Another program commanding the same head through the proxy: its replies reach the driver, which
// says so (at the 1st, 2nd, 4th... such reply), drops them, and keeps its own scan.
TEST(devicesPing360Driver, AnotherProgramOnTheHeadIsSaid) {
  Ping360Bench bench(HeadSettings{}, test::tankPing360());
  bench.start();
  bench.runUntilBeams(3, 10.0);
  for (int i = 0; i < 5; ++i) {
    pp::Transducer other;
    other.angle_grad = 300;
    other.sample_period_ticks = 80;
    other.number_of_samples = 1200;
    other.transmit_duration_us = 20;
    other.transmit_frequency_khz = 750;
    bench.fromAnotherProgram(pp::encode(other));
    bench.runFor(0.5);
  }
  std::size_t said = 0;
  for (const std::string& note : bench.notes()) said += note.find("another program is commanding the head") != std::string::npos;
  // at the 1st, 2nd and 4th such reply: the other program's commands that the head answered (a
  // command the head gets while busy replaces the one under way)
  EXPECT_GE(said, 2U);
  EXPECT_LE(said, 3U);
  for (const Beam& beam : bench.beams()) EXPECT_NE(gradiansOf(beam), 300);
}

TEST(devicesPing360Driver, StopSendsMotorOffAndThenNothing) {
  Ping360Bench bench(HeadSettings{}, test::tankPing360());
  bench.start();
  bench.runUntilBeams(3, 10.0);
  const std::size_t sent = bench.sent().size();
  bench.stop();
  const std::vector<std::uint8_t> tail(bench.sent().begin() + static_cast<std::ptrdiff_t>(sent), bench.sent().end());
  EXPECT_EQ(tail, hexBytes("42520000570b0000f600"));  // ping-python's motor_off
  bench.runFor(5.0);
  EXPECT_EQ(bench.sent().size(), sent + tail.size());  // nothing after it, no repeat
  EXPECT_EQ(bench.beams().size(), 4u);                 // the ping on its way still arrives
}

TEST(devicesPing360Driver, NacksAndStrangeRepliesBecomeNotes) {
  Ping360Driver driver(HeadSettings{}, Ping360DriverOptions{0});
  driver.start(0.0);
  DriverOutput out = driver.receive(pp::encode(pp::Nack{pp::kGeneralRequest, "no"}, 2, 0), 0.1);
  EXPECT_TRUE(hasNote(out.notes, "the Ping360 refused general_request (6): no"));
  ASSERT_FALSE(out.send.empty());  // the head answers: scanning begins
  out = driver.receive(pp::encode(pp::Nack{pp::kTransducer, "transducer (2601): angle 400 is outside 0–399"}, 2, 0), 0.2);
  EXPECT_TRUE(hasNote(out.notes, "the Ping360 refused transducer (2601): transducer (2601): angle 400"));
  EXPECT_TRUE(out.send.empty());
  out = driver.poll(1.2);  // retried a second after the nack
  EXPECT_EQ(out.send.size(), 24u);
  EXPECT_EQ(driver.repeats(), 1u);
  // A reply at an angle no command of ours asked for: another program commands the head; dropped, noted.
  out = driver.receive(pp::encode(pp::DeviceData{1, 1, 7, 107, 888, 750, 3, {1, 2, 3}}, 2, 0), 1.3);
  EXPECT_TRUE(out.beams.empty());
  EXPECT_TRUE(hasNote(out.notes, "device_data at 7 grad, not the 0 grad commanded: another program is commanding the head"));
  // Settings the head changed are noted and shown in applied().
  out = driver.receive(pp::encode(pp::DeviceData{1, 1, 0, 100, 888, 750, 3, {1, 2, 3}}, 2, 0), 1.4);
  ASSERT_EQ(out.beams.size(), 1u);
  EXPECT_TRUE(hasNote(out.notes, "the Ping360 applied transmit_duration_us 100 (asked 107)"));
  EXPECT_EQ(driver.applied().value("transmit_duration_us"), "100");
  // A head left auto-transmitting: its pings are beams, and motor_off is sent.
  out = driver.receive(pp::encode(pp::AutoDeviceData{1, 1, 50, 107, 888, 750, 0, 399, 1, 0, 2, {9, 9}}, 2, 0), 1.5);
  ASSERT_EQ(out.beams.size(), 1u);
  EXPECT_NEAR(out.beams[0].bearing_rad, 50 * kGradian, 1e-12);
  EXPECT_EQ(out.send, hexBytes("42520000570b0000f600"));
  // Line noise is a note, at most once a second.
  out = driver.receive(std::vector<std::uint8_t>{0, 'U', 0}, 1.6);
  out = driver.receive(pp::encode(pp::Ack{pp::kMotorOff}, 2, 0), 2.7);
  EXPECT_TRUE(hasNote(out.notes, "Ping360 link: stream: byte"));
}

TEST(devicesPing360Driver, BadSettingsAreRefusedAtConstruction) {
  HeadSettings settings;
  settings.range_m = 100.0;
  EXPECT_THROW(Ping360Driver{settings}, ValueError);
  settings = HeadSettings{};
  settings.gain = "max";
  EXPECT_THROW(Ping360Driver{settings}, ValueError);
  settings = HeadSettings{};
  settings.step_rad = 0.2;  // 11.5 degrees, coarser than the head's 10 gradians
  EXPECT_THROW(Ping360Driver{settings}, ValueError);
}

TEST(devicesPing360Driver, TheSettingsRoundingIsSaidAtTheStart) {
  HeadSettings settings;
  settings.step_rad = 1.0 * std::numbers::pi / 180.0;
  Ping360Driver driver(settings);
  const DriverOutput out = driver.start(0.0);
  ASSERT_EQ(out.notes.size(), 1u);
  EXPECT_NE(out.notes[0].find("--step 1 degrees rounded to 1 gradian = 0.9 degrees"), std::string::npos) << out.notes[0];
  EXPECT_FALSE(out.send.empty());
  EXPECT_EQ(driver.applied().value("step_deg"), "0.9");
}

}  // namespace
}  // namespace sonarmap
