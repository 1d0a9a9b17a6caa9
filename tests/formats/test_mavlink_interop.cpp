/// Interoperability with a MAVLink implementation that is not sonarmap's: npm's node-mavlink (its
/// version pinned by tests/interop/package-lock.json). A navigation written as a CSV is encoded by
/// node-mavlink as an autopilot sends it (tests/interop/encode_navigation.js), MAVLink 1 and 2, into
/// a `.tlog` and over UDP, and decoded by MavlinkNavigation and readMavlinkTlogNavigation: the fixes
/// are the CSV's to float32. sonarmap's encoder's frames are parsed by node-mavlink
/// (tests/interop/parse_frames.js) field by field. Skipped, with the reason, without `node` or
/// without tests/interop/node_modules (`npm ci` there; scripts/install-deps.sh test does it).

#include <gtest/gtest.h>

#include <poll.h>
#include <sys/socket.h>
#include <netinet/in.h>
#include <arpa/inet.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/temp_dir.hpp"
#include "sonarmap/formats/mavlink.hpp"
#include "sonarmap/formats/mavlink_messages.hpp"
#include "sonarmap/formats/mavlink_navigation.hpp"
#include "sonarmap/formats/navigation_reader.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;
const fs::path kInterop = SONARMAP_INTEROP_DIR;
constexpr std::uint64_t kEpochUs = 1723630500000000ULL;

std::optional<std::string> whyNodeMavlinkIsMissing() {
  if (std::system("node --version >/dev/null 2>&1") != 0) {
    return "node is not on PATH: install Node.js and run `npm ci` in tests/interop (scripts/install-deps.sh test)";
  }
  if (!fs::exists(kInterop / "node_modules" / "node-mavlink" / "package.json")) {
    return "tests/interop/node_modules is missing: run `npm ci` in tests/interop (scripts/install-deps.sh test)";
  }
  return std::nullopt;
}

#define SKIP_WITHOUT_NODE_MAVLINK()                                          \
  if (const std::optional<std::string> why = whyNodeMavlinkIsMissing()) { \
    GTEST_SKIP() << *why;                                                  \
  }

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs a node script of tests/interop with `arguments`; its standard output.
std::string runNode(const std::string& script, const std::string& arguments, const fs::path& dir) {
  const fs::path out = dir / "node.out", err = dir / "node.err";
  const std::string command = "cd '" + kInterop.string() + "' && node " + script + " " + arguments + " >'" +
                              out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << command << "\n" << readText(err);
  return readText(out);
}

/// A dive of 100 fixes `interval_s` apart from boot time 100 s, written as a navigation CSV.
struct Dive {
  std::vector<NavSample> rows;
  explicit Dive(double interval_s = 0.1) {
    for (int i = 0; i < 100; ++i) {
      NavSample s;
      s.time_s = 100.0 + interval_s * i;
      s.position_ned_m = Eigen::Vector3d(3.0 * std::sin(0.05 * i), 0.2 * i - 4.0, 2.0 + 0.5 * std::sin(0.03 * i));
      s.roll_rad = 0.05 * std::sin(0.1 * i);
      s.pitch_rad = -0.03;
      s.yaw_rad = std::remainder(-3.0 + 0.07 * i, 2.0 * std::numbers::pi);
      rows.push_back(s);
    }
  }
  void write(const fs::path& path) const {
    std::ofstream out(path);
    out << "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\n";
    char line[256];
    for (const NavSample& s : rows) {
      std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", s.time_s, s.position_ned_m.x(),
                    s.position_ned_m.y(), s.position_ned_m.z(), s.roll_rad, s.pitch_rad, s.yaw_rad);
      out << line;
    }
  }
};

double f32(double v) { return static_cast<float>(v); }

