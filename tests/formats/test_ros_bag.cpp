/// Tests of ROS 1 bags as sonar logs (ros_bag_reader.hpp, ros_bag_writer.hpp): a simulated log
/// written as micron_driver_ros/ScanLine messages and read back, the shared real bag, and errors.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/formats/ros_bag_mounting.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"
#include "sonarmap/formats/ros_bag_writer.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {
namespace {

SonarLog simulatedTank(std::size_t turns) {
  MsisSimulationOptions options;
  options.turns = turns;
  SonarLog log = simulateMsis(builtinScene("tank"), options).log;
  for (Beam& beam : log.beams) beam.time_s += 1.4e9;  // ROS stamps are seconds since 1970
  return log;
}

TEST(formatsRosBag, ASimulatedLogReadsBackAsItWasWritten) {
  const test::TempDir dir;
  const SonarLog written = simulatedTank(2);
  writeRosBag(dir.file("tank.bag"), written, {}, {.sonar_topic = "/micron/scan_line"});
  const SonarLog read = readSonarLog(dir.file("tank.bag"));
  ASSERT_EQ(read.beams.size(), written.beams.size());
  EXPECT_EQ(read.skipped_beams, 0u);
  EXPECT_EQ(read.sonar, "ROS topic /micron/scan_line (micron_driver_ros/ScanLine)");
  ASSERT_EQ(read.notes.size(), 1u);
  EXPECT_NE(read.notes[0].find("read as degrees, clockwise"), std::string::npos) << read.notes[0];
  for (std::size_t i = 0; i < read.beams.size(); ++i) {
    const Beam& a = written.beams[i];
    const Beam& b = read.beams[i];
    EXPECT_EQ(b.intensities, a.intensities) << "beam " << i;
    // the message holds the bearing in float32 degrees and the bin length in float32 metres
    EXPECT_NEAR(std::remainder(b.bearing_rad - a.bearing_rad, 2.0 * std::numbers::pi), 0.0, 1e-6) << "beam " << i;
    EXPECT_NEAR(b.bin_length_m, a.bin_length_m, 1e-7 * a.bin_length_m);
    EXPECT_NEAR(b.time_s, a.time_s, 1e-6);
  }
  // And it maps as the log does, within the float32 rounding of its bearings.
  const std::size_t direct = mapSonarLog(written).stats().obstacles;
  EXPECT_EQ(mapSonarLog(read).stats().obstacles, direct);
}

TEST(formatsRosBag, Bz2AndLz4ChunksReadAsUncompressedOnes) {
  const test::TempDir dir;
  const SonarLog written = simulatedTank(1);
  writeRosBag(dir.file("plain.bag"), written);
  const SonarLog plain = readSonarLog(dir.file("plain.bag"));
  for (const BagCompression compression : {BagCompression::kBz2, BagCompression::kLz4}) {
    writeRosBag(dir.file("packed.bag"), written, {}, {.compression = compression});
    EXPECT_LT(std::filesystem::file_size(dir.file("packed.bag")), std::filesystem::file_size(dir.file("plain.bag")));
    const SonarLog read = readSonarLog(dir.file("packed.bag"));
    ASSERT_EQ(read.beams.size(), plain.beams.size());
    for (std::size_t i = 0; i < read.beams.size(); ++i) {
      EXPECT_EQ(read.beams[i].intensities, plain.beams[i].intensities);
      EXPECT_EQ(read.beams[i].bearing_rad, plain.beams[i].bearing_rad);
    }
  }
}

TEST(formatsRosBag, TheSonarTopicCanBeNamedAndAWrongNameIsAClearError) {
  const test::TempDir dir;
  writeRosBag(dir.file("tank.bag"), simulatedTank(1), {}, {.sonar_topic = "/sonar"});
  EXPECT_EQ(readRosBag(dir.file("tank.bag"), RosBagOptions{"/sonar"}).beams.size(), 200u);
  try {
    readRosBag(dir.file("tank.bag"), RosBagOptions{"/other"});
    FAIL() << "no error for a topic the bag does not hold";
  } catch (const FileError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("tank.bag"), std::string::npos) << what;
    EXPECT_NE(what.find("no topic /other (topics: /sonar (micron_driver_ros/ScanLine))"), std::string::npos) << what;
  }
}

