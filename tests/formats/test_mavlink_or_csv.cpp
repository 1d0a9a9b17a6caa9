/// Tests of NavigationStream (navigation_stream.hpp): a `--nav-stream` told MAVLink or navigation
/// CSV by its first bytes, with noise before the first frame or row, bytes in any chunks, and its
/// fixes on the arrival clock either way.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sonarmap/formats/navigation_stream.hpp"
#include "mavlink_autopilot.hpp"

namespace sonarmap {
namespace {

using test::Datagram;
using test::MavlinkSenderStream;

std::span<const std::uint8_t> bytesOf(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}
bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::vector<Datagram> autopilotStream() {
  std::vector<Datagram> out;
  MavlinkSenderStream ap{.out = &out};
  for (int i = 0; i <= 20; ++i) {
    const double t = 12.0 + 0.1 * i;
    ap.attitude(t, 0.0f, 0.1f, 0.2f);
    if (i % 2 == 0) ap.localPosition(t, 1.0f, static_cast<float>(t), 2.0f);
  }
  return out;
}

TEST(formatsNavigationStream, MavlinkIsToldByItsFirstCheckedFrameEvenAfterNoise) {
  const std::vector<Datagram> stream = autopilotStream();
  MavlinkNavigation reference;
  const std::vector<NavSample> expected = test::decodeAll(reference, stream);
  NavigationStream nav("serial:/dev/ttyUSB0");
  // a serial line's noise and a half line of text before the first frame, and a false start
  const std::string noise = std::string("noise\r\n1.5,x\n\x00\x13", 15) + std::string("\xFD\x09\x00", 3);
  std::vector<NavSample> fixes;
  EXPECT_TRUE(nav.feed(bytesOf(noise), stream.front().arrival_s - 0.01).empty());
  EXPECT_EQ(nav.protocol(), NavigationStream::Protocol::kUndecided);
  EXPECT_TRUE(contains(nav.description(), "undecided (18 bytes")) << nav.description();
  for (const Datagram& d : stream) {
    for (std::size_t half : {d.bytes.size() / 2, d.bytes.size()}) {  // each frame in two reads
      const std::size_t from = half == d.bytes.size() ? d.bytes.size() / 2 : 0;
      for (const NavSample& f : nav.feed(std::span(d.bytes).subspan(from, half - from), d.arrival_s)) fixes.push_back(f);
    }
  }
  for (const NavSample& f : nav.finish()) fixes.push_back(f);
  EXPECT_EQ(nav.protocol(), NavigationStream::Protocol::kMavlink);
  ASSERT_EQ(fixes.size(), expected.size());
  for (std::size_t i = 0; i < fixes.size(); ++i) {
    EXPECT_EQ(fixes[i].time_s, expected[i].time_s);
    EXPECT_EQ(fixes[i].position_ned_m, expected[i].position_ned_m);
  }
  EXPECT_EQ(nav.description(), "MAVLink from system 1, component 1 (attitude ATTITUDE, position LOCAL_POSITION_NED)");
  std::string notes;
  for (const std::string& n : nav.takeNotes()) notes += n + "\n";
  EXPECT_TRUE(contains(notes, "serial:/dev/ttyUSB0: MAVLink (a frame with a matching checksum)")) << notes;
  EXPECT_TRUE(contains(notes, "serial:/dev/ttyUSB0: north and east from boot time 12.000 s: LOCAL_POSITION_NED")) << notes;
}

TEST(formatsNavigationStream, CsvRowsAreToldByAWholeRowAndPutOnTheArrivalClock) {
  NavigationStream nav("udp://0.0.0.0:5000");
  const std::string text =
      "\x01\x02junk\n"
      "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\r\n"
      "100.0,1,2,3,0,0,0.5\n"
      "100.5,1.5,2,3,0,0,0.5\n"
      "101.0,2,2,3,0,0,0.5\n";
  std::vector<NavSample> fixes;
  double arrival_s = 7.0;
  for (std::size_t at = 0; at < text.size(); at += 5, arrival_s += 0.01) {
    for (const NavSample& f : nav.feed(bytesOf(text.substr(at, 5)), arrival_s)) fixes.push_back(f);
  }
  EXPECT_EQ(nav.protocol(), NavigationStream::Protocol::kCsv);
  ASSERT_EQ(fixes.size(), 3u);
  // the first fix's row ended in the read at 7.0 + 0.01 × 15 (its newline is byte 73)
  EXPECT_NEAR(fixes[0].time_s, 7.14, 1e-9);
  EXPECT_NEAR(fixes[1].time_s, 7.64, 1e-9);
  EXPECT_NEAR(fixes[2].time_s, 8.14, 1e-9);
  EXPECT_EQ(fixes[1].position_ned_m.x(), 1.5);
  EXPECT_EQ(nav.skipped(), 1u);  // the junk line
  EXPECT_EQ(nav.description(), "navigation CSV rows");
  std::string notes;
  for (const std::string& n : nav.takeNotes()) notes += n + "\n";
  EXPECT_TRUE(contains(notes, "udp://0.0.0.0:5000: navigation CSV rows")) << notes;
}

TEST(formatsNavigationStream, NoiseAloneDecidesNothingAndKeepsNoMoreThan64KiB) {
  NavigationStream nav("tcp://192.168.2.2:9000");
  std::string noise(1000, 'z');
  noise[500] = '\xFE';  // a false MAVLink 1 start
  for (int i = 0; i < 100; ++i) EXPECT_TRUE(nav.feed(bytesOf(noise), i).empty());
  EXPECT_EQ(nav.protocol(), NavigationStream::Protocol::kUndecided);
  EXPECT_EQ(nav.bytesDropped(), 100000u - 65000u);
  EXPECT_TRUE(nav.finish().empty());
  EXPECT_EQ(nav.skipped(), 0u);
  // then a row decides it
  const std::vector<NavSample> fixes = nav.feed(bytesOf("\n5,0,0,1,0,0,0\n"), 200.0);
  EXPECT_EQ(nav.protocol(), NavigationStream::Protocol::kCsv);
  ASSERT_EQ(fixes.size(), 1u);
  EXPECT_EQ(fixes[0].time_s, 200.0);
}

}  // namespace
}  // namespace sonarmap
