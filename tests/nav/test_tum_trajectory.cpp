// TUM RGB-D trajectory files (nav/tum_trajectory.hpp) and readTrajectory's format detection.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/tum_trajectory.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;

/// A turning, rolling, pitching track whose yaw runs past ±π.
NavTrack turningTrack() {
  NavTrack track;
  for (int k = 0; k < 50; ++k) {
    NavSample fix;
    fix.time_s = 100.0 + 0.1 * k;
    fix.position_ned_m = Eigen::Vector3d(std::cos(0.1 * k) * 3.0, -1.0 + 0.7 * k, 2.0 + 0.01 * k);
    fix.roll_rad = 0.1 * std::sin(0.3 * k);
    fix.pitch_rad = -0.2 + 0.005 * k;
    fix.yaw_rad = 2.5 + 0.03 * k;  // 2.5 to 3.97 rad: wraps
    track.push_back(fix);
  }
  return track;
}

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string errorOf(const fs::path& path) {
  try {
    readTumTrajectory(path.string());
  } catch (const FileError& error) {
    return error.what();
  }
  return "no error";
}

class navTum : public ::testing::Test {
 protected:
  fs::path file(const std::string& name) const { return dir_.path() / name; }
  test::TempDir dir_;
};

TEST_F(navTum, RoundTripKeepsPositionsAndAttitude) {
  const NavTrack track = turningTrack();
  writeTumTrajectory(file("t.txt").string(), track);
  const NavTrack read = readTumTrajectory(file("t.txt").string());
  ASSERT_EQ(read.size(), track.size());
  for (std::size_t k = 0; k < track.size(); ++k) {
    EXPECT_EQ(read[k].time_s, track[k].time_s);
    EXPECT_EQ(read[k].position_ned_m, track[k].position_ned_m);  // shortest exact decimals
    EXPECT_NEAR(std::remainder(read[k].yaw_rad - track[k].yaw_rad, 2.0 * std::numbers::pi), 0.0, 1e-9) << k;
    EXPECT_NEAR(read[k].pitch_rad, track[k].pitch_rad, 1e-9) << k;
    EXPECT_NEAR(read[k].roll_rad, track[k].roll_rad, 1e-9) << k;
    EXPECT_TRUE(bodyToNed(read[k]).isApprox(bodyToNed(track[k]), 1e-9)) << k;
  }
  std::ostringstream out;
  writeTumTrajectory(out, {track.front()});
  EXPECT_EQ(out.str().front(), '#');  // a comment line naming the columns
  EXPECT_THROW(writeTumTrajectory(out, {}), ValueError);
}

TEST_F(navTum, CommentsAndBlankLinesAreSkipped) {
  // Yaw 90°: q = (cos 45°, 0, 0, sin 45°); a non-unit quaternion is normalised.
  writeText(file("c.txt"), "# TUM\n\n1.5 1 2 3 0 0 0.7071067811865476 0.7071067811865476\n  # indented comment\n"
                           "2.5\t4 5 6 0 0 0 2\r\n");
  const NavTrack track = readTumTrajectory(file("c.txt").string());
  ASSERT_EQ(track.size(), 2U);
  EXPECT_EQ(track[0].time_s, 1.5);
  EXPECT_EQ(track[0].position_ned_m, Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(track[0].yaw_rad, 0.5 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(track[1].yaw_rad, 0.0, 1e-12);
}

TEST_F(navTum, HugeQuaternionsAreNormalisedWithoutOverflow) {
  // Finite components whose squared norm overflows: yaw 90°, then roll 180° (was read as identity).
  writeText(file("h.txt"), "0 0 0 0 0 0 1e200 1e200\n1 0 0 0 1e308 0 0 0\n2 0 0 0 0 0 1.5e308 1.5e308\n");
  const NavTrack track = readTumTrajectory(file("h.txt").string());
  ASSERT_EQ(track.size(), 3U);
  EXPECT_NEAR(track[0].yaw_rad, 0.5 * std::numbers::pi, 1e-12);
  const Eigen::Matrix3d roll_pi = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  EXPECT_TRUE(bodyToNed(track[1]).linear().isApprox(roll_pi, 1e-12)) << bodyToNed(track[1]).linear();
  EXPECT_NEAR(track[2].yaw_rad, 0.5 * std::numbers::pi, 1e-12);
  // A tiny quaternion is still refused as norm 0, even where its squared norm underflows.
  writeText(file("t.txt"), "0 0 0 0 0 0 0 1e-13\n");
  EXPECT_NE(errorOf(file("t.txt")).find("line 1: the quaternion has norm 0"), std::string::npos) << errorOf(file("t.txt"));
  writeText(file("u.txt"), "0 0 0 0 1e-300 0 0 1e-300\n");
  EXPECT_NE(errorOf(file("u.txt")).find("line 1: the quaternion has norm 0"), std::string::npos) << errorOf(file("u.txt"));
}

TEST_F(navTum, MalformedLinesNameTheLine) {
  writeText(file("a.txt"), "# h\n0 0 0 0 0 0 0 1\n1 0 0 0 0 0 1\n");
  EXPECT_NE(errorOf(file("a.txt")).find("line 3"), std::string::npos) << errorOf(file("a.txt"));
  writeText(file("b.txt"), "0 0 0 0 0 0 0 1\n1 0 x 0 0 0 0 1\n");
  EXPECT_NE(errorOf(file("b.txt")).find("line 2"), std::string::npos) << errorOf(file("b.txt"));
  writeText(file("c.txt"), "0 0 0 0 0 0 0 1\n0 0 0 0 0 0 0 1\n");  // time not increasing
  EXPECT_NE(errorOf(file("c.txt")).find("line 2"), std::string::npos) << errorOf(file("c.txt"));
  writeText(file("d.txt"), "0 0 0 0 0 0 0 0\n");  // zero quaternion
  EXPECT_NE(errorOf(file("d.txt")).find("line 1"), std::string::npos) << errorOf(file("d.txt"));
  writeText(file("e.txt"), "# only a comment\n");
  EXPECT_NE(errorOf(file("e.txt")).find("no poses"), std::string::npos) << errorOf(file("e.txt"));
  EXPECT_THROW(readTumTrajectory(file("missing.txt").string()), FileError);
  EXPECT_THROW(readTrajectory(file("missing.txt").string()), FileError);
}

TEST_F(navTum, ReadTrajectoryDetectsTheFormat) {
  const NavTrack track = turningTrack();
  writeNavCsv(file("nav.csv").string(), track);
  writeTumTrajectory(file("nav.tum").string(), track);
  const NavTrack from_csv = readTrajectory(file("nav.csv").string());
  const NavTrack from_tum = readTrajectory(file("nav.tum").string());
  ASSERT_EQ(from_csv.size(), track.size());
  ASSERT_EQ(from_tum.size(), track.size());
  EXPECT_EQ(from_csv.back().yaw_rad, track.back().yaw_rad);  // the CSV keeps the very values
  EXPECT_TRUE(bodyToNed(from_tum.back()).isApprox(bodyToNed(track.back()), 1e-9));
  writeText(file("bad.csv"), "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n0,0,0\n");
  try {
    readTrajectory(file("bad.csv").string());
    FAIL() << "no error";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find("line 2"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace sonarmap
