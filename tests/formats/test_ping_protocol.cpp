// ping_protocol.hpp: messages encoded byte for byte as Blue Robotics' ping-python packs them,
// payloads read back, the frame's verdicts, and the stream parser over chunks and garbage.
//
// The reference bytes were packed by ping-python's own PingMessage.pack_msg_data(): ping-python
// commit 13338a01dfd51b05b63f150b24abe835c620cedf (0.2.3) with its ping-protocol submodule at
// 73b69d544a1e9a65aa182ad1535a4fd90a240acd, the brping package generated in /tmp (not in this
// repository) by
//   git -C ping-python archive HEAD | tar -x -C /tmp/pingpy
//   git -C ping-protocol archive 73b69d5 | tar -x -C /tmp/pingpy/lib/ping-protocol
//   python3 /tmp/pingpy/generate/generate-python.py --output-directory /tmp/pingpy/brping
// then, per message, m = PingMessage(ID); m.FIELD = VALUE ...; m.pack_msg_data().hex() with the
// field values written beside each constant below (ping-python leaves data_length to the caller).
#include <gtest/gtest.h>

#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/ping_protocol.hpp"

namespace sonarmap::ping_protocol {
namespace {

std::vector<std::uint8_t> hex(const std::string& text) {
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < text.size(); i += 2) {
    bytes.push_back(static_cast<std::uint8_t>(std::stoul(text.substr(i, 2), nullptr, 16)));
  }
  return bytes;
}

/// The one message of `bytes`, parsed whole.
Message onlyMessage(const std::vector<std::uint8_t>& bytes) {
  MessageParser parser;
  std::vector<Message> messages = parser.feed(bytes);
  EXPECT_EQ(messages.size(), 1u);
  EXPECT_EQ(parser.skippedItems(), 0u);
  return messages.empty() ? Message{} : messages.front();
}

Transducer sampleTransducer() {
  Transducer command;
  command.mode = 1;
  command.gain_setting = 1;
  command.angle_grad = 133;
  command.transmit_duration_us = 107;
  command.sample_period_ticks = 888;
  command.transmit_frequency_khz = 750;
  command.number_of_samples = 1200;
  command.transmit = 1;
  return command;
}

TEST(formatsPingProtocol, HostCommandsAreThoseOfPingPython) {
  // general_request: requested_id=4 (device_information), requested_id=5 (protocol_version); the
  // second is also the byte list of ping-protocol's docs/index.md negotiation example.
  EXPECT_EQ(encode(GeneralRequest{kDeviceInformation}), hex("42520200060000000400a000"));
  EXPECT_EQ(encode(GeneralRequest{kProtocolVersion}), hex("42520200060000000500a100"));
  // transducer: mode=1 gain_setting=1 angle=133 transmit_duration=107 sample_period=888
  // transmit_frequency=750 number_of_samples=1200 transmit=1 reserved=0 (20 m at 1500 m/s).
  EXPECT_EQ(encode(sampleTransducer()), hex("42520e00290a0000010185006b007803ee02b0040100e703"));
  EXPECT_EQ(encode(MotorOff{}), hex("42520000570b0000f600"));
  // auto_transmit: mode=1 gain_setting=2 transmit_duration=267 sample_period=2222
  // transmit_frequency=750 number_of_samples=1200 start_angle=150 stop_angle=249 num_steps=2 delay=0
  AutoTransmit automatic{1, 2, 267, 2222, 750, 1200, 150, 249, 2, 0};
  EXPECT_EQ(encode(automatic), hex("425210002a0a000001020b01ae08ee02b0049600f9000200d204"));
  EXPECT_EQ(encode(Reset{0, 0}), hex("42520200280a00000000c800"));                 // bootloader=0 reserved=0
  EXPECT_EQ(encode(SetDeviceId{3, 0}), hex("42520200d007000003007001"));            // id=3 reserved=0
}

TEST(formatsPingProtocol, HeadRepliesAreThoseOfPingPython) {
  // device_information: device_type=2 device_revision=67 firmware 3.3.1 reserved=0
  EXPECT_EQ(encode(DeviceInformation{2, 67, 3, 3, 1, 0}), hex("4252060004000000024303030100ea00"));
  // protocol_version: 1.1.0 reserved=0
  EXPECT_EQ(encode(ProtocolVersion{1, 1, 0, 0}), hex("4252040005000000010100009f00"));
  EXPECT_EQ(encode(Ack{kMotorOff}), hex("4252020001000000570bf900"));  // acked_id=2903
  // device_data: mode=1 gain_setting=1 angle=133 transmit_duration=107 sample_period=888
  // transmit_frequency=750 number_of_samples=5 data_length=5 data=[0, 7, 255, 128, 3]
  DeviceData ping{1, 1, 133, 107, 888, 750, 5, {0, 7, 255, 128, 3}};
  EXPECT_EQ(encode(ping), hex("42521300fc080000010185006b007803ee02050005000007ff80039b05"));
  // auto_device_data: mode=1 gain_setting=2 angle=10 transmit_duration=267 sample_period=2222
  // transmit_frequency=750 start_angle=0 stop_angle=399 num_steps=1 delay=0 number_of_samples=3
  // data_length=3 data=[1, 2, 3]
  AutoDeviceData automatic{1, 2, 10, 267, 2222, 750, 0, 399, 1, 0, 3, {1, 2, 3}};
  EXPECT_EQ(encode(automatic), hex("42521700fd08000001020a000b01ae08ee0200008f010100030003000102030c04"));
  // The protocol's own example (docs/index.md): protocol_version 1.2.3 with source and destination 0.
  EXPECT_EQ(encode(ProtocolVersion{1, 2, 3, 0}), hex("4252040005000000010203" "00a300"));
  // The Ping360 of the shared logs sends from device 2 to 0.
  const std::vector<std::uint8_t> from_head = encode(ping, 2, 0);
  EXPECT_EQ(from_head[6], 2);
  EXPECT_EQ(onlyMessage(from_head).source_id, 2);
}

TEST(formatsPingProtocol, PayloadsReadBackWhatWasWritten) {
  const Transducer command = sampleTransducer();
  const std::optional<Transducer> transducer = decode<Transducer>(onlyMessage(encode(command)));
  ASSERT_TRUE(transducer);
  EXPECT_EQ(transducer->payload(), command.payload());
  EXPECT_EQ(transducer->number_of_samples, 1200);
  EXPECT_EQ(transducer->angle_grad, 133);

  const DeviceData ping{1, 2, 399, 5, 80, 1000, 3, {9, 8, 7}};
  const std::optional<DeviceData> data = decode<DeviceData>(onlyMessage(encode(ping)));
  ASSERT_TRUE(data);
  EXPECT_EQ(data->data, ping.data);
  EXPECT_EQ(data->angle_grad, 399);
  EXPECT_EQ(data->transmit_frequency_khz, 1000);

  const AutoDeviceData automatic{1, 0, 17, 11, 88, 750, 350, 49, 10, 100, 2, {200, 201}};
  const std::optional<AutoDeviceData> auto_data = decode<AutoDeviceData>(onlyMessage(encode(automatic)));
  ASSERT_TRUE(auto_data);
  EXPECT_EQ(auto_data->payload(), automatic.payload());
  EXPECT_EQ(auto_data->deviceData().payload(), (DeviceData{1, 0, 17, 11, 88, 750, 2, {200, 201}}.payload()));

  const AutoTransmit start{1, 1, 32, 80, 740, 1024, 0, 399, 1, 0};
  EXPECT_EQ(decode<AutoTransmit>(onlyMessage(encode(start)))->payload(), start.payload());
  EXPECT_EQ(decode<GeneralRequest>(onlyMessage(encode(GeneralRequest{kDeviceData})))->requested_id, kDeviceData);
  EXPECT_EQ(decode<Ack>(onlyMessage(encode(Ack{kMotorOff})))->acked_id, kMotorOff);
  const std::optional<Nack> nack = decode<Nack>(onlyMessage(encode(Nack{kTransducer, "bad angle"})));
  ASSERT_TRUE(nack);
  EXPECT_EQ(nack->nacked_id, kTransducer);
  EXPECT_EQ(nack->text, "bad angle");
  EXPECT_EQ(decode<AsciiText>(onlyMessage(encode(AsciiText{"hello"})))->text, "hello");
  const std::optional<DeviceInformation> info = decode<DeviceInformation>(onlyMessage(encode(DeviceInformation{2, 67, 3, 1, 1, 0})));
  ASSERT_TRUE(info);
  EXPECT_EQ(info->text(), "Ping360 (firmware 3.1.1)");
  EXPECT_EQ(decode<ProtocolVersion>(onlyMessage(encode(ProtocolVersion{1, 1, 0, 0})))->version_minor, 1);
  EXPECT_TRUE(decode<MotorOff>(onlyMessage(encode(MotorOff{}))));
  EXPECT_EQ(decode<Reset>(onlyMessage(encode(Reset{1, 0})))->bootloader, 1);
  EXPECT_EQ(decode<SetDeviceId>(onlyMessage(encode(SetDeviceId{7, 0})))->id, 7);
}

TEST(formatsPingProtocol, PayloadsOfTheWrongLengthOrIdAreRefusedWithAReason) {
  std::string why;
  const std::vector<std::uint8_t> short_transducer(13, 0);
  EXPECT_FALSE(Transducer::parse(short_transducer, &why));
  EXPECT_EQ(why, "payload of 13 bytes, expected 14");
  EXPECT_FALSE(MotorOff::parse(std::vector<std::uint8_t>{1}, &why));
  EXPECT_EQ(why, "payload of 1 bytes, expected 0");
  EXPECT_FALSE(DeviceInformation::parse(std::vector<std::uint8_t>(5, 0), &why));
  std::vector<std::uint8_t> payload = DeviceData{1, 1, 0, 5, 80, 750, 3, {1, 2, 3}}.payload();
  payload.pop_back();
  EXPECT_FALSE(DeviceData::parse(payload, &why));
  EXPECT_EQ(why, "data length 3 but the payload holds 2 bytes after its fields");
  EXPECT_FALSE(DeviceData::parse(std::vector<std::uint8_t>(12, 0), &why));
  EXPECT_EQ(why, "payload of 12 bytes, expected at least 14");
  EXPECT_FALSE(AutoDeviceData::parse(std::vector<std::uint8_t>(19, 0), &why));
  EXPECT_EQ(why, "payload of 19 bytes, expected at least 20");
  EXPECT_FALSE(decode<Transducer>(Message{kDeviceData, 0, 0, {}}, &why));
  EXPECT_EQ(why, "device_data (2300), not transducer (2601)");
  EXPECT_EQ(messageName(4242), "message 4242");
}

TEST(formatsPingProtocol, FrameVerdicts) {
  const std::vector<std::uint8_t> message = encode(sampleTransducer());
  const Framing whole = frameAt(message);
  EXPECT_EQ(whole.kind, Framing::Kind::kMessage);
  EXPECT_EQ(whole.size, message.size());
  for (std::size_t cut = 0; cut < message.size(); ++cut) {
    EXPECT_EQ(frameAt(std::span(message).first(cut)).kind, Framing::Kind::kCutShort) << cut;
  }
  EXPECT_EQ(frameAt(std::span(message).first(20)).reason, "declares 24 bytes, the capture ends 20 bytes after its start");
  std::vector<std::uint8_t> bad = message;
  bad.back() ^= 1;
  const Framing wrong = frameAt(bad);
  EXPECT_EQ(wrong.kind, Framing::Kind::kNotAMessage);
  EXPECT_EQ(wrong.reason, "checksum 743 but its bytes sum to 999 (mod 65536)");
  const std::vector<std::uint8_t> huge = {'B', 'R', 0xFF, 0xFF, 0, 0, 0, 0};
  EXPECT_EQ(frameAt(huge).reason, "declares 65545 bytes, expected fewer than 10240");
  EXPECT_EQ(frameAt(std::vector<std::uint8_t>{'B', 'X'}).kind, Framing::Kind::kNotAMessage);
  EXPECT_EQ(checksumOf(std::span(message).first(message.size() - 2)), message[22] | (message[23] << 8));
  EXPECT_THROW(appendMessage(bad, kAsciiText, std::vector<std::uint8_t>(65536, 'a')), ValueError);
}

TEST(formatsPingProtocol, TheParserFindsTheSameMessagesInAnyChunks) {
  // A stream as a serial line gives it: a break's zeros and the autobaud 'U' before the first
  // message, a message with a bad checksum, a false 'B' 'R' and garbage between the good ones.
  std::vector<std::uint8_t> stream = {0, 0, 'U'};
  const std::vector<std::vector<std::uint8_t>> good = {encode(DeviceInformation{2, 67, 3, 3, 1, 0}),
                                                       encode(DeviceData{1, 1, 133, 107, 888, 750, 5, {0, 7, 255, 128, 3}}),
                                                       encode(Ack{kMotorOff}), encode(Nack{kTransducer, "no"})};
  std::vector<std::uint8_t> corrupt = encode(sampleTransducer());
  corrupt[10] ^= 0x40;
  stream.insert(stream.end(), good[0].begin(), good[0].end());
  stream.insert(stream.end(), corrupt.begin(), corrupt.end());
  stream.insert(stream.end(), good[1].begin(), good[1].end());
  stream.insert(stream.end(), {'B', 'R', 'B', 'x'});
  stream.insert(stream.end(), good[2].begin(), good[2].end());
  stream.insert(stream.end(), good[3].begin(), good[3].end());

  MessageParser whole;
  const std::vector<Message> expected = whole.feed(stream);
  ASSERT_EQ(expected.size(), good.size());
  for (std::size_t i = 0; i < good.size(); ++i) EXPECT_EQ(encode(expected[i]), good[i]) << i;
  EXPECT_EQ(whole.skippedItems(), 3u);  // the break and 'U'; the corrupt message; the false start
  const std::vector<std::string> reasons = whole.takeSkipReasons();
  ASSERT_EQ(reasons.size(), 3u);
  EXPECT_EQ(reasons[0], "stream: byte 0 to byte 2: 3 bytes outside any message");
  EXPECT_NE(reasons[1].find("checksum"), std::string::npos) << reasons[1];
  EXPECT_TRUE(whole.takeSkipReasons().empty());
  EXPECT_EQ(whole.bytesFed(), stream.size());
  EXPECT_EQ(whole.messagesParsed(), good.size());

  for (std::size_t chunk = 1; chunk <= 29; ++chunk) {
    MessageParser parser;
    std::vector<Message> found;
    for (std::size_t at = 0; at < stream.size(); at += chunk) {
      const std::size_t n = std::min(chunk, stream.size() - at);
      for (Message& message : parser.feed(std::span(stream).subspan(at, n))) found.push_back(std::move(message));
    }
    ASSERT_EQ(found.size(), expected.size()) << "chunks of " << chunk;
    for (std::size_t i = 0; i < found.size(); ++i) EXPECT_EQ(encode(found[i]), good[i]) << chunk;
    EXPECT_EQ(parser.skippedItems(), 3u) << chunk;
  }
}

TEST(formatsPingProtocol, TheParserTakesAnyBytesWithoutThrowing) {
  std::mt19937 random(7);
  std::vector<std::uint8_t> bytes(200000);
  for (std::uint8_t& byte : bytes) byte = static_cast<std::uint8_t>(random() % 4 == 0 ? "BR"[random() % 2] : random());
  // Valid messages among the noise are found.
  const std::vector<std::uint8_t> ping = encode(DeviceData{1, 1, 7, 5, 80, 750, 2, {1, 2}});
  bytes.insert(bytes.begin() + 1000, ping.begin(), ping.end());
  MessageParser parser;
  std::size_t found = 0;
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t n = std::min<std::size_t>(1 + random() % 300, bytes.size() - at);
    for (const Message& message : parser.feed(std::span(bytes).subspan(at, n))) found += message.id == kDeviceData;
    parser.takeSkipReasons();
    at += n;
  }
  EXPECT_EQ(parser.bytesFed(), bytes.size());
  EXPECT_GE(found, 1u);
}