TEST(formatsRosBag, TheBearingsUnitAndDirectionCanBeTold) {
  const test::TempDir dir;
  writeRosBag(dir.file("tank.bag"), simulatedTank(1));
  const SonarLog clockwise_deg = readRosBag(dir.file("tank.bag"));
  const SonarLog anticlockwise = readRosBag(dir.file("tank.bag"), {.bearing_direction = BearingDirection::kCounterClockwise});
  const SonarLog gradians = readRosBag(dir.file("tank.bag"), {.bearing_unit = BearingUnit::kGradians});
  ASSERT_EQ(anticlockwise.beams.size(), clockwise_deg.beams.size());
  const double turn = 2.0 * std::numbers::pi;
  for (std::size_t i = 0; i < clockwise_deg.beams.size(); ++i) {
    const double bearing_rad = clockwise_deg.beams[i].bearing_rad;
    EXPECT_NEAR(std::remainder(anticlockwise.beams[i].bearing_rad + bearing_rad, turn), 0.0, 1e-9) << "beam " << i;
    // the same number read as gradians: 0.9 of the angle (a turn is 400 grad)
    EXPECT_NEAR(std::remainder(gradians.beams[i].bearing_rad - 0.9 * bearing_rad, turn), 0.0, 1e-9) << "beam " << i;
  }
  EXPECT_NE(gradians.notes[0].find("read as gradians (as told)"), std::string::npos) << gradians.notes[0];
  EXPECT_NE(anticlockwise.notes[0].find("counter-clockwise"), std::string::npos) << anticlockwise.notes[0];
  EXPECT_EQ(parseBearingUnit("rad"), BearingUnit::kRadians);
  EXPECT_EQ(parseBearingDirection("ccw"), BearingDirection::kCounterClockwise);
  EXPECT_THROW(parseBearingUnit("degrees"), ValueError);
  EXPECT_THROW(parseBearingDirection("clockwise"), ValueError);
}

TEST(formatsRosBag, TheWriterRefusesBeamsItCannotStamp) {
  const test::TempDir dir;
  SonarLog log = simulatedTank(1);
  log.beams[3].time_s = -1.0;
  EXPECT_THROW(writeRosBag(dir.file("bad.bag"), log), ValueError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.bag")));
}

/// The tilted loop of a Micron (a moving, rolling and pitching vehicle), its clock moved to
/// seconds since 1970 as ROS stamps are.
MissionRun movingMission() {
  MissionRun run = simulateMission(SimulatedMission{"micron", "quay3d", "tilted-loop"});
  for (Beam& beam : run.simulation.log.beams) beam.time_s += 1.4e9;
  for (NavSample& fix : run.simulation.nav) fix.time_s += 1.4e9;
  return run;
}

void expectSameTrack(const NavTrack& read, const NavTrack& written) {
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_NEAR(read[i].time_s, written[i].time_s, 1e-6) << "fix " << i;  // a stamp's nanoseconds
    EXPECT_LT((read[i].position_ned_m - written[i].position_ned_m).norm(), 1e-9) << "fix " << i;
    EXPECT_NEAR(read[i].roll_rad, written[i].roll_rad, 1e-9) << "fix " << i;
    EXPECT_NEAR(read[i].pitch_rad, written[i].pitch_rad, 1e-9) << "fix " << i;
    EXPECT_NEAR(std::remainder(read[i].yaw_rad - written[i].yaw_rad, 2.0 * std::numbers::pi), 0.0, 1e-9) << "fix " << i;
  }
}

TEST(formatsRosBag, OdometryInEnuOrNedReadsBackAsTheNedTrack) {
  const test::TempDir dir;
  const MissionRun run = movingMission();
  const NavTrack& nav = run.simulation.nav;
  ASSERT_GT(nav.size(), 100u);
  for (const std::string frame : {"odom", "odom_ned"}) {
    writeRosBag(dir.file("mission.bag"), run.simulation.log, nav, {.nav_frame = frame});
    const std::optional<RosBagNavigation> read = readRosBagNavigation(dir.file("mission.bag"));
    ASSERT_TRUE(read.has_value());
    EXPECT_EQ(read->topic, "/odometry");
    EXPECT_EQ(read->type, "nav_msgs/Odometry");
    EXPECT_EQ(read->frame, frame == "odom" ? "ENU (REP 103), turned into NED" : "NED");
    EXPECT_EQ(read->skipped, 0u);
    expectSameTrack(read->track, nav);
  }
  // Every topic listed with its type, count and span.
  const std::vector<RosBagTopic> topics = listRosBagTopics(dir.file("mission.bag"));
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].topic, "/sonar/scan_line");
  EXPECT_EQ(topics[0].messages, run.simulation.log.beams.size());
  EXPECT_EQ(topics[1].type, "nav_msgs/Odometry");
  EXPECT_EQ(topics[1].messages, nav.size());
  EXPECT_NEAR(topics[1].first_s, nav.front().time_s, 1e-6);
  EXPECT_NEAR(topics[1].last_s, nav.back().time_s, 1e-6);
}