/// The frames of a `.tlog` fed to MavlinkNavigation one record at a time, received at its stamp
/// (seconds after kEpochUs).
std::vector<NavSample> liveFixesOfTlog(const std::string& tlog, MavlinkNavigation& nav, std::size_t* frames) {
  std::vector<NavSample> fixes;
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(tlog.data());
  *frames = 0;
  for (std::size_t at = 0; at + 8 < tlog.size();) {
    std::uint64_t stamp_us = 0;
    for (int i = 0; i < 8; ++i) stamp_us = (stamp_us << 8) | bytes[at + static_cast<std::size_t>(i)];
    const std::span<const std::uint8_t> rest(bytes + at + 8, tlog.size() - at - 8);
    const MavlinkFrameRead read = readMavlinkFrame(rest);
    EXPECT_EQ(read.status, MavlinkFrameStatus::kFrame) << "at byte " << at;
    if (read.size == 0) break;
    for (const NavSample& f : nav.feed(rest.first(read.size), static_cast<double>(stamp_us - kEpochUs) / 1e6)) {
      fixes.push_back(f);
    }
    ++*frames;
    at += 8 + read.size;
  }
  for (const NavSample& f : nav.finish()) fixes.push_back(f);
  return fixes;
}

TEST(formatsMavlinkInterop, NodeMavlinksTelemetryOfANavigationDecodesToItsFixesLiveAndAsATlog) {
  SKIP_WITHOUT_NODE_MAVLINK();
  test::TempDir dir;
  const Dive dive;
  dive.write(dir.file("dive.csv"));
  for (const int version : {1, 2}) {
    const std::string tlog_path = dir.file("dive" + std::to_string(version) + ".tlog");
    runNode("encode_navigation.js", "'" + dir.file("dive.csv") + "' --version " + std::to_string(version) + " --tlog '" +
                                        tlog_path + "' --epoch-us " + std::to_string(kEpochUs),
            dir.path());
    const std::string tlog = readText(tlog_path);
    MavlinkNavigation live("node-mavlink v" + std::to_string(version));
    std::size_t frames = 0;
    const std::vector<NavSample> fixes = liveFixesOfTlog(tlog, live, &frames);
    EXPECT_EQ(frames, 1 + 10 + 4 * dive.rows.size());  // a ground station's HEARTBEAT, the vehicle's, 4 per row
    EXPECT_EQ(live.streamCounts().frames, frames);
    EXPECT_EQ(live.streamCounts().bad_frames + live.streamCounts().noise_bytes, 0u);
    EXPECT_EQ(live.vehicle()->system, 1);
    EXPECT_EQ(live.description(), "attitude ATTITUDE, position LOCAL_POSITION_NED");
    ASSERT_EQ(fixes.size(), dive.rows.size()) << version;
    for (std::size_t i = 0; i < fixes.size(); ++i) {
      const NavSample& row = dive.rows[i];
      EXPECT_NEAR(fixes[i].time_s, row.time_s + 0.020, 1e-6) << i;  // boot time + the least delay, 20 ms
      EXPECT_EQ(fixes[i].position_ned_m.x(), f32(row.position_ned_m.x())) << i;
      EXPECT_EQ(fixes[i].position_ned_m.y(), f32(row.position_ned_m.y())) << i;
      EXPECT_EQ(fixes[i].position_ned_m.z(), f32(row.position_ned_m.z())) << i;
      EXPECT_EQ(fixes[i].roll_rad, f32(row.roll_rad)) << i;
      EXPECT_EQ(fixes[i].pitch_rad, f32(row.pitch_rad)) << i;
      EXPECT_EQ(fixes[i].yaw_rad, f32(row.yaw_rad)) << i;
    }
    // the same telemetry log read whole: the same fixes
    const NavigationSource read = readMavlinkTlogNavigation(tlog_path);
    ASSERT_EQ(read.track.size(), fixes.size());
    for (std::size_t i = 0; i < fixes.size(); ++i) {
      EXPECT_NEAR(read.track[i].time_s - kEpochUs / 1e6, fixes[i].time_s, 1e-6) << i;
      EXPECT_EQ(read.track[i].position_ned_m, fixes[i].position_ned_m) << i;
      EXPECT_EQ(read.track[i].yaw_rad, fixes[i].yaw_rad) << i;
    }
    EXPECT_EQ(read.skipped, 0u);
  }
}

