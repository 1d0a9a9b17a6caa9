/// One head, every reader: the same turn of the same kind of head, recorded as each format
/// records it (files built byte by byte from the formats' specifications, not with the project's
/// encoders), gives the same bearings: "ahead" at 0 and the head's clockwise turn as increasing
/// bearings (beam.hpp). A Tritech Micron's CRAS `.mat` angle is its SeaNet count in degrees.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "common/temp_dir.hpp"
#include "mat_fixture.hpp"
#include "sonarmap/formats/mat_reader.hpp"
#include "sonarmap/formats/ping360_reader.hpp"
#include "sonarmap/formats/seanet_capture.hpp"
#include "wire_fixture.hpp"

namespace sonarmap {
namespace {

constexpr double kPi = std::numbers::pi;

std::span<const unsigned char> bytesOf(const std::string& text) {
  return {reinterpret_cast<const unsigned char*>(text.data()), text.size()};
}

/// The angle between two bearings, in (−π, π].
double turn(double from_rad, double to_rad) { return std::remainder(to_rad - from_rad, 2.0 * kPi); }

/// Tritech counts (1/16 gradian, clockwise, 3200 ahead) of a head stepping clockwise through ahead.
const std::vector<int> kSeaNetCounts = {3136, 3168, 3200, 3232, 4800};

TEST(formatsBearingConventions, ATritechHeadReadsTheSameFromItsSeaNetCaptureAndItsCrasMat) {
  std::string capture;
  std::vector<test::MatBeam> mat_beams;
  for (std::size_t i = 0; i < kSeaNetCounts.size(); ++i) {
    test::SeaNetHeadPacket packet;
    packet.head_control = 0x2305;  // adc8on, scanright; upright (invert clear)
    packet.bearing = static_cast<std::uint16_t>(kSeaNetCounts[i]);
    capture += test::seanetHeadData(packet);
    test::MatBeam beam;
    beam.time = 0.043 * static_cast<double>(i);
    beam.angle = kSeaNetCounts[i] * 360.0 / 6400.0;  // the CRAS driver's degrees of the same count
    mat_beams.push_back(beam);
  }
  const test::TempDir dir;
  test::writeCrasMat(dir.file("head.mat"), mat_beams);
  const SonarLog seanet = parseSeaNetCapture(bytesOf(capture), "head.seanet");
  const SonarLog mat = readCrasMat(dir.file("head.mat"));
  ASSERT_EQ(seanet.beams.size(), kSeaNetCounts.size());
  ASSERT_EQ(mat.beams.size(), kSeaNetCounts.size());
  for (std::size_t i = 0; i < kSeaNetCounts.size(); ++i) {
    const double expected_rad = 2.0 * kPi * (kSeaNetCounts[i] - 3200) / 6400.0;  // clockwise from ahead
    EXPECT_NEAR(turn(expected_rad, seanet.beams[i].bearing_rad), 0.0, 1e-9) << "SeaNet beam " << i;
    EXPECT_NEAR(turn(expected_rad, mat.beams[i].bearing_rad), 0.0, 1e-6) << ".mat beam " << i;  // single precision
  }
  EXPECT_NEAR(seanet.beams[2].bearing_rad, 0.0, 1e-12);  // ahead
  EXPECT_NEAR(mat.beams[2].bearing_rad, 0.0, 1e-12);
}

TEST(formatsBearingConventions, EveryHeadTurningClockwiseGivesIncreasingBearings) {
  // A Ping360 stepping clockwise (gradians, 0 ahead) across its zero.
  std::string stream;
  for (const int angle : {398, 399, 0, 1, 100}) {
    test::Ping360Data data;
    data.angle = static_cast<std::uint16_t>(angle);
    stream += test::ping360Message(data);
  }
  const SonarLog ping360 = parsePing360Stream(bytesOf(stream), "head.bin");
  ASSERT_EQ(ping360.beams.size(), 5u);
  EXPECT_NEAR(ping360.beams[2].bearing_rad, 0.0, 1e-12);              // angle 0: ahead
  EXPECT_NEAR(ping360.beams[4].bearing_rad, 0.5 * kPi, 1e-12);        // 100 gradians clockwise: starboard
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_NEAR(turn(ping360.beams[i - 1].bearing_rad, ping360.beams[i].bearing_rad), 2.0 * kPi / 400, 1e-12) << i;
  }
  // A Tritech head the same way, from its SeaNet capture.
  std::string capture;
  for (const int count : kSeaNetCounts) {
    test::SeaNetHeadPacket packet;
    packet.head_control = 0x2305;
    packet.bearing = static_cast<std::uint16_t>(count);
    capture += test::seanetHeadData(packet);
  }
  const SonarLog seanet = parseSeaNetCapture(bytesOf(capture), "head.seanet");
  ASSERT_EQ(seanet.beams.size(), kSeaNetCounts.size());
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_NEAR(turn(seanet.beams[i - 1].bearing_rad, seanet.beams[i].bearing_rad), 2.0 * kPi * 32 / 6400, 1e-12) << i;
  }
  EXPECT_NEAR(seanet.beams[4].bearing_rad, 0.5 * kPi, 1e-12);  // 4800: a quarter turn clockwise, starboard
}

}  // namespace
}  // namespace sonarmap