// NavSatFix messages read back as the fixes' latitudes and longitudes; a NaN latitude (bytes
// patched in the written bag) skips its message with a reason naming the topic and the field.
TEST(formatsRosBag, NavSatFixReadsBackAndABadLatitudeIsSkippedByName) {
  const test::TempDir dir;
  const MissionRun run = movingMission();
  const NavTrack& nav = run.simulation.nav;
  const GeodeticPoint origin{43.2961, 5.37, 0.0};
  std::vector<unsigned char> bytes = rosBagBytes(run.simulation.log, nav, {.geodetic_origin = origin});
  {
    std::ofstream(dir.file("gps.bag"), std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                               static_cast<std::streamsize>(bytes.size()));
  }
  std::optional<RosBagNavigation> read = readRosBagNavigation(dir.file("gps.bag"));
  ASSERT_TRUE(read);
  EXPECT_EQ(read->geodetic_topic, "/gps/fix");
  ASSERT_EQ(read->geodetic_fixes.size(), nav.size());
  for (std::size_t i = 0; i < nav.size(); i += 97) {
    EXPECT_NEAR(read->geodetic_fixes[i].time_s, nav[i].time_s, 1e-6);
    EXPECT_LT((geodeticToNed(origin, read->geodetic_fixes[i].point) - nav[i].position_ned_m).norm(), 1e-6) << i;
  }
  // The third fix's latitude made NaN where the bag holds it.
  const double latitude = nedToGeodetic(origin, nav[2].position_ned_m).latitude_deg;
  const auto* pattern = reinterpret_cast<const unsigned char*>(&latitude);
  const auto at = std::search(bytes.begin(), bytes.end(), pattern, pattern + sizeof latitude);
  ASSERT_NE(at, bytes.end());
  const double nan = std::nan("");
  std::copy_n(reinterpret_cast<const unsigned char*>(&nan), sizeof nan, at);
  {
    std::ofstream(dir.file("nan.bag"), std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                               static_cast<std::streamsize>(bytes.size()));
  }
  read = readRosBagNavigation(dir.file("nan.bag"));
  ASSERT_TRUE(read);
  EXPECT_EQ(read->geodetic_fixes.size(), nav.size() - 1);
  EXPECT_EQ(read->geodetic_skipped, 1u);
  ASSERT_FALSE(read->skip_reasons.empty());
  EXPECT_NE(read->skip_reasons.back().find("message 3 of /gps/fix: its latitude is not a finite number"), std::string::npos)
      << read->skip_reasons.back();
  EXPECT_EQ(read->track.size(), nav.size());  // the poses are untouched
}

// The sonar's mounting written on /tf_static (body FLU under an ENU world, FRD under a NED one)
// reads back as the sonar_to_body it was, chained from the odometry's child frame to the sonar
// messages' frame; without /tf_static, or between frames it does not join, there is none.
TEST(formatsRosBag, TheMountingOnTfStaticReadsBackAsSonarToBody) {
  const test::TempDir dir;
  const MissionRun run = movingMission();
  Eigen::Isometry3d sonar_to_body = defaultSonarToBody();
  sonar_to_body.prerotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()));  // tilted 23 degrees
  sonar_to_body.pretranslate(Eigen::Vector3d(0.3, -0.1, 0.25));
  for (const std::string frame : {"odom", "odom_ned"}) {
    writeRosBag(dir.file("mounted.bag"), run.simulation.log, run.simulation.nav,
                {.nav_frame = frame, .sonar_to_body = sonar_to_body});
    const SonarLog log = readRosBag(dir.file("mounted.bag"));
    EXPECT_EQ(log.frame_id, "sonar");
    const std::optional<RosBagNavigation> nav = readRosBagNavigation(dir.file("mounted.bag"));
    ASSERT_TRUE(nav.has_value());
    EXPECT_EQ(nav->body_frame, frame == "odom" ? "base_link" : "base_link_frd");
    const std::optional<RosBagMounting> mounting = readRosBagMounting(dir.file("mounted.bag"), log.frame_id, nav->body_frame);
    ASSERT_TRUE(mounting.has_value()) << frame;
    EXPECT_TRUE(mounting->sonar_to_body.isApprox(sonar_to_body, 1e-9)) << frame << "\n" << mounting->sonar_to_body.matrix();
    EXPECT_EQ(mounting->chain, nav->body_frame + " -> sonar");
    EXPECT_FALSE(readRosBagMounting(dir.file("mounted.bag"), "camera", nav->body_frame).has_value());
  }
  writeRosBag(dir.file("bare.bag"), run.simulation.log, run.simulation.nav);
  EXPECT_FALSE(readRosBagMounting(dir.file("bare.bag"), "sonar", "base_link").has_value());
}

