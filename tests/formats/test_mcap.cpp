/// Tests of ROS 2 logs in MCAP files (mcap_writer.hpp, and the ROS log readers: ros_bag_reader.hpp,
/// ros_bag_navigation.hpp): a simulated moving mission written with each chunk compression and
/// read back, its map against the log's, and broken files.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/mcap_writer.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"

namespace sonarmap {
namespace {

MissionRun movingMission() {
  MissionRun run = simulateMission(SimulatedMission{"micron", "quay3d", "tilted-loop"});
  for (Beam& beam : run.simulation.log.beams) beam.time_s += 1.7e9;  // ROS 2 stamps: seconds since 1970
  for (NavSample& fix : run.simulation.nav) fix.time_s += 1.7e9;
  return run;
}

TEST(formatsMcap, AMissionReadsBackWithEveryCompression) {
  const test::TempDir dir;
  const MissionRun run = movingMission();
  const SonarLog& written = run.simulation.log;
  const NavTrack& nav = run.simulation.nav;
  for (const McapCompression compression : {McapCompression::kNone, McapCompression::kZstd, McapCompression::kLz4}) {
    const std::string path = dir.file("mission.mcap");
    writeMcap(path, written, nav, {.compression = compression});
    const SonarLog read = readSonarLog(path);
    ASSERT_EQ(read.beams.size(), written.beams.size());
    EXPECT_EQ(read.sonar, "ROS topic /sonar/scan_line (micron_driver_ros/msg/ScanLine)");
    EXPECT_EQ(read.skipped_beams, 0u);
    for (std::size_t i = 0; i < read.beams.size(); i += 97) {
      EXPECT_EQ(read.beams[i].intensities, written.beams[i].intensities) << "beam " << i;
      EXPECT_NEAR(std::remainder(read.beams[i].bearing_rad - written.beams[i].bearing_rad, 2.0 * std::numbers::pi), 0.0, 1e-6);
      EXPECT_NEAR(read.beams[i].time_s, written.beams[i].time_s, 1e-6);
    }
    const std::optional<RosBagNavigation> track = readRosBagNavigation(path);
    ASSERT_TRUE(track.has_value());
    EXPECT_EQ(track->type, "nav_msgs/msg/Odometry");
    ASSERT_EQ(track->track.size(), nav.size());
    for (std::size_t i = 0; i < nav.size(); i += 13) {
      EXPECT_LT((track->track[i].position_ned_m - nav[i].position_ned_m).norm(), 1e-9) << "fix " << i;
      EXPECT_NEAR(std::remainder(track->track[i].yaw_rad - nav[i].yaw_rad, 2.0 * std::numbers::pi), 0.0, 1e-9);
      EXPECT_NEAR(track->track[i].roll_rad, nav[i].roll_rad, 1e-9);
    }
  }
  const std::vector<RosBagTopic> topics = listRosBagTopics(dir.file("mission.mcap"));
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[1].topic, "/odometry");
  EXPECT_EQ(topics[1].messages, nav.size());
  EXPECT_NEAR(topics[0].first_s, written.beams.front().time_s, 1e-6);
}

TEST(formatsMcap, AMissionMapsFromItsMcapAsFromItsLogAndTrack) {
  const test::TempDir dir;
  const MissionRun run = movingMission();
  writeMcap(dir.file("mission.mcap"), run.simulation.log, run.simulation.nav);
  MapperOptions options;
  options.resolution_m = 0.1;
  const SonarMapper direct = mapSonarLog(run.simulation.log, run.simulation.nav, run.options.sonar_to_body, options);
  const SonarMapper from_file = mapSonarLog(readSonarLog(dir.file("mission.mcap")),
                                            readRosBagNavigation(dir.file("mission.mcap"))->track, run.options.sonar_to_body, options);
  ASSERT_GT(direct.stats().obstacles, 100u);
  EXPECT_NEAR(static_cast<double>(from_file.stats().obstacles), static_cast<double>(direct.stats().obstacles),
              0.01 * static_cast<double>(direct.stats().obstacles));  // bearings in float32 degrees
}

TEST(formatsMcap, BrokenFilesAreClearErrors) {
  const test::TempDir dir;
  SonarLog log = movingMission().simulation.log;
  log.beams.resize(50);
  const std::vector<unsigned char> bytes = mcapBytes(log, {}, {.compression = McapCompression::kZstd});
  auto expectError = [&](const std::vector<unsigned char>& broken, const std::string& message) {
    const std::string path = dir.file("broken.mcap");
    writeBytesAtomically(path, broken);
    try {
      readSonarLog(path);
      ADD_FAILURE() << "no error for " << message;
    } catch (const FileError& error) {
      EXPECT_NE(std::string(error.what()).find(message), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("broken.mcap"), std::string::npos) << error.what();
    }
  };
  expectError(std::vector<unsigned char>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2)),
              "runs past the file");
  std::vector<unsigned char> zip = bytes;
  const std::string zstd = "zstd";
  const auto at = std::search(zip.begin(), zip.end(), zstd.begin(), zstd.end());
  ASSERT_NE(at, zip.end());
  std::copy_n("zip!", 4, at);
  expectError(zip, "unknown chunk compression 'zip!'");
  std::vector<unsigned char> flipped = bytes;
  const std::size_t chunk_data = static_cast<std::size_t>(at - zip.begin()) + 4 + 8 + 10;  // into the compressed records
  flipped[chunk_data] ^= 0xFF;
  expectError(flipped, "MCAP: byte");
  std::vector<unsigned char> not_mcap = bytes;
  not_mcap[1] = 'X';
  expectError(not_mcap, "ROS bag: byte 0: the first line is not '#ROSBAG V2.0'");
}

