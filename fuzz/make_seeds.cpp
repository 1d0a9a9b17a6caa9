// Writes the seed corpus of every fuzz harness: small valid inputs made with the library's own
// writers and the simulator (no copy of ../shared/data), one folder per harness.
// Usage: sonarmap_fuzz_seeds OUT_DIR   (scripts/fuzz.sh build writes them to build-fuzz/seeds/).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "formats/mat_fixture.hpp"
#include "formats/v4log_fixture.hpp"
#include "formats/wire_fixture.hpp"
#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/io/octomap_full.hpp"
#include "sonarmap/io/scan_graph.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/nav/tum_trajectory.hpp"
#include "sonarmap/slam/point_scans.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/scene_file.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/mavlink_messages.hpp"
#include "sonarmap/formats/mcap_writer.hpp"
#include "sonarmap/formats/ros_bag_writer.hpp"
#include "sonarmap/formats/seanet_protocol.hpp"

namespace fs = std::filesystem;
using namespace sonarmap;

namespace {

fs::path g_out;

void seed(const std::string& harness, const std::string& name, const std::function<void(std::ostream&)>& write) {
  fs::create_directories(g_out / harness);
  std::ofstream out(g_out / harness / name, std::ios::binary);
  write(out);
}

/// A short simulated run of the tank: 2 turns of a coarse head (few bins), with navigation.
MsisSimulation smallRun() {
  MsisSimulationOptions options;
  options.turns = 1;
  options.head.step_rad = 0.3;
  options.head.bins = 24;
  return simulateMsis(builtinScene("tank"), options);
}

OcTree16 smallTree() {
  OcTree16 tree(0.1);
  for (int i = 0; i < 12; ++i) tree.integrate(tree.coder().keyOfChecked(Eigen::Vector3d(0.1 * i, 0.05 * i, 0.3)), i % 3 != 0);
  tree.updateInnerOccupancy();
  return tree;
}

void sonarSeeds() {
  const MsisSimulation run = smallRun();
  seed("beam_csv", "tank.csv", [&](std::ostream& out) { writeBeamCsv(out, run.log); });
  seed("map_beam_csv", "tank.csv", [&](std::ostream& out) { writeBeamCsv(out, run.log); });
  SonarLog spanned = run.log;  // with the optional intensity_span_db column (a SeaNet log's AD span)
  for (std::size_t i = 0; i < spanned.beams.size(); i += 2) spanned.beams[i].intensity_span_db = 46.7;
  seed("beam_csv", "tank_span.csv", [&](std::ostream& out) { writeBeamCsv(out, spanned); });
  seed("map_beam_csv", "tank_span.csv", [&](std::ostream& out) { writeBeamCsv(out, spanned); });
  seed("nav_csv", "tank_nav.csv", [&](std::ostream& out) { writeNavCsv(out, run.nav); });
  // Point scans: a quarter of each beam's range, in the body frame, two scans.
  std::vector<BodyPoint> points;
  for (std::size_t i = 0; i < run.log.beams.size(); ++i) {
    const Beam& beam = run.log.beams[i];
    const double range_m = 0.25 * beam.bin_length_m * static_cast<double>(beam.intensities.size());
    points.push_back({2 * i / run.log.beams.size(), beam.time_s,
                      Eigen::Vector2d(range_m * std::cos(beam.bearing_rad), range_m * std::sin(beam.bearing_rad))});
  }
  seed("point_scans", "tank_scans.csv", [&](std::ostream& out) { writePointScans(out, points); });
  // readTrajectory (navigation CSV or TUM, told apart by content): the simulator's track in both
  // formats, a hand-written TUM file with comments, blank lines, tabs, a non-unit quaternion and a
  // UTF-8 byte-order mark, and CRLF line ends in both formats.
  NavTrack turning;  // the tank's track stands still: one that moves, rolls, pitches (to ±90°) and turns past ±π
  for (int k = 0; k < 8; ++k) {
    NavSample fix;
    fix.time_s = 100.0 + 0.25 * k;
    fix.position_ned_m = Eigen::Vector3d(0.5 * k, -1.0 + 0.3 * k * k, 2.0 - 0.1 * k);
    fix.roll_rad = 0.2 * (k % 3) - 0.2;
    fix.pitch_rad = k == 5 ? 1.5707963267948966 : -0.1 * k;
    fix.yaw_rad = 2.6 + 0.2 * k;
    turning.push_back(fix);
  }
  seed("trajectory", "tank_nav.csv", [&](std::ostream& out) { writeNavCsv(out, run.nav); });
  seed("trajectory", "tank.tum", [&](std::ostream& out) { writeTumTrajectory(out, run.nav); });
  seed("trajectory", "turning_nav.csv", [&](std::ostream& out) { writeNavCsv(out, turning); });
  seed("trajectory", "turning.tum", [&](std::ostream& out) { writeTumTrajectory(out, turning); });
  seed("trajectory", "comments.tum", [](std::ostream& out) {
    out << "\xEF\xBB\xBF# timestamp tx ty tz qx qy qz qw\n\n1.5 1 2 3 0 0 0.7071067811865476 0.7071067811865476\n"
           "  # indented comment\n2.5\t4 5 6 0 0 0 2\n3e1 -1e-3 0.5 7 0.5 -0.5 0.5 -0.5   \n";
  });
  seed("trajectory", "crlf.tum", [](std::ostream& out) {
    out << "# crlf\r\n0 0 0 0 0 0 0 1\r\n\r\n0.25 1 0 -2 0.1 0.2 0.3 0.9\r\n";
  });
  seed("trajectory", "crlf_nav.csv", [](std::ostream& out) {
    out << "time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad\r\n0,1,2,3,0.1,-0.2,3.1\r\n1.5, 2 ,3,4,0,0,-3.1\r\n";
  });
  // The stream harness: byte 0 seeds the chunk sizes, then rows as a vehicle sends them.
  seed("nav_stream", "tank_nav.bin", [&](std::ostream& out) {
    out << '\x05';
    writeNavCsv(out, run.nav);
    out << "1e9,1,2,x,0,0,0\n0,0,0,0,0,0,0\r\n";  // a bad row, a time going back
  });
  seed("scene", "tank.scene", [&](std::ostream& out) { writeScene(out, run.scene, kDefaultMapFrame); });
  seed("scene", "harbour.scene", [&](std::ostream& out) { writeScene(out, builtinScene("harbour"), MapFrame::kNed); });
  seed("v4log", "three.V4LOG", [](std::ostream& out) {
    test::V4Record other;
    other.type = 4;
    test::V4Record four_bit;
    four_bit.head_control = 0x230C;
    four_bit.bearing = 3264;
    out << test::v4log({test::V4Record{}, other, four_bit});
  });
  std::vector<test::MatBeam> beams(3);
  for (std::size_t i = 0; i < beams.size(); ++i) beams[i].angle = 0.1 * static_cast<double>(i), beams[i].time = 0.04 * static_cast<double>(i);
  beams[2].scalar_class = MAT_C_DOUBLE;
  const fs::path mat = g_out / "mat" / "three.mat";
  fs::create_directories(mat.parent_path());
  test::writeCrasMat(mat.string(), beams);
}

/// Raw wire captures: SeaNet packets (8- and 4-bit bins, an mtAlive, noise), a Ping360 stream
/// (device_data, auto_device_data, an ack, noise) and the same messages in a Ping Viewer log.
void wireSeeds() {
  test::SeaNetHeadPacket four_bit;
  four_bit.head_control = 0x230C;
  four_bit.bearing = 3264;
  seed("seanet", "three.seanet", [&](std::ostream& out) {
    out << "\r\n" << test::seanetHeadData({}) << test::seanetOther(4, 8) << test::seanetHeadData(four_bit);
  });
  // A SeaNet conversation both ways: the host's commands, the head's replies, noise between.
  seed("seanet_protocol", "conversation.seanet", [&](std::ostream& out) {
    namespace sn = seanet;
    std::vector<std::vector<std::uint8_t>> packets = {
        sn::encodeSimpleCommand(sn::MessageType::kReBoot), sn::encodeAlive({}),
        sn::encodeSimpleCommand(sn::MessageType::kSendVersion), sn::encodeVersionData({}),
        sn::encodeSimpleCommand(sn::MessageType::kSendBBUser), sn::encodeBBUserData({})};
    sn::HeadCommand command;
    command.hd_ctrl = 0x2307;
    command.ad_interval = 104;
    command.nbins = 8;
    command.step = 32;
    packets.push_back(sn::encodeHeadCommand(command));
    packets.push_back(sn::encodeSendData(1000));
    sn::HeadDataFields fields;
    fields.ad_interval = 104;
    packets.push_back(sn::encodeHeadData(fields, std::vector<std::uint8_t>{1, 2, 3, 250}));
    for (const auto& packet : packets) out << "x" << std::string(packet.begin(), packet.end());
  });
  test::Ping360Data sector;
  sector.auto_device_data = true;
  sector.angle = 17;
  const std::string stream = test::ping360Message({}) + test::pingMessage(1, std::string("\xB0\x04", 2)) +
                             test::ping360Message(sector);
  seed("ping360", "stream.bin", [&](std::ostream& out) { out << "xx" << stream; });
  seed("ping360", "viewer.bin", [&](std::ostream& out) {
    out << test::pingViewerLog({{"00:00:00.100", stream.substr(0, 20)}, {"00:00:00.150", stream.substr(20)}});
  });
  seed("ping360", "viewer_utf16.bin",
       [&](std::ostream& out) { out << test::pingViewerLog({{"00:00:00.100", stream}}, true); });
  // What real Ping Viewer logs do (../shared/data/README.md): time stamps in the locale's digits
  // (Persian, UTF-8 here), records that are raw serial chunks (a message over several records,
  // several messages in one), power-on pings at 2 m then a range change and a gain change.
  std::string settings;
  for (std::uint16_t angle = 0; angle < 6; ++angle) {
    test::Ping360Data ping;
    ping.angle = angle;
    ping.sample_period = angle < 2 ? 88 : 440;
    std::string message = test::ping360Message(ping);
    if (angle >= 4) message = test::pingMessage(2300, test::ping360Payload(ping).replace(1, 1, 1, '\x01'));
    settings += message;
  }
  seed("ping360", "viewer_real_chunks.bin", [&](std::ostream& out) {
    out << test::pingViewerLog({{"\u06F0\u06F0:\u06F0\u06F0:\u06F0\u06F0.\u06F1\u06F0\u06F0", settings.substr(0, 7)},
                                {"\u06F0\u06F0:\u06F0\u06F0:\u06F0\u06F0.\u06F1\u06F5\u06F0", settings.substr(7, 11)},
                                {"\u06F0\u06F0:\u06F0\u06F0:\u06F0\u06F0.\u06F2\u06F0\u06F0", settings.substr(18)}});
  });
  // The stream decoder's harness: byte 0 even for SeaNet, odd for Ping360, then the stream.
  seed("wire_stream", "seanet.bin", [&](std::ostream& out) {
    out << '\x00' << "\r\n" << test::seanetHeadData({}) << test::seanetOther(4, 8) << test::seanetHeadData(four_bit);
  });
  seed("wire_stream", "ping360.bin", [&](std::ostream& out) { out << '\x01' << "xx" << stream; });
}

/// A bag of a few ScanLine messages as the micron_driver_ros driver records them.
void rosBagSeeds() {
  SonarLog log;
  for (int i = 0; i < 4; ++i) {
    Beam beam;
    beam.time_s = 1.4e9 + 0.043 * i;
    beam.bearing_rad = 0.0314 * i;
    beam.bin_length_m = 0.05;
    beam.intensities = {0, 3, 200, 90, 10, 0};
    log.beams.push_back(beam);
  }
  const fs::path path = g_out / "ros_bag" / "scan_lines.bag";
  fs::create_directories(path.parent_path());
  writeRosBag(path.string(), log);
  NavTrack nav(3);
  for (std::size_t i = 0; i < nav.size(); ++i) {
    nav[i].time_s = 1.4e9 + 0.1 * static_cast<double>(i);
    nav[i].position_ned_m = Eigen::Vector3d(0.1 * static_cast<double>(i), 0.0, 1.0);
    nav[i].yaw_rad = 0.2;
  }
  writeRosBag((g_out / "ros_bag" / "with_odometry.bag").string(), log, nav);
  writeRosBag((g_out / "ros_bag" / "with_odometry_ned_lz4.bag").string(), log, nav,
              {.nav_frame = "odom_ned", .compression = BagCompression::kLz4});
  writeRosBag((g_out / "ros_bag" / "with_imu_dvl_pressure.bag").string(), log, nav, {.odometry = false, .raw_sensors = true});
  Eigen::Isometry3d mounted = defaultSonarToBody();
  mounted.pretranslate(Eigen::Vector3d(0.2, 0.0, 0.1));
  writeRosBag((g_out / "ros_bag" / "with_tf_static.bag").string(), log, nav,
              {.raw_sensors = true, .sonar_to_body = mounted,
               .dvl_rotation_flu = Eigen::Quaterniond(Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()))});
  fs::create_directories(g_out / "mcap");
  writeMcap((g_out / "mcap" / "plain.mcap").string(), log, nav, {.compression = McapCompression::kNone});
  writeMcap((g_out / "mcap" / "zstd.mcap").string(), log, nav, {.compression = McapCompression::kZstd});
  writeMcap((g_out / "mcap" / "lz4.mcap").string(), log, {}, {.compression = McapCompression::kLz4});
}