// Without a pose topic, the track is dead-reckoned from the IMU's attitude, the DVL's velocity and
// the pressure's depth; written from the track itself, they give it back.
TEST(formatsRosBag, ImuDvlAndPressureAloneAreDeadReckonedIntoTheTrack) {
  const test::TempDir dir;
  const MissionRun run = movingMission();
  const NavTrack& nav = run.simulation.nav;
  writeRosBag(dir.file("raw.bag"), run.simulation.log, nav, {.odometry = false, .raw_sensors = true});
  const std::vector<RosBagTopic> topics = listRosBagTopics(dir.file("raw.bag"));
  ASSERT_EQ(topics.size(), 4u);
  const std::optional<RosBagNavigation> read = readRosBagNavigation(dir.file("raw.bag"));
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->topic, "/imu/data");
  EXPECT_EQ(read->frame, "ENU (REP 103) turned into NED, dead reckoning: attitude of /imu/data, velocity of /dvl/twist, "
                         "depth of /pressure");
  ASSERT_EQ(read->track.size(), nav.size());
  // North and east count from where the DVL's first velocity was (0, 0); down is the pressure's.
  const Eigen::Vector3d start(nav.front().position_ned_m.x(), nav.front().position_ned_m.y(), 0.0);
  double worst_m = 0.0;
  for (std::size_t i = 0; i < nav.size(); ++i) {
    worst_m = std::max(worst_m, (read->track[i].position_ned_m - (nav[i].position_ned_m - start)).norm());
    EXPECT_NEAR(read->track[i].pitch_rad, nav[i].pitch_rad, 1e-9) << "fix " << i;
    EXPECT_NEAR(std::remainder(read->track[i].yaw_rad - nav[i].yaw_rad, 2.0 * std::numbers::pi), 0.0, 1e-9) << "fix " << i;
  }
  EXPECT_LT(worst_m, 1e-6);  // the integration's rounding over the whole loop
  // A fresh-water pressure read as sea water puts the vehicle 2.5 % deeper.
  const std::optional<RosBagNavigation> fresh =
      readRosBagNavigation(dir.file("raw.bag"), {.water_density_kg_m3 = 1000.0});
  const std::size_t deep = nav.size() / 2;
  EXPECT_NEAR(fresh->track[deep].position_ned_m.z(), 1.025 * nav[deep].position_ned_m.z(), 1e-9);
}

// A vehicle without a DVL (a BlueROV2 logging its IMU and depth sensor to ROS): the track has the
// attitude and the depth, and north and east stay 0 (slamHeadingOnly takes it from there).
TEST(formatsRosBag, ImuAndPressureWithoutADvlGiveTheAttitudeAndDepth) {
  const test::TempDir dir;
  const MissionRun run = movingMission();
  const NavTrack& nav = run.simulation.nav;
  writeRosBag(dir.file("imu.bag"), run.simulation.log, nav, {.odometry = false, .raw_sensors = true, .raw_dvl = false});
  EXPECT_EQ(listRosBagTopics(dir.file("imu.bag")).size(), 3u);
  const std::optional<RosBagNavigation> read = readRosBagNavigation(dir.file("imu.bag"));
  ASSERT_TRUE(read.has_value());
  EXPECT_NE(read->frame.find("no velocity (north, east 0)"), std::string::npos) << read->frame;
  ASSERT_EQ(read->track.size(), nav.size());
  for (std::size_t i = 0; i < nav.size(); ++i) {
    EXPECT_EQ(read->track[i].position_ned_m.head<2>(), Eigen::Vector2d::Zero()) << "fix " << i;
    EXPECT_NEAR(read->track[i].position_ned_m.z(), nav[i].position_ned_m.z(), 1e-6) << "fix " << i;
    EXPECT_NEAR(std::remainder(read->track[i].yaw_rad - nav[i].yaw_rad, 2.0 * std::numbers::pi), 0.0, 1e-9) << "fix " << i;
  }
}

