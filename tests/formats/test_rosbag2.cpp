/// Tests of ROS 2 logs in rosbag2's SQLite storage (src/formats/rosbag2_sqlite.hpp, read through
/// readRosBag and readRosBagNavigation): databases written here with libsqlite3 as rosbag2 writes
/// them, Humble's (type names only: built-in definitions) and Iron's (a message_definitions table),
/// split over two files, and broken ones.

#include <gtest/gtest.h>

#include <sqlite3.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;

/// Plain little-endian CDR: the encapsulation header, each number aligned to its size after it.
class Cdr {
 public:
  Cdr() : bytes_{0x00, 0x01, 0x00, 0x00} {}
  template <class T>
  Cdr& put(T value) {
    while ((bytes_.size() - 4) % sizeof(T) != 0) bytes_.push_back(0);
    const auto* raw = reinterpret_cast<const unsigned char*>(&value);
    bytes_.insert(bytes_.end(), raw, raw + sizeof(T));
    return *this;
  }
  Cdr& text(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
    return *this;
  }
  Cdr& header(std::int32_t sec, const std::string& frame) { return put<std::int32_t>(sec).put<std::uint32_t>(0).text(frame); }
  const std::vector<unsigned char>& done() const { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
};

/// The Ping360 ROS 2 driver's echo: `angle_rad`, 4 samples over 2 m.
std::vector<unsigned char> sonarEcho(std::int32_t sec, float angle_rad) {
  Cdr out;
  out.header(sec, "sonar").put<float>(angle_rad).put<std::uint8_t>(1).put<std::uint16_t>(4).put<std::uint16_t>(750);
  out.put<std::uint16_t>(1500).put<std::uint8_t>(2).put<std::uint32_t>(4);
  for (const std::uint8_t v : {0, 10, 200, 30}) out.put<std::uint8_t>(v);
  return out.done();
}

/// A nav_msgs/msg/Odometry at ENU (east_m, north_m, up 0), facing north (ENU yaw 90°).
std::vector<unsigned char> odometry(std::int32_t sec, double east_m, double north_m) {
  Cdr out;
  out.header(sec, "odom").text("base_link");
  const double half = std::numbers::pi / 4.0;
  for (const double v : {east_m, north_m, 0.0, 0.0, 0.0, std::sin(half), std::cos(half)}) out.put<double>(v);
  for (int i = 0; i < 36 + 6 + 36; ++i) out.put<double>(0.0);
  return out.done();
}

/// A rosbag2 database as rosbag2_storage_default_plugins' sqlite3 storage writes it.
class Db3 {
 public:
  explicit Db3(const std::string& file) {
    EXPECT_EQ(sqlite3_open(file.c_str(), &db_), SQLITE_OK);
    exec("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
         "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL)");
    exec("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL)");
  }
  ~Db3() { sqlite3_close(db_); }
  void exec(const std::string& sql) { EXPECT_EQ(sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK) << sql; }
  void topic(int id, const std::string& name, const std::string& type) {
    exec("INSERT INTO topics VALUES(" + std::to_string(id) + ", '" + name + "', '" + type + "', 'cdr', '')");
  }
  void message(int topic_id, std::int64_t timestamp_ns, const std::vector<unsigned char>& data) {
    sqlite3_stmt* s = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db_, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?1, ?2, ?3)", -1, &s, nullptr), SQLITE_OK);
    sqlite3_bind_int(s, 1, topic_id);
    sqlite3_bind_int64(s, 2, timestamp_ns);
    sqlite3_bind_blob(s, 3, data.data(), static_cast<int>(data.size()), SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(s), SQLITE_DONE);
    sqlite3_finalize(s);
  }

 private:
  sqlite3* db_ = nullptr;
};

constexpr std::int32_t kSec = 1700000000;

