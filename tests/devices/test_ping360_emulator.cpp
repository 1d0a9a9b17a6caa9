// Ping360Emulator: it answers only what it is asked, when the head would (motor, listening,
// transfer), with the commanded settings and the scene's echoes; auto-transmit scans by itself
// until motor_off; refusals are nacks. ping360EchoModel's choices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "devices/ping360_bench.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap {
namespace {

namespace pp = ping_protocol;

/// The one message of `replies` (each TimedBytes holds one).
pp::Message only(const std::vector<TimedBytes>& replies) {
  EXPECT_EQ(replies.size(), 1u);
  if (replies.empty()) return {};
  pp::MessageParser parser;
  std::vector<pp::Message> messages = parser.feed(replies.front().bytes);
  EXPECT_EQ(messages.size(), 1u);
  return messages.empty() ? pp::Message{} : messages.front();
}

pp::Transducer command(int angle, int gain = 1, int period = 888, int samples = 1200, int transmit = 1) {
  return {1, static_cast<std::uint8_t>(gain), static_cast<std::uint16_t>(angle), 107, static_cast<std::uint16_t>(period),
          750, static_cast<std::uint16_t>(samples), static_cast<std::uint8_t>(transmit), 0};
}

double mean(const std::vector<std::uint8_t>& data, std::size_t from, std::size_t to) {
  return std::accumulate(data.begin() + static_cast<std::ptrdiff_t>(from), data.begin() + static_cast<std::ptrdiff_t>(to), 0.0) /
         static_cast<double>(to - from);
}

TEST(devicesPing360Emulator, PingsOnlyWhenCommanded) {
  Ping360Emulator head = test::tankPing360();
  for (double t = 0.0; t < 10.0; t += 0.1) EXPECT_TRUE(head.poll(t).empty());
  EXPECT_TRUE(head.receive(std::vector<std::uint8_t>{0, 0, 'U', 'B'}, 1.0).empty());  // a break, autobaud, noise
  EXPECT_EQ(head.beamsSent(), 0u);

  const pp::Message info = only(head.receive(pp::encode(pp::GeneralRequest{pp::kDeviceInformation}), 10.0));
  EXPECT_EQ(info.source_id, 2);
  EXPECT_EQ(pp::decode<pp::DeviceInformation>(info)->text(), "Ping360 (firmware 3.3.1)");
  EXPECT_EQ(pp::decode<pp::DeviceInformation>(info)->device_revision, 67);
  const pp::Message version = only(head.receive(pp::encode(pp::GeneralRequest{pp::kProtocolVersion}), 10.0));
  EXPECT_EQ(pp::decode<pp::ProtocolVersion>(version)->version_minor, 1);
  // ping-python's Ping360.initialize() reads the settings with general_request(device_data): the
  // firmware's boot settings, no samples.
  const pp::Message state = only(head.receive(pp::encode(pp::GeneralRequest{pp::kDeviceData}), 10.0));
  const std::optional<pp::DeviceData> boot = pp::decode<pp::DeviceData>(state);
  ASSERT_TRUE(boot);
  EXPECT_EQ(boot->payload(), (pp::DeviceData{1, 0, 0, 32, 80, 740, 1024, {}}.payload()));
  // transmit = 0: the head moves, answers, does not ping.
  const pp::Message moved = only(head.receive(pp::encode(command(100, 2, 888, 1200, 0)), 11.0));
  EXPECT_TRUE(pp::decode<pp::DeviceData>(moved)->data.empty());
  EXPECT_EQ(pp::decode<pp::DeviceData>(moved)->angle_grad, 100);
  EXPECT_EQ(head.beamsSent(), 0u);
  EXPECT_EQ(head.settingsText(), "range 19.98 m (1200 samples of 888 ticks), gain 2, angle 100 grad, transmit 107 us, 750 kHz");
}

TEST(devicesPing360Emulator, RepliesWhenTheHeadWould) {
  Ping360Emulator head = test::tankPing360(115200);
  const double listen_s = 1200 * 888 * 25e-9;
  const double transfer_s = (8 + 14 + 1200 + 2) * 10.0 / 115200.0;
  const std::vector<TimedBytes> first = head.receive(pp::encode(command(100)), 1.0);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_NEAR(first[0].at_s, 1.0 + 100 * 0.006 + listen_s + transfer_s, 1e-12);  // 100 gradians from 0
  // A command that arrives while the head is busy waits for it.
  const std::vector<TimedBytes> second = head.receive(pp::encode(command(99)), 1.1);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_NEAR(second[0].at_s, first[0].at_s + 0.006 + listen_s + transfer_s, 1e-12);
  // Over UDP (baud 0) there is no transfer time; the shortest way round is taken.
  Ping360Emulator udp = test::tankPing360(0);
  EXPECT_NEAR(udp.receive(pp::encode(command(390)), 0.0)[0].at_s, 10 * 0.006 + listen_s, 1e-12);
  const std::vector<TimedBytes> info = udp.receive(pp::encode(pp::GeneralRequest{pp::kDeviceInformation}), 0.0);
  EXPECT_NEAR(info[0].at_s, 10 * 0.006 + listen_s, 1e-12);  // after the ping it was busy with
}

TEST(devicesPing360Emulator, ThePingHasTheCommandedSettingsAndTheScenesEchoes) {
  Ping360Emulator head = test::tankPing360(0);
  // 5 m (222 ticks): the tank's +x wall (north, bearing 0) is 2.1 m away, at sample ≈ 504.
  const pp::Message reply = only(head.receive(pp::encode(command(0, 1, 222)), 0.0));
  EXPECT_EQ(reply.id, pp::kDeviceData);
  const std::optional<pp::DeviceData> ping = pp::decode<pp::DeviceData>(reply);
  ASSERT_TRUE(ping);
  EXPECT_EQ(ping->angle_grad, 0);
  EXPECT_EQ(ping->gain_setting, 1);
  EXPECT_EQ(ping->sample_period_ticks, 222);
  EXPECT_EQ(ping->number_of_samples, 1200);
  EXPECT_EQ(ping->data.size(), 1200u);
  EXPECT_EQ(ping->transmit_duration_us, 107);
  EXPECT_EQ(ping->transmit_frequency_khz, 750);
  EXPECT_EQ(head.beamsSent(), 1u);
  const auto wall = std::max_element(ping->data.begin() + 480, ping->data.begin() + 540);
  EXPECT_GT(*wall, 150) << "no wall echo near sample 504";
  EXPECT_LT(mean(ping->data, 150, 450), 20.0) << "the water before the wall is not dark";

  // More gain, louder echoes: 4 dB a step, 17 counts a step on the 60 dB span of the presets.
  Ping360Emulator low = test::tankPing360(0, 5);
  Ping360Emulator high = test::tankPing360(0, 5);
  const std::vector<std::uint8_t> quiet = pp::decode<pp::DeviceData>(only(low.receive(pp::encode(command(0, 0, 222)), 0.0)))->data;
  const std::vector<std::uint8_t> loud = pp::decode<pp::DeviceData>(only(high.receive(pp::encode(command(0, 2, 222)), 0.0)))->data;
  EXPECT_GT(mean(loud, 490, 530), mean(quiet, 490, 530) + 15.0);
  // The transmit duration is held within what the firmware applies: 64 periods of 80 ticks = 128 µs.
  pp::Transducer long_pulse = command(0, 1, 80, 1200);
  long_pulse.transmit_duration_us = 1000;
  EXPECT_EQ(pp::decode<pp::DeviceData>(only(head.receive(pp::encode(long_pulse), 1.0)))->transmit_duration_us, 128);
}

TEST(devicesPing360Emulator, RefusalsAreNacks) {
  Ping360Emulator head = test::tankPing360(0);
  const std::optional<pp::Nack> samples = pp::decode<pp::Nack>(only(head.receive(pp::encode(command(0, 1, 888, 1500)), 0.0)));
  ASSERT_TRUE(samples);
  EXPECT_EQ(samples->nacked_id, pp::kTransducer);
  EXPECT_EQ(samples->text, "transducer (2601): number_of_samples 1500 is outside 200..1200");
  EXPECT_EQ(pp::decode<pp::Nack>(only(head.receive(pp::encode(command(400)), 0.0)))->text,
            "transducer (2601): angle 400 is outside 0..399");
  pp::Message unknown{1234, 0, 0, {1, 2}};
  EXPECT_EQ(pp::decode<pp::Nack>(only(head.receive(pp::encode(unknown), 0.0)))->text, "message 1234: not a command of this head");
  pp::Message short_transducer{pp::kTransducer, 0, 0, {1, 2, 3}};
  EXPECT_EQ(pp::decode<pp::Nack>(only(head.receive(pp::encode(short_transducer), 0.0)))->text,
            "transducer (2601): payload of 3 bytes, expected 14");
  EXPECT_EQ(pp::decode<pp::Nack>(only(head.receive(pp::encode(pp::GeneralRequest{pp::kTransducer}), 0.0)))->text,
            "general_request (6): transducer (2601) cannot be requested");
  EXPECT_EQ(head.beamsSent(), 0u);
}

// nack_message is a char array hosts decode as ASCII (ping-python, Ping Viewer): every nack the
// head can send, for every refusal it makes, carries printable 7-bit ASCII.
TEST(devicesPing360Emulator, EveryNackTextIsAscii) {
  Ping360Emulator head = test::tankPing360(0);
  std::vector<pp::Message> asked;
  // Each field of a transducer command outside its range, at both ends where it has two.
  const pp::Transducer good = command(0);
  for (int i = 0; i < 11; ++i) {
    pp::Transducer t = good;
    switch (i) {
      case 0: t.gain_setting = 3; break;
      case 1: t.transmit_duration_us = 0; break;
      case 2: t.transmit_duration_us = 1001; break;
      case 3: t.sample_period_ticks = 79; break;
      case 4: t.sample_period_ticks = 40001; break;
      case 5: t.transmit_frequency_khz = 499; break;
      case 6: t.transmit_frequency_khz = 1001; break;
      case 7: t.number_of_samples = 199; break;
      case 8: t.number_of_samples = 1201; break;
      case 9: t.angle_grad = 400; break;
      default: t.angle_grad = 65535; break;
    }
    asked.push_back({pp::kTransducer, 0, 0, t.payload()});
  }
  // The same of auto_transmit, and its own fields.
  const pp::AutoTransmit scan{1, 1, 27, 222, 750, 1200, 390, 10, 5, 0};
  for (int i = 0; i < 13; ++i) {
    pp::AutoTransmit a = scan;
    switch (i) {
      case 0: a.gain_setting = 3; break;
      case 1: a.transmit_duration_us = 0; break;
      case 2: a.sample_period_ticks = 40001; break;
      case 3: a.transmit_frequency_khz = 1001; break;
      case 4: a.number_of_samples = 1201; break;
      case 5: a.start_angle_grad = 400; break;
      case 6: a.stop_angle_grad = 400; break;
      case 7: a.num_steps = 0; break;
      case 8: a.num_steps = 11; break;
      case 9: a.delay_ms = 101; break;
      case 10: a.transmit_frequency_khz = 499; break;
      case 11: a.number_of_samples = 199; break;
      default: a.sample_period_ticks = 79; break;
    }
    asked.push_back({pp::kAutoTransmit, 0, 0, a.payload()});
  }
  // Every command the head reads, with payloads of every wrong length up to 24 bytes.
  for (const std::uint16_t id : {pp::kGeneralRequest, pp::kTransducer, pp::kAutoTransmit, pp::kMotorOff, pp::kSetDeviceId,
                                 pp::kReset}) {
    for (std::size_t length = 0; length <= 24; ++length) asked.push_back({id, 0, 0, std::vector<std::uint8_t>(length, 0xFF)});
  }
  // Requests of every message id, reserved device ids, messages the head does not take.
  for (int id = 0; id <= 65535; id += (id < 3000 ? 1 : 97)) {
    asked.push_back({pp::kGeneralRequest, 0, 0, pp::GeneralRequest{static_cast<std::uint16_t>(id)}.payload()});
  }
  asked.push_back({pp::kSetDeviceId, 0, 0, pp::SetDeviceId{0, 0}.payload()});
  asked.push_back({pp::kSetDeviceId, 0, 0, pp::SetDeviceId{255, 0}.payload()});
  for (const std::uint16_t id : {0, 1, 2, 3, 4, 5, 100, 1234, 2300, 65535}) asked.push_back({id, 0, 0, {1, 2}});

  std::size_t nacks = 0;
  for (const pp::Message& message : asked) {
    for (const TimedBytes& reply : head.receive(pp::encode(message), 0.0)) {
      pp::MessageParser parser;
      for (const pp::Message& answer : parser.feed(reply.bytes)) {
        const std::optional<pp::Nack> nack = pp::decode<pp::Nack>(answer);
        if (!nack) continue;
        ++nacks;
        EXPECT_FALSE(nack->text.empty()) << "a nack of " << nack->nacked_id << " without text";
        for (const char c : nack->text) {
          const auto byte = static_cast<unsigned char>(c);
          EXPECT_TRUE(byte >= 0x20 && byte < 0x7F) << "byte " << static_cast<int>(byte) << " in \"" << nack->text << '"';
        }
      }
    }
  }
  // Every command above but the three requests the head answers, motor_off and reset: a nack.
  EXPECT_GT(nacks, 3000u);
  EXPECT_EQ(head.beamsSent(), 0u);
}

TEST(devicesPing360Emulator, AutoTransmitScansUntilMotorOff) {
  Ping360Emulator head = test::tankPing360(0);
  // A sector from 390 clockwise to 10, 5 gradians a step: 390, 395, 0, 5, 10, 5, 0, 395, 390, 395...
  EXPECT_TRUE(head.receive(pp::encode(pp::AutoTransmit{1, 1, 27, 222, 750, 1200, 390, 10, 5, 0}), 0.0).empty());
  std::vector<int> angles;
  double last_s = 0.0;
  for (double t = 0.0; t < 5.0 && angles.size() < 10; t += 0.01) {
    for (const TimedBytes& ping : head.poll(t)) {
      pp::MessageParser parser;
      const std::optional<pp::AutoDeviceData> data = pp::decode<pp::AutoDeviceData>(parser.feed(ping.bytes).at(0));
      ASSERT_TRUE(data);
      EXPECT_EQ(data->data.size(), 1200u);
      EXPECT_EQ(data->start_angle_grad, 390);
      EXPECT_EQ(data->stop_angle_grad, 10);
      EXPECT_EQ(data->num_steps, 5);
      EXPECT_GT(ping.at_s, last_s);
      last_s = ping.at_s;
      angles.push_back(data->angle_grad);
    }
  }
  EXPECT_EQ(angles, (std::vector<int>{390, 395, 0, 5, 10, 5, 0, 395, 390, 395}));
  EXPECT_NE(head.settingsText().find("auto-transmit 390..10 grad by 5"), std::string::npos);
  const std::vector<TimedBytes> off = head.receive(pp::encode(pp::MotorOff{}), 5.0);
  ASSERT_FALSE(off.empty());
  EXPECT_EQ(pp::decode<pp::Ack>(only({off.back()}))->acked_id, pp::kMotorOff);
  const std::size_t pinged = head.beamsSent();
  for (double t = 5.0; t < 10.0; t += 0.1) EXPECT_TRUE(head.poll(t).empty());
  EXPECT_EQ(head.beamsSent(), pinged);
  // The whole circle (stop + 1 = start) turns on clockwise.
  head.receive(pp::encode(pp::AutoTransmit{1, 1, 27, 222, 750, 1200, 0, 399, 1, 0}), 10.0);
  std::vector<int> turn;
  for (double t = 10.0; turn.size() < 402; t += 0.05) {
    for (const TimedBytes& ping : head.poll(t)) {
      pp::MessageParser parser;
      turn.push_back(pp::decode<pp::AutoDeviceData>(parser.feed(ping.bytes).at(0))->angle_grad);
    }
  }
  for (std::size_t i = 0; i < turn.size(); ++i) EXPECT_EQ(turn[i], static_cast<int>(i % 400));
}

TEST(devicesPing360Emulator, DeviceIdAndReset) {
  Ping360Emulator head = test::tankPing360(0);
  const pp::Message ack = only(head.receive(pp::encode(pp::SetDeviceId{9, 0}), 0.0));
  EXPECT_EQ(ack.source_id, 2);
  EXPECT_EQ(pp::decode<pp::Ack>(ack)->acked_id, pp::kSetDeviceId);
  EXPECT_EQ(only(head.receive(pp::encode(pp::GeneralRequest{pp::kDeviceInformation}), 0.0)).source_id, 9);
  head.receive(pp::encode(command(50, 2)), 0.0);
  EXPECT_TRUE(head.receive(pp::encode(pp::Reset{0, 0}), 1.0).empty());
  EXPECT_EQ(head.state().payload(), (pp::DeviceData{1, 0, 0, 32, 80, 740, 1024, {}}.payload()));
  EXPECT_EQ(only(head.receive(pp::encode(pp::GeneralRequest{pp::kDeviceInformation}), 2.0)).source_id, 2);
}

TEST(devicesPing360Emulator, EchoModelByRangeGainPulseAndFrequency) {
  const auto model = [](int gain, int period, int duration, int frequency) {
    return ping360EchoModel(pp::DeviceData{1, static_cast<std::uint8_t>(gain), 0, static_cast<std::uint16_t>(duration),
                                           static_cast<std::uint16_t>(period), static_cast<std::uint16_t>(frequency), 1200, {}},
                            1500.0);
  };
  // At each preset's own range, gain and automatic pulse: the preset's levels.
  const SonarPreset two = model(0, 88, 11, 750);
  const SonarPreset preset_two = sonarPreset("ping360-2m");
  EXPECT_NEAR(two.head.range_m, 1.98, 1e-9);
  EXPECT_EQ(two.head.bins, 1200);
  EXPECT_EQ(two.echo.ad_low_db, preset_two.echo.ad_low_db);
  EXPECT_EQ(two.echo.self_reflection_end_m, preset_two.echo.self_reflection_end_m);
  EXPECT_NEAR(two.echo.noise_level_db, preset_two.echo.noise_level_db - 10 * std::log10(0.00825 / 0.008), 1e-9);
  const SonarPreset fifty = model(2, 2222, 267, 750);
  EXPECT_EQ(fifty.echo.ad_low_db, sonarPreset("ping360").echo.ad_low_db);
  EXPECT_EQ(model(0, 444, 53, 750).echo.self_reflection_end_m, sonarPreset("ping360-5m").echo.self_reflection_end_m);
  // 4 dB a gain step; a longer pulse, lower noise; a higher frequency, a narrower beam.
  EXPECT_EQ(model(1, 2222, 267, 750).echo.ad_low_db, fifty.echo.ad_low_db + 4.0);
  EXPECT_NEAR(model(2, 2222, 500, 750).echo.noise_level_db, fifty.echo.noise_level_db - 10 * std::log10(500.0 / 267.0), 1e-9);
  EXPECT_NEAR(model(2, 2222, 267, 1000).head.horizontal_beam_width_rad, fifty.head.horizontal_beam_width_rad * 0.75, 1e-12);
  EXPECT_EQ(fifty.echo.speckle_looks, 5);  // the pulse's 0.2 m over 4.2 cm samples
  EXPECT_TRUE(fifty.head.logs_pulse_length);
  EXPECT_NO_THROW(fifty.head.validate());
  EXPECT_NO_THROW(fifty.echo.validate());
}

TEST(devicesPing360Emulator, RefusesAWrongSoundSpeed) {
  Ping360EmulatorOptions options;
  options.sound_speed_m_s = 0.0;
  EXPECT_THROW(Ping360Emulator(builtinScene("tank"), staticTrajectory(), defaultSonarToBody(), 1, options), ValueError);
}

}  // namespace
}  // namespace sonarmap
