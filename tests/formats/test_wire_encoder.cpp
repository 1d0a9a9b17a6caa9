// encodeSeaNetCapture / encodePing360Stream: what the wire readers read back is the beams encoded,
// rounded as the wire rounds them (bearings to 1/16 or 1 gradian, bin lengths to 640 or 25 ns of
// two-way travel), with no skipped byte; a SeaNet log re-encoded gives its own beams exactly; what
// the wire cannot carry is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <span>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/ping360_reader.hpp"
#include "sonarmap/formats/seanet_capture.hpp"
#include "sonarmap/formats/v4log_reader.hpp"
#include "sonarmap/formats/wire_encoder.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// 300 beams: bearings around the turn in 1.2° steps, 0.0125 m bins, 100…399 bins of a ramp.
std::vector<Beam> sampleBeams() {
  std::vector<Beam> beams;
  for (int i = 0; i < 300; ++i) {
    Beam beam;
    beam.time_s = 0.05 * i;
    beam.bearing_rad = std::fmod(i * 1.2 * std::numbers::pi / 180.0, kTwoPi);
    beam.bin_length_m = 0.0125;
    beam.intensity_span_db = 45.0;
    for (int b = 0; b < 100 + i; ++b) beam.intensities.push_back(static_cast<std::uint8_t>((b * 7 + i) % 256));
    beams.push_back(beam);
  }
  return beams;
}

double angleBetween(double a_rad, double b_rad) { return std::abs(std::remainder(a_rad - b_rad, kTwoPi)); }

void expectRoundTrip(const std::vector<Beam>& sent, const SonarLog& read, double bearing_step_rad, double tick_s) {
  ASSERT_EQ(read.beams.size(), sent.size());
  EXPECT_EQ(read.skipped_beams, 0U);
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(read.beams[i].intensities, sent[i].intensities) << "beam " << i;
    EXPECT_LE(angleBetween(read.beams[i].bearing_rad, sent[i].bearing_rad), 0.5 * bearing_step_rad + 1e-9) << "beam " << i;
    EXPECT_NEAR(read.beams[i].bin_length_m, sent[i].bin_length_m, 0.5 * tick_s * 1500.0 / 2.0 + 1e-12) << "beam " << i;
  }
}

TEST(formatsWireEncoder, SeaNetCaptureReadsBackTheBeams) {
  const std::vector<Beam> beams = sampleBeams();
  const std::vector<std::uint8_t> bytes = encodeSeaNetCapture(beams);
  const SonarLog read = parseSeaNetCapture(std::span(bytes.data(), bytes.size()), "encoded");
  expectRoundTrip(beams, read, kTwoPi / 6400.0, 640e-9);
  EXPECT_NEAR(*read.beams.front().intensity_span_db, 45.0, 80.0 / 255.0);
}

TEST(formatsWireEncoder, Ping360StreamReadsBackTheBeams) {
  const std::vector<Beam> beams = sampleBeams();
  const std::vector<std::uint8_t> bytes = encodePing360Stream(beams);
  const SonarLog read = parsePing360Stream(std::span(bytes.data(), bytes.size()), "encoded");
  expectRoundTrip(beams, read, kTwoPi / 400.0, 25e-9);
  // The sound speed sets the sample period written, and the reader given it reads the bins back.
  CaptureOptions slow;
  slow.sound_speed_m_s = 1400.0;
  const std::vector<std::uint8_t> slow_bytes = encodePing360Stream(beams, slow);
  const SonarLog slow_read = parsePing360Stream(std::span(slow_bytes.data(), slow_bytes.size()), "encoded", slow);
  EXPECT_NEAR(slow_read.beams.front().bin_length_m, 0.0125, 25e-9 * 1400.0 / 4.0 + 1e-12);
  EXPECT_NE(slow_bytes, bytes);
}

// The shared SeaNet log's beams (already on SeaNet's grid) come back bit for bit.
TEST(formatsWireEncoder, SeaNetLogReencodedGivesItsOwnBeams) {
  const std::string path = std::string(SONARMAP_SHARED_DATA) + "/seanet_sector_target.V4LOG";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
  const SonarLog log = readSeaNetV4Log(path);
  const std::vector<std::uint8_t> bytes = encodeSeaNetCapture(log.beams);
  const SonarLog read = parseSeaNetCapture(std::span(bytes.data(), bytes.size()), "encoded");
  ASSERT_EQ(read.beams.size(), log.beams.size());
  for (std::size_t i = 0; i < log.beams.size(); ++i) {
    EXPECT_EQ(read.beams[i].intensities, log.beams[i].intensities);
    EXPECT_EQ(read.beams[i].bearing_rad, log.beams[i].bearing_rad);
    EXPECT_EQ(read.beams[i].bin_length_m, log.beams[i].bin_length_m);
    EXPECT_EQ(read.beams[i].intensity_span_db, log.beams[i].intensity_span_db);
  }
}

TEST(formatsWireEncoder, WhatTheWireCannotCarryIsRefused) {
  std::vector<Beam> beams = sampleBeams();
  beams[3].bin_length_m = 0.0;
  EXPECT_THROW(encodeSeaNetCapture(beams), ValueError);
  EXPECT_THROW(encodePing360Stream(beams), ValueError);
  beams[3].bin_length_m = 100.0;  // 133 ms of two-way travel: beyond 65535 × 640 ns
  EXPECT_THROW(encodeSeaNetCapture(beams), ValueError);
  beams[3].bin_length_m = 0.0125;
  beams[3].intensities.assign(70000, 1);
  EXPECT_THROW(encodeSeaNetCapture(beams), ValueError);
  EXPECT_THROW(encodePing360Stream(beams), ValueError);
  CaptureOptions bad;
  bad.sound_speed_m_s = -1.0;
  EXPECT_THROW(encodeSeaNetCapture({}, bad), ValueError);
  EXPECT_TRUE(encodePing360Stream({}).empty());
}

}  // namespace
}  // namespace sonarmap