TEST(formatsRosbag2, AHumbleFolderSplitInTwoFilesReadsWithBuiltInDefinitions) {
  const test::TempDir dir;
  const fs::path folder = fs::path(dir.file("rosbag2_2024_05_01-10_00_00"));
  fs::create_directories(folder);
  std::ofstream(folder / "metadata.yaml") << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n";
  {
    Db3 first((folder / "rosbag2_2024_05_01-10_00_00_0.db3").string());
    first.topic(1, "/ping360_node/sonar/data", "ping360_sonar_msgs/msg/SonarEcho");
    first.topic(2, "/odom", "nav_msgs/msg/Odometry");
    for (int i = 0; i < 3; ++i) first.message(1, (kSec + i) * 1000000000LL, sonarEcho(kSec + i, 0.1F * static_cast<float>(i)));
    first.message(2, kSec * 1000000000LL, odometry(kSec, 0.0, 0.0));
    first.message(2, (kSec + 2) * 1000000000LL, odometry(kSec + 2, 1.0, 2.0));
  }
  {
    Db3 second((folder / "rosbag2_2024_05_01-10_00_00_1.db3").string());
    second.topic(1, "/ping360_node/sonar/data", "ping360_sonar_msgs/msg/SonarEcho");
    for (int i = 3; i < 5; ++i) second.message(1, (kSec + i) * 1000000000LL, sonarEcho(kSec + i, 0.1F * static_cast<float>(i)));
  }
  EXPECT_EQ(logFormatOfPath(folder.string()), LogFormat::kRosbag2);
  const SonarLog log = readSonarLog(folder.string());
  ASSERT_EQ(log.beams.size(), 5u);
  EXPECT_EQ(log.sonar, "ROS topic /ping360_node/sonar/data (ping360_sonar_msgs/msg/SonarEcho)");
  EXPECT_EQ(log.beams[4].intensities, (std::vector<std::uint8_t>{0, 10, 200, 30}));
  EXPECT_DOUBLE_EQ(log.beams[0].bin_length_m, 0.5);  // range 2 m over 4 samples
  EXPECT_NEAR(log.beams[4].time_s, kSec + 4.0, 1e-6);
  EXPECT_NEAR(log.beams[2].bearing_rad, 0.2, 1e-6);  // radians, clockwise as beam.hpp counts
  const std::optional<RosBagNavigation> nav = readRosBagNavigation(folder.string());
  ASSERT_TRUE(nav.has_value());
  ASSERT_EQ(nav->track.size(), 2u);
  EXPECT_LT((nav->track[1].position_ned_m - Eigen::Vector3d(2.0, 1.0, 0.0)).norm(), 1e-12);  // north 2, east 1
  EXPECT_NEAR(nav->track[1].yaw_rad, 0.0, 1e-12);  // facing north
  // One file of it reads on its own.
  EXPECT_EQ(readSonarLog((folder / "rosbag2_2024_05_01-10_00_00_1.db3").string()).beams.size(), 2u);
  // Beam by beam, file after file, the same beams (openBeamSource, pass after pass).
  const std::unique_ptr<BeamSource> source = openBeamSource(folder.string(), LogFormat::kRosbag2);
  for (int pass = 0; pass < 2; ++pass) {
    source->rewind();
    for (const Beam& expected : log.beams) {
      const std::optional<Beam> beam = source->next();
      ASSERT_TRUE(beam.has_value());
      EXPECT_EQ(beam->time_s, expected.time_s);
      EXPECT_EQ(beam->bearing_rad, expected.bearing_rad);
      EXPECT_EQ(beam->intensities, expected.intensities);
    }
    EXPECT_FALSE(source->next().has_value());
    EXPECT_EQ(source->header().notes, log.notes);
    EXPECT_EQ(source->header().clock_utc_s, log.clock_utc_s);
  }
}

TEST(formatsRosbag2, AnIronDatabaseCarriesTheDefinitionOfADriversOwnMessage) {
  const test::TempDir dir;
  const std::string file = dir.file("run_0.db3");
  {
    Db3 db(file);
    db.exec("CREATE TABLE message_definitions(id INTEGER PRIMARY KEY, topic_type TEXT NOT NULL, encoding TEXT NOT NULL, "
            "encoded_message_definition TEXT NOT NULL, type_description_hash TEXT NOT NULL)");
    db.exec("INSERT INTO message_definitions VALUES(1, 'my_sonar/msg/Beam', 'ros2msg', "
            "'std_msgs/Header header\nfloat64 bearing_deg\nfloat32 bin_length 0.05\nuint8[<=2000] data\n"
            "================================================================================\n"
            "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n', 'RIHS01_0')");
    db.topic(1, "/sonar", "my_sonar/msg/Beam");
    Cdr beam;
    beam.header(kSec, "sonar").put<double>(90.0).put<float>(0.1F).put<std::uint32_t>(3);
    for (const std::uint8_t v : {5, 250, 7}) beam.put<std::uint8_t>(v);
    db.message(1, kSec * 1000000000LL, beam.done());
  }
  const SonarLog log = readSonarLog(file);
  ASSERT_EQ(log.beams.size(), 1u);
  EXPECT_EQ(log.beams[0].intensities, (std::vector<std::uint8_t>{5, 250, 7}));
  EXPECT_NEAR(log.beams[0].bin_length_m, 0.1, 1e-7);
  EXPECT_NEAR(log.beams[0].bearing_rad, 0.5 * std::numbers::pi, 1e-9);  // 90° clockwise: starboard
}