void cloudSeeds() {
  Scan scan;
  for (int i = 0; i < 8; ++i) scan.points_m.emplace_back(0.5 * i, 1.0, -0.25 * i);
  scan.sensor_to_world.translate(Eigen::Vector3d(0.1, 0.2, 0.3));
  seed("scan_graph", "two.graph", [&](std::ostream& out) { writeScanGraph(out, {scan, scan}); });
  seed("point_text", "cloud.xyz", [](std::ostream& out) { out << "1 2 3\n0.5 -0.25 4e1\n# comment\nnan 0 0\n"; });
  const OcTree16 tree = smallTree();
  seed("octomap_bt", "small.bt", [&](std::ostream& out) { writeBinary(tree, out); });
  seed("octomap_ot", "small.ot", [&](std::ostream& out) { writeFull(tree, out); });
}

/// An ArduSub autopilot's stream, as the MAVLink stream harness reads it: byte 0 seeds the chunk
/// sizes, then frames of every message the decoder reads, noise, a corrupted frame, a reboot.
void mavlinkSeeds() {
  const auto stream = [](int version, bool with_ekf) {
    MavlinkEncoder vehicle(1, 1, version), gcs(255, 190, version), dvl(255, 0, 2);
    std::vector<std::uint8_t> out{0x05};
    const auto put = [&out](const std::vector<std::uint8_t>& frame) { out.insert(out.end(), frame.begin(), frame.end()); };
    put(encodeMavlink(gcs, toMavlinkPayload(MavlinkHeartbeat{0, 6, 8, 0, 4, 3})));
    for (int boot = 0; boot < 2; ++boot) {
      for (int i = 0; i < 30; ++i) {
        const auto ms = static_cast<std::uint32_t>((boot == 0 ? 60000 : 3000) + 100 * i);
        if (i % 10 == 0) put(encodeMavlink(vehicle, toMavlinkPayload(MavlinkHeartbeat{19, 12, 3, 209, 4, 3})));
        put(encodeMavlink(vehicle, toMavlinkPayload(MavlinkAttitude{ms, 0.01f * i, -0.02f, 0.1f * i - 1.0f})));
        if (with_ekf && i % 2 == 0) put(encodeMavlink(vehicle, toMavlinkPayload(MavlinkLocalPositionNed{ms, 0.2f * i, 1.0f, 3.0f})));
        MavlinkGlobalPositionInt global;
        global.time_boot_ms = ms;
        global.relative_alt_mm = -3000 - i;
        put(encodeMavlink(vehicle, toMavlinkPayload(global)));
        put(encodeMavlink(vehicle, toMavlinkPayload(MavlinkScaledPressure{137, ms, 1315.0f + i, 0.0f, 1500, 0})));
        put(encodeMavlink(vehicle, toMavlinkPayload(MavlinkScaledPressure{143, ms, 0.0f, 0.0f, 1210, 0})));
        put(encodeMavlink(vehicle, toMavlinkPayload(MavlinkScaledPressure{29, ms, 1003.0f, 0.0f, 3000, 0})));
        MavlinkVisionPositionDelta delta;
        delta.time_delta_usec = 100000;
        delta.position_delta_m = {0.05f, 0.0f, 0.0f};
        put(encodeMavlink(dvl, toMavlinkPayload(delta)));
        if (i == 15) {
          const std::vector<std::uint8_t> noise{'n', 0xFD, 0x20, 0x00, 0x00, 0xFE, 0x03, '\n'};
          out.insert(out.end(), noise.begin(), noise.end());
          std::vector<std::uint8_t> corrupt = encodeMavlink(vehicle, toMavlinkPayload(MavlinkAttitude{ms + 50, 9.0f, 9.0f, 9.0f}));
          corrupt.back() ^= 0x5A;
          put(corrupt);
        }
      }
    }
    return out;
  };
  for (const auto& named : {std::pair{"ardusub_v2_ekf.bin", stream(2, true)}, std::pair{"ardusub_v1_depth.bin", stream(1, false)}}) {
    const std::vector<std::uint8_t>& bytes = named.second;  // a structured binding cannot be captured before C++20 in clang 14
    seed("mavlink_stream", named.first, [&bytes](std::ostream& out) {
      out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    });
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: sonarmap_fuzz_seeds OUT_DIR\n";
    return 2;
  }
  g_out = argv[1];
  sonarSeeds();
  wireSeeds();
  rosBagSeeds();
  cloudSeeds();
  mavlinkSeeds();
  return 0;
}
