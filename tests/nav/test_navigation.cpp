/// Tests of navigation.hpp: poses from fixes, interpolation (navInterpolation) and the navigation
/// CSV (navCsv).

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {
namespace {

using test::TempDir;

constexpr double kPi = std::numbers::pi;
constexpr char kHeader[] = "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n";

NavSample fix(double time_s, Eigen::Vector3d position_ned_m, double roll_rad, double pitch_rad, double yaw_rad) {
  NavSample sample;
  sample.time_s = time_s;
  sample.position_ned_m = position_ned_m;
  sample.roll_rad = roll_rad;
  sample.pitch_rad = pitch_rad;
  sample.yaw_rad = yaw_rad;
  return sample;
}

NavSample atTime(double time_s) { return fix(time_s, Eigen::Vector3d::Zero(), 0.0, 0.0, 0.0); }

void expectNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected) {
  EXPECT_TRUE(actual.isApprox(expected, 1e-12) || (actual - expected).norm() < 1e-12)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

// ---- bodyToNed, nedToMap -------------------------------------------------------------------------

TEST(navInterpolation, ZeroFixIsTheIdentityPlusPosition) {
  const Eigen::Isometry3d pose = bodyToNed(fix(0.0, {1.0, 2.0, 3.0}, 0.0, 0.0, 0.0));
  EXPECT_TRUE(pose.linear().isIdentity(1e-15));
  EXPECT_EQ(pose.translation(), Eigen::Vector3d(1.0, 2.0, 3.0));
}

TEST(navInterpolation, YawNinetyDegreesTurnsForwardToEast) {
  const Eigen::Isometry3d pose = bodyToNed(fix(0.0, Eigen::Vector3d::Zero(), 0.0, 0.0, kPi / 2));
  expectNear(pose * Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());   // forward → east
  expectNear(pose * Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitX());  // starboard → south
  expectNear(pose * Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ());   // down stays down
}

TEST(navInterpolation, PitchUpRaisesTheBowAndRollLowersStarboard) {
  const double angle = 0.3;
  const Eigen::Isometry3d pitched = bodyToNed(fix(0.0, Eigen::Vector3d::Zero(), 0.0, angle, 0.0));
  expectNear(pitched * Eigen::Vector3d::UnitX(), {std::cos(angle), 0.0, -std::sin(angle)});  // z down: bow up
  const Eigen::Isometry3d rolled = bodyToNed(fix(0.0, Eigen::Vector3d::Zero(), angle, 0.0, 0.0));
  expectNear(rolled * Eigen::Vector3d::UnitY(), {0.0, std::cos(angle), std::sin(angle)});  // starboard down
}

TEST(navInterpolation, EulerOrderIsYawThenPitchThenRoll) {
  const double roll = 0.2, pitch = -0.4, yaw = 2.5;
  const Eigen::Isometry3d pose = bodyToNed(fix(0.0, Eigen::Vector3d::Zero(), roll, pitch, yaw));
  // Z-Y-X: R = Rz(yaw) Ry(pitch) Rx(roll), the matrix written out (Fossen 2011, Handbook of Marine Craft
  // Hydrodynamics and Motion Control, Euler-angle rotation of body to NED).
  const double cr = std::cos(roll), sr = std::sin(roll), cp = std::cos(pitch), sp = std::sin(pitch);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  Eigen::Matrix3d expected;
  expected << cy * cp, -sy * cr + cy * sp * sr, sy * sr + cy * cr * sp,  //
      sy * cp, cy * cr + sr * sp * sy, -cy * sr + sp * sy * cr,          //
      -sp, cp * sr, cp * cr;
  EXPECT_TRUE(pose.linear().isApprox(expected, 1e-14)) << pose.linear();
}

TEST(navInterpolation, NedToMapIsNorthWestUp) {
  expectNear(nedToMap() * Eigen::Vector3d(1.0, 2.0, 3.0), {1.0, -2.0, -3.0});
  EXPECT_TRUE(nedToMap().translation().isZero());
}

TEST(navInterpolation, UprightAlignedSonarHasTheIdentityMountingAndTheStaticMapPose) {
  // The sonar frame is FRD like the body: upright and aligned is the identity mounting.
  const Eigen::Isometry3d sonar_to_body = defaultSonarToBody();
  EXPECT_TRUE(sonar_to_body.matrix().isIdentity(0.0)) << sonar_to_body.matrix();
  const Eigen::Isometry3d sonar_to_map = nedToMap() * bodyToNed(atTime(0.0)) * sonar_to_body;
  EXPECT_TRUE(sonar_to_map.isApprox(staticSonarToMap(), 1e-15)) << sonar_to_map.matrix();
  // Bearing 0 north (map +x), bearing 90° (sonar +y, clockwise from above) east (map −y).
  expectNear(sonar_to_map * Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX());
  expectNear(sonar_to_map * Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitY());
  // Heading east: the sonar's +x (forward) points east, which is map −y (map y is west).
  const Eigen::Isometry3d heading_east =
      nedToMap() * bodyToNed(fix(0.0, Eigen::Vector3d::Zero(), 0.0, 0.0, kPi / 2)) * sonar_to_body;
  expectNear(heading_east * Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitY());
}

// ---- interpolateBodyToNed ------------------------------------------------------------------------

TEST(navInterpolation, MidpointInterpolatesPositionLinearly) {
  const NavTrack track = {fix(10.0, {0.0, 0.0, 0.0}, 0.0, 0.0, 0.0), fix(12.0, {4.0, -2.0, 1.0}, 0.0, 0.0, 0.0),
                          fix(13.0, {4.0, -2.0, 5.0}, 0.0, 0.0, 0.0)};
  const auto mid = interpolateBodyToNed(track, 11.0);
  ASSERT_TRUE(mid.has_value());
  expectNear(mid->translation(), {2.0, -1.0, 0.5});
  const auto quarter = interpolateBodyToNed(track, 12.25);
  ASSERT_TRUE(quarter.has_value());
  expectNear(quarter->translation(), {4.0, -2.0, 2.0});
}

TEST(navInterpolation, MidpointAttitudeIsTheSlerpHalfway) {
  const NavTrack track = {fix(0.0, Eigen::Vector3d::Zero(), 0.0, 0.0, 0.2),
                          fix(1.0, Eigen::Vector3d::Zero(), 0.0, 0.0, 1.0)};
  const auto mid = interpolateBodyToNed(track, 0.5);
  ASSERT_TRUE(mid.has_value());
  EXPECT_TRUE(mid->linear().isApprox(bodyToNed(fix(0.0, Eigen::Vector3d::Zero(), 0.0, 0.0, 0.6)).linear(), 1e-14));
  const NavTrack pitching = {fix(0.0, Eigen::Vector3d::Zero(), 0.0, -0.2, 0.0),
                             fix(1.0, Eigen::Vector3d::Zero(), 0.0, 0.4, 0.0)};
  EXPECT_TRUE(interpolateBodyToNed(pitching, 0.5)
                  ->linear()
                  .isApprox(bodyToNed(fix(0.0, Eigen::Vector3d::Zero(), 0.0, 0.1, 0.0)).linear(), 1e-14));
}

TEST(navInterpolation, YawAcrossTheWrapTakesTheShortWay) {
  const double one_degree = kPi / 180.0;
  const NavTrack track = {fix(0.0, Eigen::Vector3d::Zero(), 0.0, 0.0, kPi - one_degree),   // 179°
                          fix(1.0, Eigen::Vector3d::Zero(), 0.0, 0.0, -kPi + one_degree)};  // −179°
  const auto mid = interpolateBodyToNed(track, 0.5);
  ASSERT_TRUE(mid.has_value());
  expectNear(*mid * Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX());  // 180°: south, not north
  const auto quarter = interpolateBodyToNed(track, 0.25);
  ASSERT_TRUE(quarter.has_value());
  const Eigen::Vector3d forward = *quarter * Eigen::Vector3d::UnitX();
  const double yaw_deg = std::atan2(forward.y(), forward.x()) * 180.0 / kPi;
  EXPECT_NEAR(yaw_deg, 179.5, 1e-9);
}

TEST(navInterpolation, AtAFixItsOwnPose) {
  const NavTrack track = {fix(1.0, {1.0, 0.0, 0.0}, 0.1, 0.0, 0.0), fix(2.0, {2.0, 0.0, 0.0}, 0.0, 0.2, 0.0),
                          fix(3.0, {3.0, 0.0, 0.0}, 0.0, 0.0, 0.3)};
  for (const NavSample& sample : track) {
    const auto pose = interpolateBodyToNed(track, sample.time_s);
    ASSERT_TRUE(pose.has_value()) << sample.time_s;
    EXPECT_TRUE(pose->matrix().isApprox(bodyToNed(sample).matrix(), 1e-14)) << sample.time_s;
  }
}

TEST(navInterpolation, OutsideTheTrackIsNullopt) {
  const NavTrack track = {atTime(1.0), atTime(2.0)};
  EXPECT_FALSE(interpolateBodyToNed(track, 0.999).has_value());
  EXPECT_FALSE(interpolateBodyToNed(track, 2.001).has_value());
  EXPECT_FALSE(interpolateBodyToNed(track, std::nan("")).has_value());
  const NavTrack single = {atTime(5.0)};
  EXPECT_TRUE(interpolateBodyToNed(single, 5.0).has_value());
  EXPECT_FALSE(interpolateBodyToNed(single, 5.1).has_value());
}

TEST(navInterpolation, BadTracksAreValueErrors) {
  EXPECT_THROW(interpolateBodyToNed({}, 0.0), ValueError);
  EXPECT_THROW(interpolateBodyToNed({atTime(1.0), atTime(1.0)}, 1.0), ValueError);       // repeated time
  EXPECT_THROW(interpolateBodyToNed({atTime(2.0), atTime(1.0)}, 1.5), ValueError);       // backwards
  EXPECT_THROW(interpolateBodyToNed({atTime(1.0), fix(2.0, {0.0, std::nan(""), 0.0}, 0.0, 0.0, 0.0)}, 1.5),
               ValueError);
}

// ---- navigation CSV ------------------------------------------------------------------------------

void write(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// Expects readNavCsv to throw a FileError whose message holds the file name and every part.
void expectFileError(const std::string& text, std::initializer_list<std::string> parts) {
  const TempDir dir;
  const std::string path = dir.file("nav.csv");
  write(path, text);
  try {
    readNavCsv(path);
    ADD_FAILURE() << "no FileError for:\n" << text;
  } catch (const FileError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

TEST(navCsv, RoundTripIsExact) {
  const TempDir dir;
  const NavTrack track = {fix(0.1, {1.0 / 3.0, -2e-7, 12345.678}, 0.01, -0.02, kPi - 1e-12),
                          fix(0.2, {-0.0, 5.5, 1e300}, -kPi, kPi / 7.0, -3.0),
                          fix(1e9, {0.0, 0.0, 0.0}, 0.0, 0.0, 0.0)};
  writeNavCsv(dir.file("nav.csv"), track);
  const NavTrack read = readNavCsv(dir.file("nav.csv"));
  ASSERT_EQ(read.size(), track.size());
  for (std::size_t i = 0; i < track.size(); ++i) {
    EXPECT_EQ(read[i].time_s, track[i].time_s);
    EXPECT_EQ(read[i].position_ned_m, track[i].position_ned_m);
    EXPECT_EQ(read[i].roll_rad, track[i].roll_rad);
    EXPECT_EQ(read[i].pitch_rad, track[i].pitch_rad);
    EXPECT_EQ(read[i].yaw_rad, track[i].yaw_rad);
  }
  std::ifstream in(dir.file("nav.csv"));
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header + "\n", kHeader);
}

TEST(navCsv, ReadsFieldsInOrderWithCrlfAndTrailingWhitespace) {
  const TempDir dir;
  write(dir.file("nav.csv"),
        "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad \r\n"
        "0.5,1,2,3,0.1,0.2,0.3\r\n"
        "\r\n"
        "1.5, 4 ,5,6,-0.1,-0.2,-0.3\t\r\n");
  const NavTrack track = readNavCsv(dir.file("nav.csv"));
  ASSERT_EQ(track.size(), 2u);
  EXPECT_EQ(track[0].time_s, 0.5);
  EXPECT_EQ(track[0].position_ned_m, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(track[0].roll_rad, 0.1);
  EXPECT_EQ(track[0].pitch_rad, 0.2);
  EXPECT_EQ(track[0].yaw_rad, 0.3);
  EXPECT_EQ(track[1].position_ned_m, Eigen::Vector3d(4.0, 5.0, 6.0));
  EXPECT_EQ(track[1].yaw_rad, -0.3);
}

TEST(navCsv, BrokenFilesNameLineAndField) {
  const std::string h = kHeader;
  expectFileError("", {"empty", "time_s,x_m"});
  expectFileError(h, {"no fixes"});
  expectFileError("time_s,x_m,y_m,z_m,roll_rad,pitch_rad,heading_rad\n0,0,0,0,0,0,0\n",
                  {"line 1", "'heading_rad'", "expected 'yaw_rad'"});
  expectFileError("time_s,x_m,y_m,z_m,roll_rad,pitch_rad\n", {"line 1", "'yaw_rad'"});
  expectFileError("time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad,extra\n", {"line 1", "8 columns"});
  expectFileError(h + "0,0,0,0,0,0\n", {"line 2", "6 field(s), expected 7"});
  expectFileError(h + "0,0,0,0,0,0,0,0\n", {"line 2", "8 field(s), expected 7"});
  expectFileError(h + "0,0,0,0,0,0,0\n1,0,abc,0,0,0,0\n",
                  {"line 3", "field 'y_m' (column 3)", "'abc' is not a number"});
  expectFileError(h + "0,0,0,,0,0,0\n", {"line 2", "field 'z_m'", "'' is not a number"});
  expectFileError(h + "0,0,0,0,nan,0,0\n", {"line 2", "field 'roll_rad'", "not finite"});
  expectFileError(h + "0,0,0,0,0,0,inf\n", {"line 2", "field 'yaw_rad'", "not finite"});
  expectFileError(h + "0,1e999,0,0,0,0,0\n", {"line 2", "field 'x_m'", "out of the range"});
  expectFileError(h + "1,0,0,0,0,0,0\n\n1,0,0,0,0,0,0\n",
                  {"line 4", "field 'time_s'", "not after the previous fix's 1 s (line 2)"});
  expectFileError(h + "2,0,0,0,0,0,0\n1,0,0,0,0,0,0\n", {"line 3", "field 'time_s'", "increase strictly"});
}

TEST(navCsv, MissingFileIsFileError) {
  const TempDir dir;
  EXPECT_THROW(readNavCsv(dir.file("missing.csv")), FileError);
}

TEST(navCsv, WriterRejectsTracksTheReaderWouldReject) {
  const TempDir dir;
  const std::string path = dir.file("nav.csv");
  write(path, "keep me");
  EXPECT_THROW(writeNavCsv(path, {}), ValueError);
  EXPECT_THROW(writeNavCsv(path, {atTime(1.0), atTime(1.0)}), ValueError);
  EXPECT_THROW(writeNavCsv(path, {fix(1.0, Eigen::Vector3d::Zero(), 0.0, std::nan(""), 0.0)}), ValueError);
  std::ifstream in(path);
  std::string content;
  std::getline(in, content);
  EXPECT_EQ(content, "keep me");  // nothing was written
  EXPECT_THROW(writeNavCsv(dir.file("no-such-folder/nav.csv"), {atTime(1.0)}), FileError);
}

}  // namespace
}  // namespace sonarmap