TEST(formatsMavlinkInterop, WithoutLocalPositionTheDepthIsGlobalPositionsRelativeAltitude) {
  SKIP_WITHOUT_NODE_MAVLINK();
  test::TempDir dir;
  const Dive dive;
  dive.write(dir.file("dive.csv"));
  runNode("encode_navigation.js", "'" + dir.file("dive.csv") + "' --tlog '" + dir.file("depth.tlog") +
                                      "' --without local --epoch-us " + std::to_string(kEpochUs),
          dir.path());
  MavlinkNavigation live;
  std::size_t frames = 0;
  const std::vector<NavSample> fixes = liveFixesOfTlog(readText(dir.file("depth.tlog")), live, &frames);
  const NavigationSource read = readMavlinkTlogNavigation(dir.file("depth.tlog"));
  ASSERT_EQ(fixes.size(), dive.rows.size());
  ASSERT_EQ(read.track.size(), dive.rows.size());
  for (std::size_t i = 0; i < fixes.size(); ++i) {
    EXPECT_NEAR(fixes[i].position_ned_m.z(), dive.rows[i].position_ned_m.z(), 0.0005) << i;  // millimetres
    EXPECT_EQ(fixes[i].position_ned_m.x(), 0.0);
    EXPECT_EQ(read.track[i].position_ned_m, fixes[i].position_ned_m) << i;
  }
  EXPECT_TRUE(read.description.find("depth GLOBAL_POSITION_INT.relative_alt, no horizontal position") != std::string::npos)
      << read.description;
  EXPECT_TRUE(read.geodetic_fixes.empty());  // lat, lon 0, 0: ArduSub's "no position"
}

TEST(formatsMavlinkInterop, GlobalPositionsLatitudeAndLongitudePlaceTheTrack) {
  SKIP_WITHOUT_NODE_MAVLINK();
  test::TempDir dir;
  const Dive dive;
  dive.write(dir.file("dive.csv"));
  // A vehicle at the surface at one place, its GPS in GLOBAL_POSITION_INT as node-mavlink encodes it.
  runNode("encode_navigation.js", "'" + dir.file("dive.csv") + "' --tlog '" + dir.file("gps.tlog") +
                                      "' --without local --lat-lon 43.2961,5.37 --epoch-us " + std::to_string(kEpochUs),
          dir.path());
  const NavigationSource read = readNavigation(dir.file("gps.tlog"));
  ASSERT_EQ(read.geodetic_fixes.size(), dive.rows.size());
  for (const GeodeticFix& fix : read.geodetic_fixes) {
    EXPECT_NEAR(fix.point.latitude_deg, 43.2961, 1e-12);
    EXPECT_NEAR(fix.point.longitude_deg, 5.37, 1e-12);
  }
  EXPECT_NEAR(read.geodetic_fixes.front().time_s, read.track.front().time_s, 0.05);  // the same clock
  EXPECT_EQ(read.geodetic_description, "GLOBAL_POSITION_INT (lat, lon)");
  // No horizontal position (north, east 0): the navigation's zero is where the GPS is.
  ASSERT_TRUE(read.geodetic_origin);
  EXPECT_NEAR(read.geodetic_origin->latitude_deg, 43.2961, 1e-9);
  EXPECT_NEAR(read.geodetic_origin->longitude_deg, 5.37, 1e-9);
}

/// A UDP socket on 127.0.0.1 at a free port.
class UdpReceiver {
 public:
  UdpReceiver() : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    socklen_t length = sizeof address;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length);
    port_ = ntohs(address.sin_port);
  }
  ~UdpReceiver() { ::close(fd_); }
  int port() const { return port_; }
  /// The next datagram, or nothing after `timeout_ms` without one.
  std::optional<std::vector<std::uint8_t>> receive(int timeout_ms) {
    pollfd waiting{fd_, POLLIN, 0};
    if (::poll(&waiting, 1, timeout_ms) <= 0) return std::nullopt;
    std::vector<std::uint8_t> datagram(65536);
    const ssize_t got = ::recv(fd_, datagram.data(), datagram.size(), 0);
    if (got < 0) return std::nullopt;
    datagram.resize(static_cast<std::size_t>(got));
    return datagram;
  }

 private:
  int fd_;
  int port_ = 0;
};