TEST(formatsPingProtocol, APingIsABeam) {
  const DeviceData ping{1, 2, 100, 267, 2222, 750, 3, {10, 20, 30}};
  std::string why;
  const std::optional<Beam> beam = ping360Beam(ping, 1500.0, &why);
  ASSERT_TRUE(beam) << why;
  EXPECT_DOUBLE_EQ(beam->bearing_rad, std::numbers::pi / 2.0);  // 100 grad clockwise: starboard
  EXPECT_DOUBLE_EQ(beam->bin_length_m, 2222 * 25e-9 * 1500.0 / 2.0);
  EXPECT_DOUBLE_EQ(*beam->pulse_length_m, 267e-6 * 1500.0 / 2.0);
  EXPECT_EQ(*beam->gain_setting, 2);
  EXPECT_EQ(beam->intensities, ping.data);
  EXPECT_FALSE(beam->intensity_span_db);

  DeviceData bad = ping;
  bad.angle_grad = 400;
  EXPECT_FALSE(ping360Beam(bad, 1500.0, &why));
  EXPECT_EQ(why, "angle 400, expected 0…399 gradians");
  bad = ping;
  bad.sample_period_ticks = 0;
  EXPECT_FALSE(ping360Beam(bad, 1500.0, &why));
  EXPECT_EQ(why, "sample period 0, expected > 0 (units of 25 ns)");
  bad = ping;
  bad.data.clear();  // the reply to a transducer command with transmit = 0
  EXPECT_FALSE(ping360Beam(bad, 1500.0, &why));
  EXPECT_EQ(why, "no samples");
  bad = ping;
  bad.transmit_duration_us = 0;
  EXPECT_FALSE(ping360Beam(bad, 1500.0)->pulse_length_m);
}

}  // namespace
}  // namespace sonarmap::ping_protocol
