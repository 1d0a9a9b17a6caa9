/// Tests of WireStreamDecoder: SeaNet and Ping360 streams built byte by byte (wire_fixture.hpp),
/// with noise, other messages, bad checksums, false starts and a frame cut at the end, fed in
/// chunks of every size from 1 byte up and in random chunkings, give the beams and skip lines of
/// the whole stream parsed at once (parseSeaNetCapture / parsePing360Stream); beams come out as
/// soon as their frame's last byte is fed.

#include <gtest/gtest.h>

#include <random>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/ping360_reader.hpp"
#include "sonarmap/formats/seanet_capture.hpp"
#include "sonarmap/formats/wire_stream.hpp"
#include "wire_fixture.hpp"

namespace sonarmap {
namespace {

std::span<const std::uint8_t> bytesOf(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

/// A SeaNet stream: beams, noise (with a false '@' and a packet with a bad LF), an mtAlive, and
/// the last packet cut short.
std::string seanetStream() {
  std::string out = "\x01\x02@12zz";
  for (int i = 0; i < 12; ++i) {
    test::SeaNetHeadPacket packet;
    packet.bearing = static_cast<std::uint16_t>(i * 32);
    packet.data = {static_cast<std::uint8_t>(i), 9, 200, 3};
    out += test::seanetHeadData(packet);
    if (i == 3) out += test::seanetOther(4, 6);
    if (i == 5) {
      std::string broken = test::seanetHeadData(packet);
      broken.back() = 'X';  // no LF where the length says
      out += broken + "noise@";
    }
  }
  test::SeaNetHeadPacket cut;
  return out + test::seanetHeadData(cut).substr(0, 30);
}

/// A Ping360 stream: device_data and auto_device_data, a bad checksum, an ack, a lone 'B', and the
/// last message cut short.
std::string ping360Stream() {
  std::string out = "BxB";
  for (int i = 0; i < 12; ++i) {
    test::Ping360Data data;
    data.angle = static_cast<std::uint16_t>(i * 2);
    data.auto_device_data = i % 3 == 0;
    data.data = {static_cast<std::uint8_t>(i), 7, 99};
    out += test::ping360Message(data);
    if (i == 4) {
      std::string bad = test::ping360Message(data);
      bad.back() ^= 0x55;  // checksum off
      out += bad + "B";
    }
    if (i == 7) out += test::pingMessage(1, "\x01\x02");
  }
  return out + test::ping360Message({}).substr(0, 11);
}

struct Decoded {
  std::vector<Beam> beams;
  std::size_t skipped = 0;
  std::vector<std::string> reasons;
};

Decoded decodeInChunks(LogFormat format, const std::string& stream, const std::vector<std::size_t>& chunks) {
  WireStreamDecoder decoder(format, {}, "live");
  Decoded out;
  std::size_t at = 0;
  for (std::size_t i = 0; at < stream.size(); ++i) {
    const std::size_t n = std::min(chunks[i % chunks.size()], stream.size() - at);
    for (Beam& beam : decoder.feed(bytesOf(stream).subspan(at, n))) out.beams.push_back(std::move(beam));
    at += n;
  }
  for (Beam& beam : decoder.finish()) out.beams.push_back(std::move(beam));
  out.skipped = decoder.skippedItems();
  out.reasons = decoder.takeSkipReasons();
  EXPECT_EQ(decoder.bytesFed(), stream.size());
  return out;
}

void expectSame(const Decoded& chunked, const SonarLog& whole, const std::string& how) {
  ASSERT_EQ(chunked.beams.size(), whole.beams.size()) << how;
  for (std::size_t i = 0; i < whole.beams.size(); ++i) {
    EXPECT_EQ(chunked.beams[i].bearing_rad, whole.beams[i].bearing_rad) << how << " beam " << i;
    EXPECT_EQ(chunked.beams[i].bin_length_m, whole.beams[i].bin_length_m) << how << " beam " << i;
    EXPECT_EQ(chunked.beams[i].intensities, whole.beams[i].intensities) << how << " beam " << i;
  }
  EXPECT_EQ(chunked.skipped, whole.skipped_beams) << how;
  EXPECT_EQ(chunked.reasons, whole.skip_reasons) << how;
}

void expectChunkingsAgree(LogFormat format, const std::string& stream, const SonarLog& whole) {
  for (std::size_t size = 1; size <= 70; ++size) expectSame(decodeInChunks(format, stream, {size}), whole, "chunk " + std::to_string(size));
  std::mt19937 random(12);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<std::size_t> chunks(20);
    for (std::size_t& n : chunks) n = std::uniform_int_distribution<std::size_t>(1, 90)(random);
    expectSame(decodeInChunks(format, stream, chunks), whole, "random chunking " + std::to_string(trial));
  }
}

TEST(formatsWireStream, SeaNetInAnyChunksGivesTheWholeCapture) {
  const std::string stream = seanetStream();
  const SonarLog whole = parseSeaNetCapture(bytesOf(stream), "live");
  ASSERT_EQ(whole.beams.size(), 12u);
  ASSERT_GE(whole.skipped_beams, 4u);  // noise, mtAlive, the broken packet's run, the cut packet
  EXPECT_NE(whole.skip_reasons.back().find("cut short"), std::string::npos) << whole.skip_reasons.back();
  expectChunkingsAgree(LogFormat::kSeaNet, stream, whole);
}

TEST(formatsWireStream, Ping360InAnyChunksGivesTheWholeStream) {
  const std::string stream = ping360Stream();
  const SonarLog whole = parsePing360Stream(bytesOf(stream), "live");
  ASSERT_EQ(whole.beams.size(), 12u);
  ASSERT_GE(whole.skipped_beams, 4u);
  EXPECT_NE(whole.skip_reasons.back().find("cut short"), std::string::npos) << whole.skip_reasons.back();
  expectChunkingsAgree(LogFormat::kPing360, stream, whole);
}

TEST(formatsWireStream, ABeamComesOutWithItsFramesLastByte) {
  test::SeaNetHeadPacket packet;
  const std::string frame = test::seanetHeadData(packet);
  WireStreamDecoder decoder(LogFormat::kSeaNet);
  EXPECT_TRUE(decoder.feed(bytesOf(frame).first(frame.size() - 1)).empty());
  EXPECT_EQ(decoder.feed(bytesOf(frame).last(1)).size(), 1u);
  EXPECT_TRUE(decoder.finish().empty());
  EXPECT_EQ(decoder.skippedItems(), 0u);
  EXPECT_THROW(decoder.feed(bytesOf(frame)), ValueError);
}

TEST(formatsWireStream, FinishReportsAFrameCutShort) {
  const std::string frame = test::ping360Message({});
  WireStreamDecoder decoder(LogFormat::kPing360, {}, "udp");
  EXPECT_TRUE(decoder.feed(bytesOf(frame).first(12)).empty());
  EXPECT_EQ(decoder.skippedItems(), 0u);  // it may still come
  EXPECT_TRUE(decoder.finish().empty());
  ASSERT_EQ(decoder.skippedItems(), 1u);
  const std::vector<std::string> reasons = decoder.takeSkipReasons();
  ASSERT_EQ(reasons.size(), 1u);
  EXPECT_EQ(reasons[0].rfind("udp: message at byte 0 cut short", 0), 0u) << reasons[0];
  EXPECT_TRUE(decoder.takeSkipReasons().empty());
}

TEST(formatsWireStream, TimesBeamsByTheIntervalAndRejectsOtherFormatsAndBadOptions) {
  CaptureOptions options;
  options.beam_interval_s = 0.5;
  WireStreamDecoder decoder(LogFormat::kPing360, options);
  const std::string two = test::ping360Message({}) + test::ping360Message({});
  std::vector<Beam> beams = decoder.feed(bytesOf(two));
  ASSERT_EQ(beams.size(), 2u);
  EXPECT_EQ(beams[0].time_s, 0.0);
  EXPECT_EQ(beams[1].time_s, 0.5);
  EXPECT_THROW(WireStreamDecoder(LogFormat::kMat), ValueError);
  EXPECT_THROW(WireStreamDecoder(LogFormat::kSeaNet, CaptureOptions{-1.0, 0.0}), ValueError);
}

}  // namespace
}  // namespace sonarmap