TEST(formatsMavlinkInterop, NodeMavlinkOverUdpDatagramsOfSeveralFramesDecodesToTheRows) {
  SKIP_WITHOUT_NODE_MAVLINK();
  test::TempDir dir;
  const Dive dive(0.01);  // sent in real time: 1 s
  dive.write(dir.file("dive.csv"));
  UdpReceiver udp;
  const std::string command = "cd '" + kInterop.string() + "' && node encode_navigation.js '" + dir.file("dive.csv") +
                              "' --udp 127.0.0.1:" + std::to_string(udp.port()) + " 2>&1";
  FILE* sender = ::popen(command.c_str(), "r");
  ASSERT_NE(sender, nullptr);
  MavlinkNavigation live("udp://127.0.0.1:" + std::to_string(udp.port()));
  const auto start = std::chrono::steady_clock::now();
  std::vector<NavSample> fixes;
  std::size_t datagrams = 0;
  while (datagrams < dive.rows.size()) {
    const std::optional<std::vector<std::uint8_t>> datagram = udp.receive(10000);
    if (!datagram) break;
    ++datagrams;
    const double arrival_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const NavSample& f : live.feed(*datagram, arrival_s)) fixes.push_back(f);
  }
  for (const NavSample& f : live.finish()) fixes.push_back(f);
  EXPECT_EQ(::pclose(sender), 0);
  EXPECT_EQ(datagrams, dive.rows.size());
  EXPECT_EQ(live.streamCounts().frames, 1 + 10 + 4 * dive.rows.size());
  // Every fix is a row's, in order; a fix whose time would not be after the previous one (the
  // least delay found lower by more than a row's interval) is dropped, so most, not all, come.
  EXPECT_GE(fixes.size(), dive.rows.size() * 8 / 10);
  RecordProperty("fixes", static_cast<int>(fixes.size()));
  std::size_t row = 0;
  double last_delay_s = INFINITY;
  for (std::size_t i = 0; i < fixes.size(); ++i) {
    while (row < dive.rows.size() && f32(dive.rows[row].roll_rad) != fixes[i].roll_rad) ++row;
    ASSERT_LT(row, dive.rows.size()) << "fix " << i << " is no row's";
    EXPECT_EQ(fixes[i].position_ned_m.y(), f32(dive.rows[row].position_ned_m.y()));
    if (i > 0) {
      EXPECT_GT(fixes[i].time_s, fixes[i - 1].time_s);
    }
    // time − boot time is the least delay so far: it never grows
    const double delay_s = fixes[i].time_s - dive.rows[row].time_s;
    EXPECT_LE(delay_s, last_delay_s + 1e-9);
    last_delay_s = delay_s;
  }
}

/// One frame of each message sonarmap writes, as `encoder` sends it, and what node-mavlink must
/// read in it (field names of the XML definitions).
struct Written {
  std::vector<std::uint8_t> bytes;
  nlohmann::json fields;
};

