/// Tests of the MAVLink frame layer (mavlink.hpp, mavlink_messages.hpp): the checksum and the
/// CRC_EXTRA of each known message recomputed from its XML definition; frames built byte by byte
/// from the serialization spec (vehicle_log_fixture.hpp) read back; the stream parser over noise,
/// false starts, corrupted and signed frames, in chunks of every size; the encoder's truncation,
/// sequence numbers and MAVLink 1 limits; each message's fields encoded and decoded.

#include <gtest/gtest.h>

#include <cstring>
#include <numeric>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/mavlink.hpp"
#include "sonarmap/formats/mavlink_messages.hpp"
#include "vehicle_log_fixture.hpp"

namespace sonarmap {
namespace {

using test::MavlinkFrameOptions;

std::span<const std::uint8_t> bytesOf(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}
std::string textOf(const std::vector<std::uint8_t>& v) { return {v.begin(), v.end()}; }

TEST(formatsMavlink, TheChecksumIsCrc16Mcrf4xx) {
  EXPECT_EQ(mavlinkCrc(bytesOf("123456789")), 0x6F91);  // the CRC catalogue's check value
  EXPECT_EQ(mavlinkCrc(bytesOf("56789"), mavlinkCrc(bytesOf("1234"))), 0x6F91);
}

// Each message's fields in wire order (by type size, largest first; extensions left out), as
// message_definitions/v1.0 (mavlink/mavlink) defines them.
TEST(formatsMavlink, EachKnownMessagesCrcExtraAndLengthsFollowFromItsDefinition) {
  struct Definition {
    std::uint32_t id;
    std::string_view name;
    std::vector<std::string_view> fields;
    std::size_t min_length, max_length;
  };
  const std::vector<Definition> definitions{
      {0, "HEARTBEAT",
       {"uint32_t custom_mode", "uint8_t type", "uint8_t autopilot", "uint8_t base_mode", "uint8_t system_status",
        "uint8_t_mavlink_version mavlink_version"},
       9, 9},
      {22, "PARAM_VALUE",
       {"float param_value", "uint16_t param_count", "uint16_t param_index", "char[16] param_id", "uint8_t param_type"},
       25, 25},
      {29, "SCALED_PRESSURE", {"uint32_t time_boot_ms", "float press_abs", "float press_diff", "int16_t temperature"}, 14, 16},
      {30, "ATTITUDE",
       {"uint32_t time_boot_ms", "float roll", "float pitch", "float yaw", "float rollspeed", "float pitchspeed",
        "float yawspeed"},
       28, 28},
      {32, "LOCAL_POSITION_NED",
       {"uint32_t time_boot_ms", "float x", "float y", "float z", "float vx", "float vy", "float vz"}, 28, 28},
      {33, "GLOBAL_POSITION_INT",
       {"uint32_t time_boot_ms", "int32_t lat", "int32_t lon", "int32_t alt", "int32_t relative_alt", "int16_t vx",
        "int16_t vy", "int16_t vz", "uint16_t hdg"},
       28, 28},
      {137, "SCALED_PRESSURE2", {"uint32_t time_boot_ms", "float press_abs", "float press_diff", "int16_t temperature"}, 14, 16},
      {143, "SCALED_PRESSURE3", {"uint32_t time_boot_ms", "float press_abs", "float press_diff", "int16_t temperature"}, 14, 16},
      {11011, "VISION_POSITION_DELTA",
       {"uint64_t time_usec", "uint64_t time_delta_usec", "float[3] angle_delta", "float[3] position_delta",
        "float confidence"},
       44, 44},
  };
  ASSERT_EQ(mavlinkMessages().size(), definitions.size());
  for (const Definition& d : definitions) {
    const MavlinkMessageInfo* info = findMavlinkMessage(d.id);
    ASSERT_NE(info, nullptr) << d.name;
    EXPECT_EQ(info->name, d.name);
    EXPECT_EQ(info->crc_extra, mavlinkCrcExtra(d.name, d.fields)) << d.name;
    EXPECT_EQ(info->min_length, d.min_length) << d.name;
    EXPECT_EQ(info->max_length, d.max_length) << d.name;
  }
  // the values every MAVLink library carries (c_library_v2's MAVLINK_MESSAGE_CRCS)
  EXPECT_EQ(findMavlinkMessage(0)->crc_extra, 50);
  EXPECT_EQ(findMavlinkMessage(22)->crc_extra, 220);
  EXPECT_EQ(findMavlinkMessage(30)->crc_extra, 39);
  EXPECT_EQ(findMavlinkMessage(137)->crc_extra, 195);
  EXPECT_EQ(findMavlinkMessage(11011)->crc_extra, 106);
  EXPECT_EQ(findMavlinkMessage(1), nullptr);
}

TEST(formatsMavlink, ReadsFramesBuiltFromTheSpecificationInBothVersions) {
  for (const bool v2 : {true, false}) {
    const std::string bytes = test::attitudeFrame(1234, 0.5f, -0.25f, 3.0f, {.v2 = v2, .system = 7, .component = 9, .sequence = 200});
    const MavlinkFrameRead read = readMavlinkFrame(bytesOf(bytes + "tail"));
    ASSERT_EQ(read.status, MavlinkFrameStatus::kFrame) << v2;
    EXPECT_EQ(read.size, bytes.size());
    EXPECT_EQ(read.frame.version, v2 ? 2 : 1);
    EXPECT_EQ(read.frame.system, 7);
    EXPECT_EQ(read.frame.component, 9);
    EXPECT_EQ(read.frame.sequence, 200);
    EXPECT_EQ(read.frame.message_id, 30u);
    EXPECT_TRUE(read.frame.checked);
    // MAVLink 2 dropped the zero rates: the payload is restored with zeros
    EXPECT_EQ(read.frame.payload_length, v2 ? 16 : 28);
    const MavlinkAttitude a = *decodeMavlink<MavlinkAttitude>(read.frame);
    EXPECT_EQ(a.time_boot_ms, 1234u);
    EXPECT_EQ(a.roll_rad, 0.5f);
    EXPECT_EQ(a.pitch_rad, -0.25f);
    EXPECT_EQ(a.yaw_rad, 3.0f);
    EXPECT_EQ(a.yawspeed_rad_s, 0.0f);
    EXPECT_FALSE(decodeMavlink<MavlinkLocalPositionNed>(read.frame));
  }
  const std::string signed_frame = test::localPositionNedFrame(5, 1.0f, 2.0f, 3.0f, {.sign = true});
  const MavlinkFrameRead read = readMavlinkFrame(bytesOf(signed_frame));
  EXPECT_EQ(read.status, MavlinkFrameStatus::kFrame);
  EXPECT_TRUE(read.frame.is_signed);
  EXPECT_EQ(read.size, signed_frame.size());
}

TEST(formatsMavlink, NamesWhatIsWrongWithAFrame) {
  const std::string good = test::attitudeFrame(1, 1.0f, 2.0f, 3.0f);
  EXPECT_EQ(readMavlinkFrame(bytesOf("x" + good)).status, MavlinkFrameStatus::kNoMagic);
  EXPECT_EQ(readMavlinkFrame(bytesOf(good.substr(0, 5))).status, MavlinkFrameStatus::kCutShort);
  EXPECT_EQ(readMavlinkFrame(bytesOf(good.substr(0, 5))).size, 0u);  // the header itself is cut
  const MavlinkFrameRead cut = readMavlinkFrame(bytesOf(good.substr(0, good.size() - 1)));
  EXPECT_EQ(cut.status, MavlinkFrameStatus::kCutShort);
  EXPECT_EQ(cut.size, good.size());
  EXPECT_EQ(readMavlinkFrame(bytesOf(test::attitudeFrame(1, 1.0f, 2.0f, 3.0f, {.corrupt = true}))).status,
            MavlinkFrameStatus::kBadChecksum);
  // an ATTITUDE two bytes longer than its definition, with a checksum that matches
  std::string long_payload(30, '\x01');
  EXPECT_EQ(readMavlinkFrame(bytesOf(test::mavlinkFrame(30, 39, long_payload))).status, MavlinkFrameStatus::kBadLength);
  std::string flagged = good;
  flagged[2] = 0x02;  // an incompat flag no one defined
  EXPECT_EQ(readMavlinkFrame(bytesOf(flagged)).status, MavlinkFrameStatus::kBadFlags);
  const MavlinkFrameRead unknown = readMavlinkFrame(bytesOf(test::mavlinkFrame(24, 24, std::string(30, '\x05'))));
  EXPECT_EQ(unknown.status, MavlinkFrameStatus::kUnknownMessage);
  EXPECT_FALSE(unknown.frame.checked);
  EXPECT_EQ(unknown.frame.message_id, 24u);
}

/// A stream as a serial line gives it: noise, a false start (a magic byte and a header that
/// swallows the next frame), frames of both versions, a corrupted one, a signed one, an unknown
/// message, and noise between them.
struct NoisyStream {
  std::string bytes;
  std::vector<std::uint32_t> expected_ids;  // the frames the parser must pass on, in order
  std::size_t frame_bytes = 0;
};

NoisyStream noisyStream() {
  NoisyStream s;
  const auto frame = [&s](const std::string& f, std::uint32_t id) {
    s.bytes += f;
    s.expected_ids.push_back(id);
    s.frame_bytes += f.size();
  };
  s.bytes += "hello\r\n\x01\x02";
  s.bytes += std::string("\xFD\x40\x00\x00", 4);  // a false start: a header whose length reaches past the next frames
  frame(test::attitudeFrame(100, 0.1f, 0.2f, 0.3f), 30);
  frame(test::heartbeatFrame({.v2 = false, .system = 255, .component = 190}), 0);
  s.bytes += test::localPositionNedFrame(100, 9.0f, 9.0f, 9.0f, {.corrupt = true});
  frame(test::localPositionNedFrame(100, 1.0f, 2.0f, 3.0f, {.v2 = false}), 32);
  frame(test::scaledPressure2Frame(100, 1100.0f, {.sign = true}), 137);
  frame(test::mavlinkFrame(24, 24, std::string(30, '\x07')), 24);  // GPS_RAW_INT: unknown here, a frame follows
  frame(test::globalPositionIntFrame(100, -2500), 33);
  s.bytes += test::mavlinkFrame(24, 24, std::string(30, '\x07'));   // unknown, then noise: taken for noise
  s.bytes += std::string("\x00\x00zz", 4);
  frame(test::attitudeFrame(200, 0.4f, 0.5f, 0.6f), 30);
  return s;
}

std::vector<std::uint32_t> idsOf(const std::vector<MavlinkFrame>& frames) {
  std::vector<std::uint32_t> ids;
  for (const MavlinkFrame& f : frames) ids.push_back(f.message_id);
  return ids;
}

TEST(formatsMavlink, TheParserFindsFramesInNoiseAfterFalseStartsAndBadChecksums) {
  const NoisyStream s = noisyStream();
  MavlinkFrameParser parser;
  const std::vector<MavlinkFrame> frames = parser.feed(bytesOf(s.bytes));
  EXPECT_EQ(idsOf(frames), s.expected_ids);
  const MavlinkStreamCounts& c = parser.counts();
  EXPECT_EQ(c.bytes, s.bytes.size());
  EXPECT_EQ(c.frames, 6u);
  EXPECT_EQ(c.unknown_frames, 1u);
  EXPECT_GE(c.bad_frames, 1u);  // the corrupted LOCAL_POSITION_NED (and any false start inside it)
  EXPECT_EQ(parser.heldBytes(), 0u);
  EXPECT_EQ(c.noise_bytes + s.frame_bytes, c.bytes);  // every byte is a frame's or noise
  EXPECT_EQ(decodeMavlink<MavlinkLocalPositionNed>(frames[2])->x_m, 1.0f);
  EXPECT_TRUE(frames[3].is_signed);
  EXPECT_FALSE(frames[4].checked);
}

TEST(formatsMavlink, AnyChunkingOfTheStreamGivesTheSameFrames) {
  const NoisyStream s = noisyStream();
  MavlinkFrameParser whole;
  const std::vector<MavlinkFrame> expected = whole.feed(bytesOf(s.bytes));
  for (std::size_t chunk = 1; chunk <= s.bytes.size(); chunk += (chunk < 40 ? 1 : 17)) {
    MavlinkFrameParser parser;
    std::vector<MavlinkFrame> frames;
    for (std::size_t at = 0; at < s.bytes.size(); at += chunk) parser.feed(bytesOf(s.bytes.substr(at, chunk)), frames);
    ASSERT_EQ(frames.size(), expected.size()) << chunk;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      EXPECT_EQ(frames[i].message_id, expected[i].message_id) << chunk;
      EXPECT_EQ(frames[i].payload, expected[i].payload) << chunk;
    }
    EXPECT_EQ(parser.counts().noise_bytes, whole.counts().noise_bytes) << chunk;
    EXPECT_EQ(parser.counts().bad_frames, whole.counts().bad_frames) << chunk;
  }
}

TEST(formatsMavlink, AFrameCutByTheChunkWaitsForItsRest) {
  const std::string f = test::attitudeFrame(7, 1.0f, 1.0f, 1.0f);
  MavlinkFrameParser parser;
  EXPECT_TRUE(parser.feed(bytesOf(f.substr(0, 12))).empty());
  EXPECT_EQ(parser.heldBytes(), 12u);
  EXPECT_EQ(parser.feed(bytesOf(f.substr(12))).size(), 1u);
  // an unknown message at a datagram's end waits for the next datagram's first byte
  EXPECT_TRUE(parser.feed(bytesOf(test::mavlinkFrame(24, 24, std::string(30, '\x07')))).empty());
  EXPECT_EQ(idsOf(parser.feed(bytesOf(f))), (std::vector<std::uint32_t>{24, 30}));
}

TEST(formatsMavlink, TheEncoderTruncatesMavlink2AndSendsMavlink1WithoutExtensions) {
  MavlinkEncoder v2(1, 1);
  MavlinkPayload pressure = toMavlinkPayload(MavlinkScaledPressure{137, 5000, 1013.25f, 0.0f, 1520, 0});
  const std::vector<std::uint8_t> a = encodeMavlink(v2, pressure);
  EXPECT_EQ(a[0], kMavlinkMagicV2);
  EXPECT_EQ(a[1], 14);  // temperature_press_diff 0 truncated
  EXPECT_EQ(textOf(a), [] {  // the same frame built by the fixture from the specification
    std::string p;
    test::putLittle(p, std::uint32_t{5000});
    test::putLittle(p, 1013.25f);
    test::putLittle(p, 0.0f);
    test::putLittle(p, std::int16_t{1520});
    test::putLittle(p, std::int16_t{0});
    return test::mavlinkFrame(137, 195, p, {.sequence = 0});
  }());
  // all zeros: MAVLink 2 keeps the first byte
  const std::vector<std::uint8_t> zeros = encodeMavlink(v2, toMavlinkPayload(MavlinkAttitude{}));
  EXPECT_EQ(zeros[1], 1);
  EXPECT_EQ(zeros[4], 1);  // the second frame's sequence number
  MavlinkEncoder v1(42, 158, 1);
  const std::vector<std::uint8_t> b = encodeMavlink(v1, pressure);
  EXPECT_EQ(b[0], kMavlinkMagicV1);
  EXPECT_EQ(b[1], 14);  // MAVLink 1 carries no extension fields
  const MavlinkFrameRead read = readMavlinkFrame(b);
  ASSERT_EQ(read.status, MavlinkFrameStatus::kFrame);
  EXPECT_EQ(read.frame.system, 42);
  EXPECT_EQ(read.frame.component, 158);
  EXPECT_THROW(encodeMavlink(v1, toMavlinkPayload(MavlinkVisionPositionDelta{})), ValueError);  // id 11011 > 255
  EXPECT_THROW(v2.encode(24, std::vector<std::uint8_t>(30)), ValueError);
  EXPECT_THROW(v2.encode(30, std::vector<std::uint8_t>(29)), ValueError);
  EXPECT_THROW(MavlinkEncoder(1, 1, 3), ValueError);
  EXPECT_THROW(toMavlinkPayload(MavlinkScaledPressure{30}), ValueError);
  for (int i = 0; i < 300; ++i) v1.encode(0, std::vector<std::uint8_t>(9));
  EXPECT_EQ(v1.nextSequence(), (1 + 300) % 256);
}

TEST(formatsMavlink, EveryMessageComesBackFieldByField) {
  MavlinkEncoder encoder(1, 1);
  const auto roundTrip = [&encoder](const MavlinkPayload& payload) {
    const MavlinkFrameRead read = readMavlinkFrame(encodeMavlink(encoder, payload));
    EXPECT_EQ(read.status, MavlinkFrameStatus::kFrame);
    return read.frame;
  };
  const MavlinkHeartbeat h = *decodeMavlink<MavlinkHeartbeat>(roundTrip(toMavlinkPayload(MavlinkHeartbeat{19, 12, 3, 81, 4, 3})));
  EXPECT_EQ(h.custom_mode, 19u);
  EXPECT_EQ(h.type, 12);
  EXPECT_EQ(h.autopilot, 3);
  EXPECT_EQ(h.base_mode, 81);
  EXPECT_EQ(h.system_status, 4);
  EXPECT_EQ(h.mavlink_version, 3);
  const MavlinkParamValue q =
      *decodeMavlink<MavlinkParamValue>(roundTrip(toMavlinkPayload(MavlinkParamValue{1.024f, 900, 65535, "BARO_SPEC_GRAV", 9})));
  EXPECT_EQ(q.param_value, 1.024f);
  EXPECT_EQ(q.param_count, 900);
  EXPECT_EQ(q.param_index, 65535);
  EXPECT_EQ(q.param_id, "BARO_SPEC_GRAV");
  EXPECT_EQ(q.param_type, 9);
  EXPECT_EQ(decodeMavlink<MavlinkParamValue>(roundTrip(toMavlinkPayload(MavlinkParamValue{0, 1, 0, "SIXTEEN_LETTERS_", 9})))->param_id,
            "SIXTEEN_LETTERS_");  // no NUL after a name of 16
  const MavlinkLocalPositionNed l =
      *decodeMavlink<MavlinkLocalPositionNed>(roundTrip(toMavlinkPayload(MavlinkLocalPositionNed{9, 1.5f, -2.5f, 3.5f, 0.1f, 0.2f, -0.3f})));
  EXPECT_EQ(l.time_boot_ms, 9u);
  EXPECT_EQ(l.y_m, -2.5f);
  EXPECT_EQ(l.vz_m_s, -0.3f);
  const MavlinkGlobalPositionInt g = *decodeMavlink<MavlinkGlobalPositionInt>(
      roundTrip(toMavlinkPayload(MavlinkGlobalPositionInt{8, 473977418, 85455939, -12345, -23456, -5, 6, -7, 35999})));
  EXPECT_EQ(g.lat_degE7, 473977418);
  EXPECT_EQ(g.lon_degE7, 85455939);
  EXPECT_EQ(g.alt_mm, -12345);
  EXPECT_EQ(g.relative_alt_mm, -23456);
  EXPECT_EQ(g.vx_cm_s, -5);
  EXPECT_EQ(g.vz_cm_s, -7);
  EXPECT_EQ(g.hdg_cdeg, 35999);
  const MavlinkScaledPressure p =
      *decodeMavlink<MavlinkScaledPressure>(roundTrip(toMavlinkPayload(MavlinkScaledPressure{143, 7, 1200.5f, -0.5f, -150, 2100})));
  EXPECT_EQ(p.message_id, 143u);
  EXPECT_EQ(p.press_abs_hpa, 1200.5f);
  EXPECT_EQ(p.temperature_cdegc, -150);
  EXPECT_EQ(p.temperature_press_diff_cdegc, 2100);
  MavlinkVisionPositionDelta v;
  v.time_usec = 1723630500123456ULL;
  v.time_delta_usec = 125000;
  v.angle_delta_rad = {0.01f, -0.02f, 0.03f};
  v.position_delta_m = {0.1f, -0.05f, 0.002f};
  v.confidence_percent = 87.5f;
  const MavlinkVisionPositionDelta w = *decodeMavlink<MavlinkVisionPositionDelta>(roundTrip(toMavlinkPayload(v)));
  EXPECT_EQ(w.time_usec, v.time_usec);
  EXPECT_EQ(w.time_delta_usec, v.time_delta_usec);
  EXPECT_EQ(w.angle_delta_rad, v.angle_delta_rad);
  EXPECT_EQ(w.position_delta_m, v.position_delta_m);
  EXPECT_EQ(w.confidence_percent, v.confidence_percent);
}

}  // namespace
}  // namespace sonarmap