// A DVL mounted turned (45 degrees in yaw, as a Water Linked A50 often is on a BlueROV2) records
// its velocities in its own frame: /tf_static's rotation turns them back into the IMU's frame, and
// the dead-reckoned track is the true one.
TEST(formatsRosBag, ADvlMountedTurnedIsTurnedBackByTfStatic) {
  const test::TempDir dir;
  const MissionRun run = movingMission();
  const NavTrack& nav = run.simulation.nav;
  const Eigen::Quaterniond turned(Eigen::AngleAxisd(std::numbers::pi / 4.0, Eigen::Vector3d::UnitZ()));
  writeRosBag(dir.file("turned.bag"), run.simulation.log, nav,
              {.odometry = false, .raw_sensors = true, .dvl_rotation_flu = turned});
  const std::optional<RosBagNavigation> read = readRosBagNavigation(dir.file("turned.bag"));
  ASSERT_TRUE(read.has_value());
  EXPECT_NE(read->frame.find("turned by /tf_static (imu_link -> dvl_link)"), std::string::npos) << read->frame;
  const Eigen::Vector3d start(nav.front().position_ned_m.x(), nav.front().position_ned_m.y(), 0.0);
  double worst_m = 0.0;
  for (std::size_t i = 0; i < nav.size(); ++i) {
    worst_m = std::max(worst_m, (read->track[i].position_ned_m - (nav[i].position_ned_m - start)).norm());
  }
  EXPECT_LT(worst_m, 1e-6);  // read as the body's, the DVL's own velocities would turn the track 45 degrees away
}

TEST(formatsRosBag, AMovingMissionMapsFromItsBagAsFromItsLogAndTrack) {
  const test::TempDir dir;
  const MissionRun run = movingMission();
  writeRosBag(dir.file("mission.bag"), run.simulation.log, run.simulation.nav);
  const SonarLog log = readRosBag(dir.file("mission.bag"));
  const NavTrack nav = readRosBagNavigation(dir.file("mission.bag"))->track;
  MapperOptions options;
  options.resolution_m = 0.1;
  const SonarMapper direct = mapSonarLog(run.simulation.log, run.simulation.nav, run.options.sonar_to_body, options);
  const SonarMapper from_bag = mapSonarLog(log, nav, run.options.sonar_to_body, options);
  ASSERT_GT(direct.stats().obstacles, 100u);
  // The bag holds bearings in float32 degrees: a few obstacles may fall in a neighbouring voxel.
  EXPECT_NEAR(static_cast<double>(from_bag.stats().obstacles), static_cast<double>(direct.stats().obstacles),
              0.01 * static_cast<double>(direct.stats().obstacles));
}

TEST(formatsRosBag, ANavigationTopicIsChosenOrNamedAndWrongNamesAreClearErrors) {
  const test::TempDir dir;
  writeRosBag(dir.file("sonar_only.bag"), simulatedTank(1));
  EXPECT_FALSE(readRosBagNavigation(dir.file("sonar_only.bag")).has_value());
  try {
    readRosBagNavigation(dir.file("sonar_only.bag"), {.nav_topic = "/sonar/scan_line"});
    FAIL() << "a sonar topic read as navigation";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find("the topic /sonar/scan_line holds no pose"), std::string::npos) << error.what();
  }
  try {
    readRosBagNavigation(dir.file("sonar_only.bag"), {.nav_topic = "/odom"});
    FAIL() << "a topic that is not there";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find("no topic /odom (topics: /sonar/scan_line (micron_driver_ros/ScanLine))"),
              std::string::npos) << error.what();
  }
}

TEST(formatsRosBag, TheSharedPoolBagMapsByDefault) {
  const std::string path = std::string(SONARMAP_SHARED_DATA) + "/micron_pool_ros1.bag";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const SonarLog log = readSonarLog(path);
  ASSERT_EQ(log.beams.size(), 3616u);  // the data README: 3,616 beams on /micron_driver/scan_line
  EXPECT_EQ(log.skipped_beams, 0u);
  EXPECT_EQ(log.sonar, "ROS topic /micron_driver/scan_line (micron_driver_ros/ScanLine)");
  for (const Beam& beam : log.beams) {
    ASSERT_EQ(beam.intensities.size(), 200u);
    ASSERT_NEAR(beam.bin_length_m, 0.05, 1e-6);
  }
  // 1.8° steps of bearing, stamps of 2014-07-18 about 43 ms apart
  const double step_rad = std::abs(std::remainder(log.beams[1].bearing_rad - log.beams[0].bearing_rad, 2.0 * std::numbers::pi));
  EXPECT_NEAR(step_rad, 1.8 * std::numbers::pi / 180.0, 1e-5);
  EXPECT_NEAR(log.beams.front().time_s, 1405709972.9, 0.1);
  EXPECT_NEAR((log.beams.back().time_s - log.beams.front().time_s) / (log.beams.size() - 1), 0.043, 0.002);
  const SonarMapper mapper = mapSonarLog(log);
  EXPECT_GT(mapper.stats().obstacles, 100u);
}

}  // namespace
}  // namespace sonarmap
