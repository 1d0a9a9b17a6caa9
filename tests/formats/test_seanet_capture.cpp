/// Tests of parseSeaNetCapture / readSeaNetCapture: SeaNet packets built byte by byte from the
/// protocol (wire_fixture.hpp), 8-bit and 4-bit bins, garbage and other messages between packets,
/// a capture cut inside its last packet, bad fields; and the packets of V4LOG records re-framed as
/// a wire capture give the V4LOG reader's beams (synthetic, and the shared log when present).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/seanet_capture.hpp"
#include "sonarmap/formats/v4log_reader.hpp"
#include "sonarmap/formats/wire_encoder.hpp"
#include "wire_fixture.hpp"

namespace sonarmap {
namespace {

using test::SeaNetHeadPacket;
using test::seanetHeadData;
using test::seanetOther;

constexpr double kPi = std::numbers::pi;
const std::string kSectorLog = std::string(SONARMAP_SHARED_DATA) + "/seanet_sector_target.V4LOG";

SonarLog parse(const std::string& bytes, const CaptureOptions& options = {}) {
  return parseSeaNetCapture(std::span(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()), "cap.seanet",
                            options);
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// The FileError message of parsing `bytes`, or "" when nothing is thrown.
std::string errorOf(const std::string& bytes) {
  try {
    parse(bytes);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

void expectSameBeams(const SonarLog& wire, const SonarLog& v4) {
  ASSERT_EQ(wire.beams.size(), v4.beams.size());
  for (std::size_t i = 0; i < v4.beams.size(); ++i) {
    ASSERT_EQ(wire.beams[i].bearing_rad, v4.beams[i].bearing_rad) << "beam " << i;
    ASSERT_EQ(wire.beams[i].bin_length_m, v4.beams[i].bin_length_m) << "beam " << i;
    ASSERT_EQ(wire.beams[i].intensities, v4.beams[i].intensities) << "beam " << i;
    ASSERT_EQ(wire.beams[i].intensity_span_db, v4.beams[i].intensity_span_db) << "beam " << i;
  }
}

TEST(formatsSeaNetCapture, ConvertsPacketsBuiltFromTheSpec) {
  SeaNetHeadPacket ahead;  // 8-bit bins, an upright head (HdCtrl invert clear)
  ahead.head_control = 0x2305;
  ahead.bearing = 3200;  // Tritech's ahead
  ahead.ad_interval = 10;
  ahead.data = {0, 7, 255, 128};
  SeaNetHeadPacket four_bit;
  four_bit.head_control = 0x2304;  // adc8on clear: two 4-bit bins per byte; upright
  four_bit.bearing = 4800;         // a quarter turn clockwise from ahead: starboard
  four_bit.ad_span = 0;            // no span: unknown
  four_bit.data = {0xF1, 0x0A};
  SeaNetHeadPacket last;
  last.head_control = 0x2305;
  last.bearing = 3201;
  const std::string capture = seanetHeadData(ahead) + seanetHeadData(four_bit) + seanetHeadData(last);
  ASSERT_EQ(capture.size(), 4 + 45 + 2 + 45 + 3 + 45u);  // data bytes + 45 each

  const SonarLog log = parse(capture);
  ASSERT_EQ(log.beams.size(), 3u);
  EXPECT_EQ(log.skipped_beams, 0u);
  EXPECT_DOUBLE_EQ(log.beams[0].bearing_rad, 0.0);
  EXPECT_NEAR(log.beams[0].bin_length_m, 10 * 640e-9 * 1500.0 / 2.0, 1e-15);  // 4.8 mm
  EXPECT_EQ(log.beams[0].intensities, (std::vector<std::uint8_t>{0, 7, 255, 128}));
  ASSERT_TRUE(log.beams[0].intensity_span_db.has_value());
  EXPECT_NEAR(*log.beams[0].intensity_span_db, 149 * 80.0 / 255.0, 1e-12);
  EXPECT_NEAR(log.beams[1].bearing_rad, 0.5 * kPi, 1e-12);  // clockwise 90°, as beam.hpp counts
  EXPECT_EQ(log.beams[1].intensities, (std::vector<std::uint8_t>{255, 17, 0, 170}));  // high nibble first, ×17
  EXPECT_FALSE(log.beams[1].intensity_span_db.has_value());
  EXPECT_NEAR(log.beams[1].bin_length_m, 33 * 640e-9 * 750.0, 1e-15);
  EXPECT_NEAR(log.beams[2].bearing_rad, 2.0 * kPi / 6400, 1e-12);
  for (const Beam& beam : log.beams) EXPECT_EQ(beam.time_s, 0.0);  // no clock in the protocol

  const SonarLog timed = parse(capture, CaptureOptions{1400.0, 0.25});
  EXPECT_NEAR(timed.beams[0].bin_length_m, 10 * 640e-9 * 700.0, 1e-15);
  EXPECT_DOUBLE_EQ(timed.beams[2].time_s, 0.5);
}

TEST(formatsSeaNetCapture, AheadIsBearingZeroAndInvertReversesTheTurn) {
  // Beams ahead, a quarter turn to starboard and one step to port, as the project's encoder writes them.
  std::vector<Beam> beams(3);
  const double bearings_rad[] = {0.0, 0.5 * kPi, 2.0 * kPi - 2.0 * kPi / 6400};
  for (std::size_t i = 0; i < beams.size(); ++i) {
    beams[i].bearing_rad = bearings_rad[i];
    beams[i].bin_length_m = 0.05;
    beams[i].intensities = {1, 2, 3};
  }
  std::vector<std::uint8_t> bytes = encodeSeaNetCapture(beams);
  // The head's own count in each 48-byte packet (bytes 40–41): ahead 3200, clockwise.
  ASSERT_EQ(bytes.size(), 3u * 48u);
  const unsigned expected_counts[] = {3200, 4800, 3199};
  for (std::size_t i = 0; i < beams.size(); ++i) {
    EXPECT_EQ(bytes[48 * i + 40] | (bytes[48 * i + 41] << 8), expected_counts[i]) << "packet " << i;
  }
  const auto read = [&] {
    return parse(std::string(bytes.begin(), bytes.end()));
  };
  const SonarLog upright = read();
  ASSERT_EQ(upright.beams.size(), 3u);
  for (std::size_t i = 0; i < beams.size(); ++i) EXPECT_NEAR(upright.beams[i].bearing_rad, bearings_rad[i], 1e-12);
  // HdCtrl bit 3 `invert` (bytes 18–19): the head upside down counts the other way seen from above.
  for (std::size_t i = 0; i < beams.size(); ++i) bytes[48 * i + 18] |= 0x08;
  const SonarLog inverted = read();
  ASSERT_EQ(inverted.beams.size(), 3u);
  EXPECT_NEAR(inverted.beams[0].bearing_rad, 0.0, 1e-12);         // ahead stays ahead
  EXPECT_NEAR(inverted.beams[1].bearing_rad, 1.5 * kPi, 1e-12);   // starboard of the head: port
  EXPECT_NEAR(inverted.beams[2].bearing_rad, 2.0 * kPi / 6400, 1e-12);
}

TEST(formatsSeaNetCapture, SkipsAndCountsGarbageAndOtherMessages) {
  SeaNetHeadPacket a;
  a.bearing = 100;
  SeaNetHeadPacket b;
  b.bearing = 164;
  const std::string noise = std::string("\x00\xFFnoise@12", 9);  // a false '@' whose length is not hex
  const std::string capture = noise + seanetOther(4, 8) + seanetHeadData(a) + seanetOther(1, 12) + "@@" +
                              seanetHeadData(b) + "tail";
  const SonarLog log = parse(capture);
  ASSERT_EQ(log.beams.size(), 2u);
  EXPECT_NEAR(log.beams[1].bearing_rad, 2 * kPi * (3200 - 164) / 6400, 1e-12);  // the fixture's head is inverted
  ASSERT_EQ(log.skipped_beams, 5u);
  ASSERT_EQ(log.skip_reasons.size(), 5u);
  EXPECT_EQ(log.skip_reasons[0], "cap.seanet: byte 0 to byte 8: 9 bytes outside any packet (at byte 7: length is not "
                                 "4 ASCII hex digits)");
  EXPECT_EQ(log.skip_reasons[1], "cap.seanet: packet at byte 9: message type 4, not mtHeadData (2)");
  EXPECT_TRUE(contains(log.skip_reasons[2], "message type 1, not mtHeadData")) << log.skip_reasons[2];
  EXPECT_TRUE(contains(log.skip_reasons[3], ": 2 bytes outside any packet")) << log.skip_reasons[3];
  EXPECT_TRUE(contains(log.skip_reasons[4], ": 4 bytes outside any packet")) << log.skip_reasons[4];
}

TEST(formatsSeaNetCapture, ACaptureCutInsideItsLastPacketKeepsTheWholeOnes) {
  const std::string whole = seanetHeadData({}) + seanetOther(4, 8);
  const std::string last = seanetHeadData({});
  for (std::size_t cut = 1; cut < last.size(); ++cut) {
    const SonarLog log = parse(whole + last.substr(0, cut));
    ASSERT_EQ(log.beams.size(), 1u) << "cut at " << cut;
    ASSERT_EQ(log.skipped_beams, 2u) << "cut at " << cut;
    const std::string& reason = log.skip_reasons.back();
    ASSERT_TRUE(contains(reason, "packet at byte " + std::to_string(whole.size()) + " cut short")) << reason;
    if (cut >= 7) {
      ASSERT_TRUE(contains(reason, "declares 48 bytes, the capture ends " + std::to_string(cut))) << reason;
    }
  }
}

TEST(formatsSeaNetCapture, SkipsPacketsWithBadFieldsOrFraming) {
  SeaNetHeadPacket zero_interval;
  zero_interval.ad_interval = 0;
  SeaNetHeadPacket bad_bearing;
  bad_bearing.bearing = 6400;
  SeaNetHeadPacket count_too_big;
  count_too_big.data_count = 4;
  SeaNetHeadPacket extra;  // not data bytes + 45: e.g. a profiling head's layout
  extra.extra_bytes = 2;
  SeaNetHeadPacket empty;
  empty.data.clear();
  std::string no_lf = seanetHeadData({});
  no_lf.back() = '\r';
  std::string lengths_differ = seanetHeadData({});
  lengths_differ[5] = static_cast<char>(lengths_differ[5] + 1);
  const std::string good = seanetHeadData({});
  const std::string capture = seanetHeadData(zero_interval) + seanetHeadData(bad_bearing) + seanetHeadData(count_too_big) +
                              seanetHeadData(extra) + seanetHeadData(empty) + no_lf + lengths_differ + good;
  const SonarLog log = parse(capture);
  ASSERT_EQ(log.beams.size(), 1u);
  ASSERT_EQ(log.skip_reasons.size(), 6u);
  EXPECT_EQ(log.skip_reasons[0], "cap.seanet: byte 33: ADInterval of packet at byte 0 is 0, expected > 0 (units of 640 "
                                 "ns; bin length 0 m)");
  EXPECT_EQ(log.skip_reasons[1], "cap.seanet: byte 88: bearing of packet at byte 48 is 6400, expected 0…6399 (1/16 gradian)");
  EXPECT_EQ(log.skip_reasons[2], "cap.seanet: byte 138: data byte count of packet at byte 96 is 4 but the packet holds 3 "
                                 "bytes after its 44-byte header");
  EXPECT_EQ(log.skip_reasons[3], "cap.seanet: packet at byte 144: 2 bytes between its data bytes and the LF, expected "
                                 "none (an imaging head's packet is data bytes + 45 bytes)");
  EXPECT_EQ(log.skip_reasons[4], "cap.seanet: packet at byte 194: mtHeadData with no data bytes");
  EXPECT_EQ(log.skip_reasons[5], "cap.seanet: byte 239 to byte 334: 96 bytes outside any packet (at byte 239: no LF at "
                                 "its end (byte 286))");
}

TEST(formatsSeaNetCapture, ThrowsOnlyWhenNothingIsUsable) {
  EXPECT_TRUE(contains(errorOf(""), "cap.seanet: no beam in 0 bytes, expected SeaNet mtHeadData packets"));
  const std::string alive = errorOf(seanetOther(4, 8) + seanetOther(4, 8));
  EXPECT_TRUE(contains(alive, "no beam in 44 bytes")) << alive;
  EXPECT_TRUE(contains(alive, "(packet at byte 0: message type 4, not mtHeadData (2))")) << alive;
  const std::string text = errorOf("time,angle\n1,2\n");
  EXPECT_TRUE(contains(text, "(byte 0 to byte 14: 15 bytes outside any packet)")) << text;
  EXPECT_THROW(parse(seanetHeadData({}), CaptureOptions{0.0, 0.0}), ValueError);
  EXPECT_THROW(parse(seanetHeadData({}), CaptureOptions{1500.0, -1.0}), ValueError);
  EXPECT_THROW(parse(seanetHeadData({}), CaptureOptions{1500.0, std::numeric_limits<double>::infinity()}), ValueError);
}

TEST(formatsSeaNetCapture, ReframedV4RecordsGiveTheV4LogBeams) {
  std::vector<test::V4Record> records(3);
  records[1].head_control = 0x230C;  // 4-bit
  records[1].bearing = 1234;
  records[1].data = {0x12, 0xEF};
  records[2].ad_interval = 7;
  records[2].bearing = 6000;
  records[2].appended_bytes = 5;
  std::string capture;
  for (const test::V4Record& record : records) capture += test::seanetPacketOfV4Record(test::v4RecordBytes(record));
  const std::string v4 = test::v4log(records);
  const SonarLog from_v4 =
      parseSeaNetV4Log(std::span(reinterpret_cast<const unsigned char*>(v4.data()), v4.size()), "synthetic.V4LOG");
  const SonarLog from_wire = parse(capture);
  EXPECT_EQ(from_wire.skipped_beams, 0u);
  expectSameBeams(from_wire, from_v4);
}

TEST(formatsSeaNetCapture, TheSharedV4LogReframedAsAWireCaptureGivesTheSameBeams) {
  if (!std::filesystem::exists(kSectorLog)) GTEST_SKIP() << "no shared data at " << kSectorLog;
  std::ifstream in(kSectorLog, std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t data_offset = 0;
  std::uint32_t record_count = 0;
  for (int i = 3; i >= 0; --i) {
    data_offset = (data_offset << 8) | static_cast<unsigned char>(file[test::kV4DataOffsetAt + i]);
    record_count = (record_count << 8) | static_cast<unsigned char>(file[test::kV4RecordCountAt + i]);
  }
  std::string capture = "\r\n";  // line noise before the first packet
  for (std::size_t at = data_offset, i = 0; i < record_count; ++i) {
    const std::size_t length = static_cast<unsigned char>(file[at]) | (static_cast<unsigned char>(file[at + 1]) << 8);
    capture += test::seanetPacketOfV4Record(std::string_view(file).substr(at, length));
    if (i % 50 == 0) capture += seanetOther(4, 8);  // the head's mtAlive between beams
    at += length;
  }
  const SonarLog from_v4 = readSonarLog(kSectorLog);
  ASSERT_EQ(from_v4.beams.size(), 468u);
  const SonarLog from_wire = parse(capture);
  EXPECT_EQ(from_wire.skipped_beams, 1u + 10u);  // the noise, the mtAlive packets
  expectSameBeams(from_wire, from_v4);
}

TEST(formatsSeaNetCapture, ReadSonarLogByExtensionOrByName) {
  test::TempDir dir;
  const std::string capture = seanetHeadData({}) + seanetHeadData({});
  for (const char* name : {"a.seanet", "b.SEANET", "c.raw"}) {
    std::ofstream(dir.file(name), std::ios::binary) << capture;
  }
  EXPECT_EQ(readSonarLog(dir.file("a.seanet")).beams.size(), 2u);
  EXPECT_EQ(readSonarLog(dir.file("b.SEANET")).beams.size(), 2u);
  EXPECT_THROW(readSonarLog(dir.file("c.raw")), FileError);  // unknown extension
  EXPECT_EQ(readSonarLog(dir.file("c.raw"), parseLogFormat("seanet")).beams.size(), 2u);
  EXPECT_EQ(readSeaNetCapture(dir.file("c.raw")).beams.size(), 2u);
  EXPECT_THROW(readSeaNetCapture(dir.file("missing.seanet")), FileError);
}

}  // namespace
}  // namespace sonarmap
