/// Tests of the Ping360 readers: ping-protocol messages built byte by byte from the protocol
/// (wire_fixture.hpp): device_data and auto_device_data, bad checksums, other messages and noise
/// between messages, a stream cut inside its last message, bad fields; Ping Viewer logs (UTF-8
/// and UTF-16 strings, messages split across records, their times); dispatch by content and name.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/ping360_reader.hpp"
#include "wire_fixture.hpp"

namespace sonarmap {
namespace {

using test::Ping360Data;
using test::ping360Message;
using test::pingMessage;
using test::pingViewerLog;

constexpr double kPi = std::numbers::pi;

std::span<const unsigned char> spanOf(const std::string& bytes) {
  return {reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()};
}
SonarLog parseStream(const std::string& bytes, const CaptureOptions& options = {}) {
  return parsePing360Stream(spanOf(bytes), "ping.bin", options);
}
SonarLog parseLog(const std::string& bytes) { return parsePingViewerLog(spanOf(bytes), "viewer.bin"); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

template <class Parse>
std::string fileErrorOf(Parse&& parse) {
  try {
    parse();
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

// ---- raw message streams -------------------------------------------------------------------------

TEST(formatsPing360, ConvertsDeviceDataAndAutoDeviceData) {
  Ping360Data ahead;
  ahead.data = {0, 9, 255};
  Ping360Data right;  // 100 gradians clockwise: a quarter turn to starboard
  right.auto_device_data = true;
  right.angle = 100;
  right.sample_period = 1000;  // 25 µs
  right.data = std::vector<std::uint8_t>(1200, 7);
  Ping360Data last;
  last.angle = 399;
  const SonarLog log = parseStream(ping360Message(ahead) + ping360Message(right) + ping360Message(last));
  ASSERT_EQ(log.beams.size(), 3u);
  EXPECT_EQ(log.skipped_beams, 0u);
  EXPECT_DOUBLE_EQ(log.beams[0].bearing_rad, 0.0);
  EXPECT_NEAR(log.beams[0].bin_length_m, 80 * 25e-9 * 1500.0 / 2.0, 1e-15);  // 1.5 mm
  EXPECT_EQ(log.beams[0].intensities, (std::vector<std::uint8_t>{0, 9, 255}));
  EXPECT_FALSE(log.beams[0].intensity_span_db.has_value());
  // the fixture's transmit duration, 32 µs, is a pulse of 2.4 cm at 1500 m/s
  ASSERT_TRUE(log.beams[0].pulse_length_m.has_value());
  EXPECT_NEAR(*log.beams[0].pulse_length_m, 32e-6 * 1500.0 / 2.0, 1e-15);
  EXPECT_NEAR(log.beams[1].bearing_rad, 0.5 * kPi, 1e-12);  // clockwise, as beam.hpp counts
  EXPECT_NEAR(log.beams[1].bin_length_m, 0.01875, 1e-15);  // 1200 samples reach 22.5 m
  EXPECT_EQ(log.beams[1].intensities.size(), 1200u);
  EXPECT_NEAR(log.beams[2].bearing_rad, 2.0 * kPi * 399 / 400, 1e-12);  // one gradian to port of ahead
  for (const Beam& beam : log.beams) EXPECT_EQ(beam.time_s, 0.0);

  const SonarLog timed = parseStream(ping360Message(ahead) + ping360Message(last), CaptureOptions{1450.0, 0.1});
  EXPECT_NEAR(timed.beams[0].bin_length_m, 80 * 25e-9 * 725.0, 1e-15);
  EXPECT_NEAR(*timed.beams[0].pulse_length_m, 32e-6 * 725.0, 1e-15);
  EXPECT_DOUBLE_EQ(timed.beams[1].time_s, 0.1);
}

TEST(formatsPing360, SkipsBadChecksumsOtherMessagesAndNoise) {
  std::string corrupted = ping360Message({});
  corrupted[12] = static_cast<char>(corrupted[12] ^ 0x01);  // a flipped bit in the transmit duration
  const std::string ack = pingMessage(1, std::string("\xB0\x04", 2));  // ack of 1200
  Ping360Data second;
  second.angle = 200;
  const std::string stream = "xxBR" + ack + ping360Message({}) + corrupted + ping360Message(second) + "B";
  const SonarLog log = parseStream(stream);
  ASSERT_EQ(log.beams.size(), 2u);
  EXPECT_NEAR(log.beams[1].bearing_rad, kPi, 1e-12);
  ASSERT_EQ(log.skip_reasons.size(), 4u);
  EXPECT_TRUE(contains(log.skip_reasons[0], "ping.bin: byte 0 to byte 3: 4 bytes outside any message")) << log.skip_reasons[0];
  EXPECT_EQ(log.skip_reasons[1], "ping.bin: message at byte 4: id 1, not device_data (2300) or auto_device_data (2301)");
  const std::size_t corrupted_at = 4 + ack.size() + ping360Message({}).size();
  EXPECT_TRUE(contains(log.skip_reasons[2], "byte " + std::to_string(corrupted_at) + " to byte " +
                                                std::to_string(corrupted_at + corrupted.size() - 1) + ": " +
                                                std::to_string(corrupted.size()) + " bytes outside any message (at byte " +
                                                std::to_string(corrupted_at) + ": checksum "))
      << log.skip_reasons[2];
  EXPECT_TRUE(contains(log.skip_reasons[3], ": 1 bytes outside any message")) << log.skip_reasons[3];

  // A message longer than Ping Viewer's parser takes (10,240 bytes) is not one.
  const std::string huge = pingMessage(3, std::string(10231, 'a'));
  const SonarLog after_huge = parseStream(huge + ping360Message({}));
  ASSERT_EQ(after_huge.beams.size(), 1u);
  EXPECT_TRUE(contains(after_huge.skip_reasons.at(0), "(at byte 0: declares 10241 bytes, expected fewer than 10240)"))
      << after_huge.skip_reasons.at(0);
}

TEST(formatsPing360, AStreamCutInsideItsLastMessageKeepsTheWholeOnes) {
  const std::string whole = ping360Message({}) + pingMessage(5, "\x01\x02\x03\x00");
  const std::string last = ping360Message({});
  for (std::size_t cut = 2; cut < last.size(); ++cut) {
    const SonarLog log = parseStream(whole + last.substr(0, cut));
    ASSERT_EQ(log.beams.size(), 1u) << "cut at " << cut;
    ASSERT_EQ(log.skipped_beams, 2u) << "cut at " << cut;
    ASSERT_TRUE(contains(log.skip_reasons.back(), "message at byte " + std::to_string(whole.size()) + " cut short"))
        << log.skip_reasons.back();
  }
}

TEST(formatsPing360, SkipsDeviceDataWithBadFields) {
  Ping360Data bad_angle;
  bad_angle.angle = 400;
  Ping360Data zero_period;
  zero_period.sample_period = 0;
  Ping360Data short_data;
  short_data.data_length = 2;  // three samples follow
  Ping360Data no_samples;
  no_samples.data.clear();
  const std::string truncated_payload = pingMessage(2300, std::string(6, '\0'));
  const SonarLog log = parseStream(ping360Message(bad_angle) + ping360Message(zero_period) + ping360Message(short_data) +
                                   ping360Message(no_samples) + truncated_payload + ping360Message({}));
  ASSERT_EQ(log.beams.size(), 1u);
  ASSERT_EQ(log.skip_reasons.size(), 5u);
  EXPECT_EQ(log.skip_reasons[0], "ping.bin: message at byte 0 (device_data): angle 400, expected 0…399 gradians");
  EXPECT_TRUE(contains(log.skip_reasons[1], "(device_data): sample period 0, expected > 0 (units of 25 ns)"));
  EXPECT_TRUE(contains(log.skip_reasons[2], "(device_data): data length 2 but the payload holds 3 bytes after its fields"));
  EXPECT_TRUE(contains(log.skip_reasons[3], "(device_data): no samples"));
  EXPECT_TRUE(contains(log.skip_reasons[4], "(device_data): payload of 6 bytes, expected at least 14"));
}

TEST(formatsPing360, ThrowsOnlyWhenNothingIsUsable) {
  EXPECT_TRUE(contains(fileErrorOf([] { parseStream(""); }), "ping.bin: no beam in 0 bytes, expected Ping360 device_data"));
  const std::string acks = fileErrorOf([] { parseStream(pingMessage(1, "\x01\x00") + pingMessage(1, "\x01\x00")); });
  EXPECT_TRUE(contains(acks, "(message at byte 0: id 1, not device_data (2300) or auto_device_data (2301))")) << acks;
  EXPECT_THROW(parseStream(ping360Message({}), CaptureOptions{-1500.0, 0.0}), ValueError);
}

// ---- Ping Viewer logs ----------------------------------------------------------------------------

TEST(formatsPingViewerLog, ReadsMessagesWithTheirRecordTimes) {
  for (const bool utf16 : {false, true}) {
    Ping360Data second;
    second.angle = 50;
    const std::string split = ping360Message(second);
    Ping360Data third;
    third.angle = 52;
    const std::string log_bytes = pingViewerLog({{"00:00:01.250", ping360Message({})},
                                                 {"00:00:01.300", split.substr(0, 10)},
                                                 {"00:01:02.005", split.substr(10) + ping360Message(third)},
                                                 {"01:00:00.000", pingMessage(1, "\x01\x00")}},
                                                utf16);
    ASSERT_TRUE(isPingViewerLog(spanOf(log_bytes)));
    const SonarLog log = parseLog(log_bytes);
    ASSERT_EQ(log.beams.size(), 3u) << "utf16 " << utf16;
    EXPECT_DOUBLE_EQ(log.beams[0].time_s, 1.25);
    EXPECT_DOUBLE_EQ(log.beams[1].time_s, 62.005);  // its last byte came with the third record
    EXPECT_DOUBLE_EQ(log.beams[2].time_s, 62.005);
    EXPECT_NEAR(log.beams[1].bearing_rad, 2 * kPi * 50 / 400, 1e-12);
    ASSERT_EQ(log.skip_reasons.size(), 1u);
    EXPECT_TRUE(contains(log.skip_reasons[0], "(record 3): id 1, not device_data")) << log.skip_reasons[0];
  }
}

TEST(formatsPingViewerLog, KeepsRecordsWithUnreadableTimesAndStopsAtACutOne) {
  Ping360Data later;
  later.angle = 10;
  // A one-digit hour reads; a time that is no time keeps its data (the stream goes on through it)
  // at the previous record's time, with a note.
  const std::string good = pingViewerLog({{"00:00:00.100", ping360Message({})},
                                          {"0:00:00.200", ping360Message({})},
                                          {"soon", ping360Message({})},
                                          {"00:00:00.300", ping360Message(later)}});
  const SonarLog log = parseLog(good + test::qtString("00:00:00.400", false) + test::qtByteArray("BR").substr(0, 5));
  ASSERT_EQ(log.beams.size(), 4u);
  EXPECT_DOUBLE_EQ(log.beams[1].time_s, 0.2);
  EXPECT_DOUBLE_EQ(log.beams[2].time_s, 0.2);
  EXPECT_DOUBLE_EQ(log.beams[3].time_s, 0.3);
  ASSERT_EQ(log.notes.size(), 1u);
  EXPECT_TRUE(contains(log.notes[0], "viewer.bin: 1 record time(s) unreadable, their data kept at the previous record's time (the first: record 2 at byte "))
      << log.notes[0];
  EXPECT_TRUE(contains(log.notes[0], ": 'soon')")) << log.notes[0];
  ASSERT_EQ(log.skip_reasons.size(), 1u);
  EXPECT_TRUE(contains(log.skip_reasons[0], "record 4 at byte " + std::to_string(good.size()) +
                                                ": data of 2 bytes, the file ends 1 bytes after their start"))
      << log.skip_reasons[0];
}

TEST(formatsPingViewerLog, ReadsTimeStampsWrittenWithTheDigitsOfAnyLocale) {
  // Qt writes the time with the recording computer's locale digits: Persian (U+06F0…), Arabic-Indic
  // (U+0660…), Devanagari (U+0966…), as UTF-16BE on Windows and UTF-8 elsewhere.
  const auto digits = [](char32_t zero, const std::string& ascii, bool utf16) {
    std::string bytes;
    for (const char c : ascii) {
      const char32_t code = c >= '0' && c <= '9' ? zero + static_cast<char32_t>(c - '0') : static_cast<char32_t>(c);
      if (utf16) {
        bytes += static_cast<char>(code >> 8);
        bytes += static_cast<char>(code & 0xFF);
      } else if (code < 0x80) {
        bytes += static_cast<char>(code);
      } else {  // two or three UTF-8 bytes
        if (code < 0x800) {
          bytes += static_cast<char>(0xC0 | (code >> 6));
        } else {
          bytes += static_cast<char>(0xE0 | (code >> 12));
          bytes += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
        }
        bytes += static_cast<char>(0x80 | (code & 0x3F));
      }
    }
    std::string out;
    test::putBigU32(out, static_cast<std::uint32_t>(bytes.size()));
    return out + bytes;
  };
  for (const bool utf16 : {true, false}) {
    for (const char32_t zero : {U'\u06F0', U'\u0660', U'\u0966', U'0'}) {
      const std::string log_bytes = test::pingViewerHeader(utf16) + digits(zero, "00:01:02.394", utf16) +
                                    test::qtByteArray(ping360Message({})) + digits(zero, "01:00:00.005", utf16) +
                                    test::qtByteArray(ping360Message({}));
      const SonarLog log = parseLog(log_bytes);
      ASSERT_EQ(log.beams.size(), 2u) << static_cast<int>(zero);
      EXPECT_DOUBLE_EQ(log.beams[0].time_s, 62.394);
      EXPECT_DOUBLE_EQ(log.beams[1].time_s, 3600.005);
      EXPECT_TRUE(log.notes.empty());
    }
  }
}

TEST(formatsPingViewerLog, RejectsAForeignHeader) {
  const std::string records = test::qtString("00:00:00.100", false) + test::qtByteArray(ping360Message({}));
  std::string version_two = test::pingViewerHeader(false, 2) + records;
  EXPECT_TRUE(contains(fileErrorOf([&] { parseLog(version_two); }), "viewer.bin: byte 30: log version is 2, expected 1"));
  const std::string header = test::pingViewerHeader();
  EXPECT_TRUE(contains(fileErrorOf([&] { parseLog(header.substr(0, 40)); }), "file ends inside the git hash string"));
  EXPECT_TRUE(contains(fileErrorOf([&] { parseLog("PingViewer"); }), "not a Ping Viewer log"));
  EXPECT_TRUE(contains(fileErrorOf([&] { parseLog(header); }), "no beam in"));
}

TEST(formatsPingViewerLog, ReadPing360TellsALogFromAStreamAndReadSonarLogTakesTheName) {
  test::TempDir dir;
  const std::string stream = ping360Message({}) + ping360Message({});
  std::ofstream(dir.file("raw.bin"), std::ios::binary) << stream;
  std::ofstream(dir.file("viewer.BIN"), std::ios::binary) << pingViewerLog({{"00:00:02.000", stream}});
  std::ofstream(dir.file("capture.dat"), std::ios::binary) << stream;
  EXPECT_EQ(readSonarLog(dir.file("raw.bin")).beams.size(), 2u);
  const SonarLog viewer = readSonarLog(dir.file("viewer.BIN"));
  ASSERT_EQ(viewer.beams.size(), 2u);
  EXPECT_DOUBLE_EQ(viewer.beams[1].time_s, 2.0);
  EXPECT_EQ(readSonarLog(dir.file("capture.dat"), parseLogFormat("PING360")).beams.size(), 2u);
  EXPECT_EQ(readPing360(dir.file("capture.dat")).beams.size(), 2u);
}

TEST(formatsLogFormat, NamesAndExtensions) {
  for (const LogFormat format : {LogFormat::kMat, LogFormat::kCsv, LogFormat::kV4Log, LogFormat::kSeaNet, LogFormat::kPing360,
                                  LogFormat::kRosBag, LogFormat::kMcap, LogFormat::kRosbag2}) {
    EXPECT_EQ(parseLogFormat(logFormatName(format)), format);
  }
  EXPECT_EQ(logFormatOfPath("a/b.V4LOG"), LogFormat::kV4Log);
  EXPECT_EQ(logFormatOfPath("x.seanet"), LogFormat::kSeaNet);
  EXPECT_EQ(logFormatOfPath("20250101-120000000.bin"), LogFormat::kPing360);
  EXPECT_EQ(logFormatOfPath("2014-07-18-20-59-31.BAG"), LogFormat::kRosBag);
  EXPECT_EQ(logFormatOfPath("rosbag2_2024_05_01/rosbag2_0.mcap"), LogFormat::kMcap);
  EXPECT_EQ(logFormatOfPath("x.txt"), std::nullopt);
  EXPECT_EQ(logFormatOfPath("dive.mcap.part"), LogFormat::kMcap);  // a recording cut short
  EXPECT_EQ(logFormatOfPath("x.part"), std::nullopt);
  try {
    parseLogFormat("micron");
    ADD_FAILURE() << "no ValueError for an unknown format name";
  } catch (const ValueError& e) {
    EXPECT_TRUE(contains(e.what(), "'micron', expected mat, csv, v4log, seanet, ping360, rosbag, mcap, rosbag2")) << e.what();
  }
}

}  // namespace
}  // namespace sonarmap
