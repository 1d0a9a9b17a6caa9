// NavCsvStream: navigation CSV rows arriving in pieces (sonarmap live --nav-stream) give whole fixes
// in order; the header is optional; a malformed row, a time that does not increase and a run of
// bytes without a line end are skipped and counted, never thrown.
#include <gtest/gtest.h>

#include <span>
#include <string>
#include <vector>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {
namespace {

std::vector<NavSample> feed(NavCsvStream& rows, const std::string& text) {
  return rows.feed(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

TEST(navNavCsvStream, RowsSplitAcrossReadsGiveWholeFixes) {
  NavCsvStream rows("udp://test");
  EXPECT_TRUE(feed(rows, "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n1.5,10,-2").empty());
  const std::vector<NavSample> first = feed(rows, ",3,0.1,0.2,0.3\r\n2.5,11,");
  ASSERT_EQ(first.size(), 1U);
  EXPECT_EQ(first[0].time_s, 1.5);
  EXPECT_EQ(first[0].position_ned_m, Eigen::Vector3d(10.0, -2.0, 3.0));
  EXPECT_EQ(first[0].yaw_rad, 0.3);
  const std::vector<NavSample> second = feed(rows, "-2,3,0,0,0\n\n3.5,12,-2,3,0,0,0\n");
  ASSERT_EQ(second.size(), 2U);
  EXPECT_EQ(second[0].position_ned_m.x(), 11.0);
  EXPECT_EQ(second[1].time_s, 3.5);
  EXPECT_EQ(rows.skippedRows(), 0U);
  EXPECT_TRUE(rows.lastSkipReason().empty());
}

TEST(navNavCsvStream, BadRowsAreSkippedAndCounted) {
  NavCsvStream rows("udp://test");
  const std::vector<NavSample> fixes = feed(rows, "1,0,0,0,0,0,0\n2,0,0,nan,0,0,0\n2,0,0\n0.5,0,0,0,0,0,0\n3,1,0,0,0,0,0\n");
  ASSERT_EQ(fixes.size(), 2U);
  EXPECT_EQ(fixes[1].time_s, 3.0);
  EXPECT_EQ(rows.skippedRows(), 3U);  // a NaN, three fields, a time going back
  EXPECT_NE(rows.lastSkipReason().find("not after the previous one"), std::string::npos) << rows.lastSkipReason();
  EXPECT_TRUE(feed(rows, std::string(5000, 'x')).empty());  // no line end: noise, dropped
  EXPECT_EQ(rows.skippedRows(), 4U);
  EXPECT_EQ(feed(rows, "\n4,0,0,0,0,0,0\n").size(), 1U);  // the stream goes on
}

}  // namespace
}  // namespace sonarmap