TEST(formatsMcap, Ros2DefinitionsWithBoundsDefaultsAndUnitsInComments) {
  // The Ping360 ROS 2 driver's echo (CentraleNantesRobotics/ping360_sonar, msg/SonarEcho.msg), its
  // angle in radians by its comment, with a bounded string and a default value added.
  const std::string definition =
      "std_msgs/Header header            #header info\n"
      "float32 angle               # the measurement angle [rad]\n"
      "uint8 gain  # Sonar Gain\nuint16 number_of_samples\nuint16 transmit_frequency # [kHz]\n"
      "uint16 speed_of_sound 1500 # [m/s]\nuint8 range      #  range value [m]\nstring<=8 note\n"
      "uint8[] intensities    # intensity data [0-255]\nint32 LIMIT=10\n"
      "================================================================================\n"
      "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n"
      "================================================================================\n"
      "MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n";
  // One echo at 0.5 rad of 4 samples over 2 m, stamped 1.7e9 + 0.25 s, CDR by hand.
  std::vector<unsigned char> cdr = {0x00, 0x01, 0x00, 0x00};
  auto put = [&](const void* value, std::size_t size) {
    while ((cdr.size() - 4) % size != 0) cdr.push_back(0);
    cdr.insert(cdr.end(), static_cast<const unsigned char*>(value), static_cast<const unsigned char*>(value) + size);
  };
  const std::int32_t sec = 1700000000;
  const std::uint32_t nanosec = 250000000, frame_length = 6, note_length = 1, samples = 4;
  const float angle = 0.5F;
  const std::uint8_t gain = 1, range = 2;
  const std::uint16_t number = 4, frequency = 750, sound = 1500;
  put(&sec, 4);
  put(&nanosec, 4);
  put(&frame_length, 4);
  cdr.insert(cdr.end(), {'s', 'o', 'n', 'a', 'r', 0});
  put(&angle, 4);
  put(&gain, 1);
  put(&number, 2);
  put(&frequency, 2);
  put(&sound, 2);
  put(&range, 1);
  put(&note_length, 4);
  cdr.push_back(0);
  put(&samples, 4);
  cdr.insert(cdr.end(), {0, 10, 200, 30});
  // A one-message MCAP file around it: the writer's framing with this schema and message.
  std::vector<unsigned char> file = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  auto record = [&](std::uint8_t opcode, const std::vector<unsigned char>& content) {
    file.push_back(opcode);
    const std::uint64_t length = content.size();
    file.insert(file.end(), reinterpret_cast<const unsigned char*>(&length), reinterpret_cast<const unsigned char*>(&length) + 8);
    file.insert(file.end(), content.begin(), content.end());
  };
  auto text = [](std::vector<unsigned char>& out, const std::string& s) {
    const std::uint32_t length = static_cast<std::uint32_t>(s.size());
    out.insert(out.end(), reinterpret_cast<const unsigned char*>(&length), reinterpret_cast<const unsigned char*>(&length) + 4);
    out.insert(out.end(), s.begin(), s.end());
  };
  std::vector<unsigned char> schema = {1, 0};
  text(schema, "ping360_sonar_msgs/msg/SonarEcho");
  text(schema, "ros2msg");
  text(schema, definition);
  record(0x03, schema);
  std::vector<unsigned char> channel = {1, 0, 1, 0};
  text(channel, "/ping360_node/sonar/data");
  text(channel, "cdr");
  channel.insert(channel.end(), {0, 0, 0, 0});
  record(0x04, channel);
  std::vector<unsigned char> message = {1, 0, 0, 0, 0, 0};
  const std::uint64_t log_time = 1700000000250000000ull;
  for (int i = 0; i < 2; ++i) message.insert(message.end(), reinterpret_cast<const unsigned char*>(&log_time), reinterpret_cast<const unsigned char*>(&log_time) + 8);
  message.insert(message.end(), cdr.begin(), cdr.end());
  record(0x05, message);
  const test::TempDir dir;
  writeBytesAtomically(dir.file("echo.mcap"), file);
  const SonarLog log = readSonarLog(dir.file("echo.mcap"));
  ASSERT_EQ(log.beams.size(), 1u);
  EXPECT_EQ(log.beams[0].intensities, (std::vector<std::uint8_t>{0, 10, 200, 30}));
  EXPECT_DOUBLE_EQ(log.beams[0].bin_length_m, 0.5);
  EXPECT_NEAR(log.beams[0].time_s, 1700000000.25, 1e-6);
  EXPECT_NEAR(log.beams[0].bearing_rad, 0.5, 1e-6);  // radians, clockwise as beam.hpp counts
  EXPECT_NE(log.notes[0].find("read as radians"), std::string::npos) << log.notes[0];
}

}  // namespace
}  // namespace sonarmap