std::vector<Written> framesOf(MavlinkEncoder& encoder) {
  std::vector<Written> out;
  const auto add = [&](const MavlinkPayload& p, nlohmann::json fields) {
    out.push_back({encodeMavlink(encoder, p), std::move(fields)});
  };
  add(toMavlinkPayload(MavlinkHeartbeat{19, 12, 3, 209, 4, 3}),
      {{"custom_mode", 19}, {"type", 12}, {"autopilot", 3}, {"base_mode", 209}, {"system_status", 4}, {"mavlink_version", 3}});
  add(toMavlinkPayload(MavlinkAttitude{123456, 0.1f, -0.2f, 3.1f, 0.01f, -0.02f, 0.5f}),
      {{"time_boot_ms", 123456}, {"roll", f32(0.1)}, {"pitch", f32(-0.2)}, {"yaw", f32(3.1)}, {"rollspeed", f32(0.01)},
       {"pitchspeed", f32(-0.02)}, {"yawspeed", f32(0.5)}});
  add(toMavlinkPayload(MavlinkLocalPositionNed{123457, 12.5f, -7.25f, 31.0f, 0.25f, 0.0f, -0.125f}),
      {{"time_boot_ms", 123457}, {"x", 12.5}, {"y", -7.25}, {"z", 31.0}, {"vx", 0.25}, {"vy", 0.0}, {"vz", -0.125}});
  add(toMavlinkPayload(MavlinkGlobalPositionInt{123458, 473977418, -1220837010, -31000, -31250, 25, -3, 12, 27000}),
      {{"time_boot_ms", 123458}, {"lat", 473977418}, {"lon", -1220837010}, {"alt", -31000}, {"relative_alt", -31250},
       {"vx", 25}, {"vy", -3}, {"vz", 12}, {"hdg", 27000}});
  for (const std::uint32_t id : {29u, 137u, 143u}) {
    // MAVLink 1 carries no extension: temperature_press_diff reads 0 there
    const std::int16_t diff_cdegc = encoder.version() == 2 ? 2150 : 0;
    add(toMavlinkPayload(MavlinkScaledPressure{id, 123459, 1327.5f, -0.75f, 1215, 2150}),
        {{"time_boot_ms", 123459}, {"press_abs", 1327.5}, {"press_diff", -0.75}, {"temperature", 1215},
         {"temperature_press_diff", diff_cdegc}});
  }
  if (encoder.version() == 2) {
    MavlinkVisionPositionDelta v;
    v.time_usec = 1723630500123456ULL;
    v.time_delta_usec = 125000;
    v.angle_delta_rad = {0.001f, -0.002f, 0.03f};
    v.position_delta_m = {0.0625f, -0.01f, 0.002f};
    v.confidence_percent = 87.5f;
    add(toMavlinkPayload(v), {{"time_usec", "1723630500123456"}, {"time_delta_usec", "125000"},
                              {"angle_delta", {f32(0.001), f32(-0.002), f32(0.03)}},
                              {"position_delta", {0.0625, f32(-0.01), f32(0.002)}}, {"confidence", 87.5}});
  }
  return out;
}

TEST(formatsMavlinkInterop, NodeMavlinkReadsOurFramesFieldByField) {
  SKIP_WITHOUT_NODE_MAVLINK();
  test::TempDir dir;
  MavlinkEncoder v2(1, 1), v1(42, 158, 1);
  std::vector<Written> written = framesOf(v2);
  for (Written& w : framesOf(v1)) written.push_back(std::move(w));
  std::string bytes;
  for (const Written& w : written) bytes.append(w.bytes.begin(), w.bytes.end());
  std::ofstream(dir.file("ours.bin"), std::ios::binary) << bytes;
  std::istringstream lines(runNode("parse_frames.js", "'" + dir.file("ours.bin") + "'", dir.path()));
  std::vector<nlohmann::json> read;
  for (std::string line; std::getline(lines, line);) read.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(read.size(), written.size() + 1);
  for (std::size_t i = 0; i < written.size(); ++i) {
    const std::vector<std::uint8_t>& f = written[i].bytes;
    const nlohmann::json& r = read[i];
    const bool v2_frame = f[0] == kMavlinkMagicV2;
    EXPECT_EQ(r["magic"], f[0]) << i;
    EXPECT_EQ(r["payloadLength"], f[1]) << i;
    EXPECT_EQ(r["seq"], f[v2_frame ? 4 : 2]) << i;
    EXPECT_EQ(r["sysid"], v2_frame ? 1 : 42) << i;
    EXPECT_EQ(r["compid"], v2_frame ? 1 : 158) << i;
    EXPECT_EQ(r["name"], findMavlinkMessage(r["msgid"].get<std::uint32_t>())->name) << i;
    for (const auto& [name, value] : written[i].fields.items()) {
      EXPECT_EQ(r["fields"][name], value) << r["name"] << "." << name;
    }
  }
  const nlohmann::json& summary = read.back();
  EXPECT_EQ(summary["valid"], written.size());
  EXPECT_EQ(summary["invalid"], 0);
  EXPECT_EQ(summary["unknown"], 0);
}

}  // namespace
}  // namespace sonarmap