// A Humble database of a driver's own message (no definitions stored): unreadable with the
// built-in types alone, read with --msg-path's .msg files (PKG/msg/NAME.msg, a nested type of
// the same package named without it, std_msgs/Header from the built-in ones).
TEST(formatsRosbag2, AHumbleDriversOwnMessageReadsWithItsMsgFiles) {
  const test::TempDir dir;
  const std::string file = dir.file("run_0.db3");
  {
    Db3 db(file);
    db.topic(1, "/sonar", "vendor_sonar/msg/Scan");
    Cdr scan;
    scan.header(kSec, "sonar").put<float>(0.5F).put<double>(0.1).put<std::uint32_t>(3);
    for (const std::uint8_t v : {5, 250, 7}) scan.put<float>(static_cast<float>(v) * 0.1F).put<std::uint8_t>(v);
    db.message(1, kSec * 1000000000LL, scan.done());
  }
  EXPECT_THROW(readSonarLog(file), FileError);  // vendor_sonar/msg/Scan: no definition
  fs::create_directories(dir.path() / "msgs" / "vendor_sonar" / "msg");
  std::ofstream(dir.path() / "msgs" / "vendor_sonar" / "msg" / "Scan.msg")
      << "# one beam of the head\nstd_msgs/Header header\nfloat32 angle  # radians\nfloat64 bin_size\nBin[] bins\n"
         "uint8 MODE_FAST=1\n";
  std::ofstream(dir.path() / "msgs" / "vendor_sonar" / "msg" / "Bin.msg") << "float32 distance\nuint8 intensity\n";
  LogReadOptions options;
  options.msg_path = (dir.path() / "msgs").string();
  const SonarLog log = readSonarLog(file, LogFormat::kRosbag2, options);
  ASSERT_EQ(log.beams.size(), 1u);
  EXPECT_EQ(log.beams[0].intensities, (std::vector<std::uint8_t>{5, 250, 7}));
  EXPECT_NEAR(log.beams[0].bin_length_m, 0.1, 1e-12);
  EXPECT_EQ(log.frame_id, "sonar");
  const std::vector<RosBagTopic> topics = listRosBagTopics(file, options.msg_path);
  ASSERT_EQ(topics.size(), 1u);
  // A used type found nowhere leaves the topic without a definition.
  fs::remove(dir.path() / "msgs" / "vendor_sonar" / "msg" / "Bin.msg");
  EXPECT_THROW(readSonarLog(file, LogFormat::kRosbag2, options), FileError);
}

TEST(formatsRosbag2, BrokenLogsAreClearErrors) {
  const test::TempDir dir;
  const fs::path empty = fs::path(dir.file("empty_bag"));
  fs::create_directories(empty);
  std::ofstream(empty / "metadata.yaml") << "rosbag2_bagfile_information:\n";
  auto expectError = [](const std::string& path, const std::string& message) {
    try {
      readSonarLog(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const FileError& error) {
      EXPECT_NE(std::string(error.what()).find(message), std::string::npos) << error.what();
    }
  };
  expectError(empty.string(), "the folder holds no .db3 or .mcap file");
  const std::string other = dir.file("other.db3");
  {
    sqlite3* db = nullptr;
    sqlite3_open(other.c_str(), &db);
    sqlite3_exec(db, "CREATE TABLE notes(text TEXT)", nullptr, nullptr, nullptr);
    sqlite3_close(db);
  }
  expectError(other, "not a rosbag2 database");
  const std::string unknown = dir.file("unknown.db3");
  {
    Db3 db(unknown);
    db.topic(1, "/sonar", "vendor_msgs/msg/Echo");
    db.message(1, kSec * 1000000000LL, {0, 1, 0, 0});
  }
  expectError(unknown, "/sonar (vendor_msgs/msg/Echo, no message definition)");
}

}  // namespace
}  // namespace sonarmap
