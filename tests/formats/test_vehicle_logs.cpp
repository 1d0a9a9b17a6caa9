/// Tests of the BlueROV2 (ArduSub) navigation readers and the clocks that join a vehicle's log to a
/// sonar log: MAVLink telemetry logs and dataflash logs built byte by byte from their
/// specifications (vehicle_log_fixture.hpp), their fixes, depths and UTC clocks; bad checksums,
/// other senders, logs cut mid-frame, bytes between records; time zones, Ping Viewer file names,
/// alignNavigationClock.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <span>
#include <string>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_clock.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/navigation_reader.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"
#include "vehicle_log_fixture.hpp"
#include "wire_fixture.hpp"

namespace sonarmap {
namespace {

using test::MavlinkFrameOptions;
using test::tlogRecord;

constexpr double kPi = std::numbers::pi;
/// 2024-08-14 10:15:02.123 UTC in seconds since 1970 (date -u -d '2024-08-14 10:15:02' +%s = 1723630502).
constexpr double kAugust14_s = 1723630502.123;

std::span<const std::uint8_t> spanOf(const std::string& bytes) {
  return {reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()};
}
NavigationSource tlog(const std::string& bytes, const VehicleLogOptions& options = {}) {
  return parseMavlinkTlogNavigation(spanOf(bytes), "run.tlog", options);
}
NavigationSource dataflash(const std::string& bytes, const VehicleLogOptions& options = {}) {
  return parseDataflashNavigation(spanOf(bytes), "00000042.BIN", options);
}
std::string fileErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const FileError& e) {
    return e.what();
  }
  return "(no FileError)";
}
bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// A vehicle's telemetry: every 100 ms of boot time from 1,000 ms, an ATTITUDE and a
/// LOCAL_POSITION_NED on a turning track, received 5–45 ms later (a radio's jitter), the first
/// frame received with no delay at kStart_us.
constexpr std::uint64_t kStart_us = 1723630500000000ULL;
std::string telemetry(int fixes, const MavlinkFrameOptions& o = {}) {
  std::string log;
  for (int i = 0; i < fixes; ++i) {
    const std::uint32_t boot_ms = 1000 + 100 * static_cast<std::uint32_t>(i);
    const std::uint64_t delay_us = i == 0 ? 0 : 5000 + 40000 * static_cast<std::uint64_t>((i * 7) % 5) / 4;
    const std::uint64_t received = kStart_us + (boot_ms - 1000) * 1000ULL + delay_us;
    log += tlogRecord(received, test::attitudeFrame(boot_ms, 0.01f * i, -0.02f, static_cast<float>(0.1 * i - 1.0), o));
    log += tlogRecord(received + 1, test::localPositionNedFrame(boot_ms, 0.5f * i, -0.25f * i, 2.0f + 0.1f * i, o));
  }
  return log;
}

TEST(formatsMavlinkTlog, TheChecksumIsCrc16Mcrf4xx) {
  EXPECT_EQ(test::mcrf4xx("123456789"), 0x6F91);  // the CRC catalogue's check value
}

TEST(formatsMavlinkTlog, ReadsAttitudeAndLocalPositionOnTheLeastDelayedClock) {
  for (const bool v2 : {true, false}) {
    const NavigationSource nav = tlog(test::tlogRecord(kStart_us - 5000000, test::heartbeatFrame({v2, 255, 190})) +
                                      telemetry(20, {.v2 = v2}));
    ASSERT_EQ(nav.track.size(), 20u) << v2;
    ASSERT_TRUE(nav.clock_utc_s);
    EXPECT_EQ(*nav.clock_utc_s, 0.0);
    for (int i = 0; i < 20; ++i) {
      const NavSample& fix = nav.track[static_cast<std::size_t>(i)];
      // boot time on UTC through the frame received without delay: jitter does not move the fixes
      EXPECT_NEAR(fix.time_s, kStart_us / 1e6 + 0.1 * i, 1e-6) << i;
      EXPECT_NEAR(fix.roll_rad, 0.01 * i, 1e-6);
      EXPECT_NEAR(fix.pitch_rad, -0.02, 1e-6);
      EXPECT_NEAR(fix.yaw_rad, 0.1 * i - 1.0, 1e-6);
      EXPECT_NEAR(fix.position_ned_m.x(), 0.5 * i, 1e-5);
      EXPECT_NEAR(fix.position_ned_m.y(), -0.25 * i, 1e-5);
      EXPECT_NEAR(fix.position_ned_m.z(), 2.0 + 0.1 * i, 1e-5);
    }
    EXPECT_TRUE(contains(nav.description, "LOCAL_POSITION_NED")) << nav.description;
    EXPECT_TRUE(nav.notes.empty());
  }
}

TEST(formatsMavlinkTlog, ReadsSignedFramesAndSkipsBadChecksumsAndOtherSenders) {
  std::string log = telemetry(3, {.sign = true});
  // a companion computer's ATTITUDE (another system) and a corrupted frame of the autopilot's
  log += tlogRecord(kStart_us + 300000, test::attitudeFrame(1300, 3.0f, 3.0f, 3.0f, {.system = 2}));
  log += tlogRecord(kStart_us + 300000, test::attitudeFrame(1300, 3.0f, 3.0f, 3.0f, {.corrupt = true}));
  log += telemetry(5).substr(telemetry(3).size());  // fixes 3 and 4
  const NavigationSource nav = tlog(log);
  ASSERT_EQ(nav.track.size(), 5u);
  EXPECT_EQ(nav.skipped, 1u);
  for (const NavSample& fix : nav.track) EXPECT_LT(fix.roll_rad, 1.0);
}

TEST(formatsMavlinkTlog, TakesDepthFromGlobalPositionElseFromTheExternalPressureSensor) {
  std::string global, pressure;
  for (int i = 0; i < 4; ++i) {
    const std::uint32_t boot_ms = 100 * static_cast<std::uint32_t>(i);
    const std::uint64_t received = kStart_us + boot_ms * 1000ULL;
    const std::string attitude = tlogRecord(received, test::attitudeFrame(boot_ms, 0.0f, 0.0f, 0.5f));
    global += attitude + tlogRecord(received, test::globalPositionIntFrame(boot_ms, -1500 - 100 * i));
    // 1 m of sea water (1025 kg/m^3) is 100.52 hPa over 1013.25 hPa
    pressure += attitude + tlogRecord(received, test::scaledPressure2Frame(boot_ms, static_cast<float>(1013.25 + 100.5201 * (1 + i))));
  }
  const NavigationSource a = tlog(global);
  ASSERT_EQ(a.track.size(), 4u);
  EXPECT_NEAR(a.track[2].position_ned_m.z(), 1.7, 1e-9);
  EXPECT_EQ(a.track[2].position_ned_m.x(), 0.0);
  EXPECT_TRUE(contains(a.description, "relative_alt")) << a.description;
  EXPECT_TRUE(contains(a.description, "no horizontal position")) << a.description;
  const NavigationSource b = tlog(pressure);
  ASSERT_EQ(b.track.size(), 4u);
  EXPECT_NEAR(b.track[0].position_ned_m.z(), 1.0, 1e-4);
  EXPECT_NEAR(b.track[3].position_ned_m.z(), 4.0, 1e-4);
  EXPECT_NEAR(tlog(pressure, {.water_density_kg_m3 = 997.0}).track[3].position_ned_m.z(), 4.0 * 1025.0 / 997.0, 1e-3);
}

TEST(formatsMavlinkTlog, ALogCutMidFrameKeepsTheFixesBeforeItAndSaysWhere) {
  const std::string whole = telemetry(6);
  const NavigationSource cut = tlog(whole.substr(0, whole.size() - 10));
  ASSERT_EQ(cut.track.size(), 5u);  // the last LOCAL_POSITION_NED is cut: its ATTITUDE is past the span
  ASSERT_EQ(cut.notes.size(), 1u);
  EXPECT_TRUE(contains(cut.notes[0], "'run.tlog': record 12 at byte")) << cut.notes[0];
  EXPECT_TRUE(contains(cut.notes[0], "a frame cut short")) << cut.notes[0];
  EXPECT_TRUE(contains(cut.notes[0], "the 11 records before it are kept")) << cut.notes[0];
  const NavigationSource garbage = tlog(telemetry(3) + std::string(20, 'x'));
  ASSERT_EQ(garbage.notes.size(), 1u);
  EXPECT_TRUE(contains(garbage.notes[0], "no MAVLink frame after the time stamp (0x78")) << garbage.notes[0];
  EXPECT_TRUE(contains(fileErrorOf([&] { tlog(whole.substr(0, 30)); }), "'run.tlog': no ATTITUDE message in 1 records"));
  EXPECT_TRUE(contains(fileErrorOf([&] { tlog(tlogRecord(kStart_us, test::heartbeatFrame())); }), "no ATTITUDE message"));
  EXPECT_THROW(tlog(whole, {.surface_pressure_pa = -1.0}), ValueError);
}

/// A dataflash log as ArduSub 4.1 writes its navigation: ATT in centidegrees (the older "ccccCCCC"
/// layout), EKF3's XKF1 for cores 0 and 1, BARO for the internal (air) and external (water)
/// sensors, GPS with a 3D fix at boot second 2.
std::string ardusubLog(bool with_ekf, bool with_gps) {
  std::string log = test::dataflashFmt(129, "ATT", "QccccCCCC", "TimeUS,DesRoll,Roll,DesPitch,Pitch,DesYaw,Yaw,ErrRP,ErrYaw");
  log += test::dataflashFmt(130, "XKF1", "QBccCfffffffccce", "TimeUS,C,Roll,Pitch,Yaw,VN,VE,VD,dPD,PN,PE,PD,GX,GY,GZ,OH");
  log += test::dataflashFmt(131, "BARO", "QBfffcfIffX", "TimeUS,I,Alt,Press,Temp,CRt,SMS,Offset,GndTemp,Health,H");  // X: refused
  log += test::dataflashFmt(132, "BARO", "QBfffcfIff", "TimeUS,I,Alt,Press,Temp,CRt,SMS,Offset,GndTemp,Health");
  log += test::dataflashFmt(133, "GPS", "QBBIHBcLLeffffB", "TimeUS,I,Status,GMS,GWk,NSats,HDop,Lat,Lng,Alt,Spd,GCrs,VZ,Yaw,U");
  for (int i = 0; i < 10; ++i) {
    const std::uint64_t time_us = 1000000ULL + 200000ULL * static_cast<std::uint64_t>(i);
    std::string att;
    test::putLittle(att, time_us);
    for (std::int16_t v : {std::int16_t(0), std::int16_t(150 * i), std::int16_t(0), std::int16_t(-300)}) test::putLittle(att, v);
    for (std::uint16_t v : {std::uint16_t(0), std::uint16_t(35900 + 20 * i), std::uint16_t(0), std::uint16_t(0)}) test::putLittle(att, v);
    log += test::dataflashRecord(129, att);
    for (std::uint8_t core : {std::uint8_t(0), std::uint8_t(1)}) {
      if (!with_ekf) break;
      std::string ekf;
      test::putLittle(ekf, time_us);
      test::putLittle(ekf, core);
      for (int k = 0; k < 2; ++k) test::putLittle(ekf, std::int16_t{0});
      test::putLittle(ekf, std::uint16_t{0});
      for (float v : {0.0f, 0.0f, 0.0f, 0.0f, core == 0 ? 1.0f * i : 99.0f, -2.0f, 3.0f + 0.5f * i}) test::putLittle(ekf, v);
      for (int k = 0; k < 3; ++k) test::putLittle(ekf, std::int16_t{0});
      test::putLittle(ekf, std::int32_t{0});
      log += test::dataflashRecord(130, ekf);
    }
    for (std::uint8_t instance : {std::uint8_t(0), std::uint8_t(1)}) {
      std::string baro;
      test::putLittle(baro, time_us);
      test::putLittle(baro, instance);
      const float pressure = instance == 0 ? 98000.0f : static_cast<float>(101325.0 + 1025.0 * 9.80665 * (2.0 + 0.1 * i));
      for (float v : {0.0f, pressure, 0.0f}) test::putLittle(baro, v);
      test::putLittle(baro, std::int16_t{0});
      test::putLittle(baro, 0.0f);
      test::putLittle(baro, std::uint32_t{0});
      test::putLittle(baro, 0.0f);
      test::putLittle(baro, 0.0f);
      log += test::dataflashRecord(132, baro);
    }
    // boot 2.0 s = GPS week 2327, 123456.789 s of the week, at 43.2961 N, 5.37 E (Lat, Lng in 1e-7
    // degrees); at 2.4 s a receiver's garbage, latitude 95 degrees, skipped with a note
    if (with_gps && (i == 5 || i == 7)) {
      std::string gps;
      test::putLittle(gps, time_us);
      test::putLittle(gps, std::uint8_t{0});
      test::putLittle(gps, std::uint8_t{3});
      test::putLittle(gps, std::uint32_t{i == 5 ? 123456789u : 123457189u});
      test::putLittle(gps, std::uint16_t{2327});
      gps += std::string(1 + 2, '\0');  // NSats, HDop
      test::putLittle(gps, std::int32_t{i == 5 ? 432961000 : 950000000});
      test::putLittle(gps, std::int32_t{53700000});
      gps += std::string(4 + 16 + 1, '\0');
      log += test::dataflashRecord(133, gps);
    }
  }
  return log;
}

TEST(formatsDataflash, ReadsAttAndTheEkfsCoreZeroOnBootTimeAndGpsUtc) {
  const NavigationSource nav = dataflash(ardusubLog(true, true));
  ASSERT_EQ(nav.track.size(), 10u);
  for (int i = 0; i < 10; ++i) {
    const NavSample& fix = nav.track[static_cast<std::size_t>(i)];
    EXPECT_NEAR(fix.time_s, 1.0 + 0.2 * i, 1e-9);
    EXPECT_NEAR(fix.roll_rad, 1.5 * i * kPi / 180.0, 1e-9);
    EXPECT_NEAR(fix.pitch_rad, -3.0 * kPi / 180.0, 1e-9);
    EXPECT_NEAR(fix.yaw_rad, (359.0 + 0.2 * i) * kPi / 180.0, 1e-9);
    EXPECT_NEAR(fix.position_ned_m.x(), 1.0 * i, 1e-6);  // core 0's, not core 1's 99
    EXPECT_NEAR(fix.position_ned_m.y(), -2.0, 1e-6);
    EXPECT_NEAR(fix.position_ned_m.z(), 3.0 + 0.5 * i, 1e-6);
  }
  // GPS week 2327 + 123456.789 s − 18 leap seconds, at boot 2.0 s: 1980-01-06 + 2327 weeks = 2024-08-11
  ASSERT_TRUE(nav.clock_utc_s);
  EXPECT_NEAR(*nav.clock_utc_s, 315964800.0 + 2327 * 604800.0 + 123456.789 - 18.0 - 2.0, 1e-6);
  EXPECT_EQ(utcText(*nav.clock_utc_s + 2.0), "2024-08-12 10:17:18.789 UTC");
  ASSERT_EQ(nav.notes.size(), 2u);
  EXPECT_TRUE(contains(nav.notes[0], "1 GPS records skipped, the first: GPS record at boot time 2.400000 s: latitude 95 "
                                     "degrees is not within [-90, 90]")) << nav.notes[0];
  EXPECT_TRUE(contains(nav.notes[1], "1 FMT records refused")) << nav.notes[1];
  EXPECT_TRUE(contains(nav.description, "XKF1 (core 0)")) << nav.description;
  // The GPS fix: Lat, Lng in 1e-7 degrees, on the boot clock.
  ASSERT_EQ(nav.geodetic_fixes.size(), 1u);
  EXPECT_NEAR(nav.geodetic_fixes[0].time_s, 2.0, 1e-9);
  EXPECT_NEAR(nav.geodetic_fixes[0].point.latitude_deg, 43.2961, 1e-9);
  EXPECT_NEAR(nav.geodetic_fixes[0].point.longitude_deg, 5.37, 1e-9);
  EXPECT_TRUE(contains(nav.geodetic_description, "GPS records (Lat, Lng)")) << nav.geodetic_description;
  // The EKF's zero on the Earth: the GPS fix less the EKF's position then (5 N, -2 E, 5.5 D at 2.0 s).
  const std::optional<GeodeticPoint> zero = geodeticOriginOf(nav.geodetic_fixes, nav.track);
  ASSERT_TRUE(zero);
  const Eigen::Vector3d fix_ned = geodeticToNed(*zero, nav.geodetic_fixes[0].point);
  EXPECT_NEAR(fix_ned.x(), 5.0, 1e-4);  // the two tangent planes differ by |p|² / R: µm
  EXPECT_NEAR(fix_ned.y(), -2.0, 1e-4);
  EXPECT_NEAR(fix_ned.z(), 5.5, 1e-4);
}

TEST(formatsDataflash, WithoutAnEkfTakesDepthFromTheBarometerInTheWater) {
  const NavigationSource nav = dataflash(ardusubLog(false, false));
  ASSERT_EQ(nav.track.size(), 10u);
  EXPECT_FALSE(nav.clock_utc_s);
  EXPECT_NEAR(nav.track[4].position_ned_m.z(), 2.4, 1e-3);
  EXPECT_EQ(nav.track[4].position_ned_m.x(), 0.0);
  EXPECT_TRUE(contains(nav.description, "BARO instance 1")) << nav.description;
}

TEST(formatsDataflash, SkipsBytesBetweenRecordsAndKeepsWhatPrecedesACut) {
  std::string log = ardusubLog(true, false);
  const std::size_t half = log.size() / 2;
  const std::size_t record = log.find("\xA3\x95\x81", half);  // the next ATT record
  log.insert(record, std::string(7, '\0'));                     // a damaged block's zeros
  const NavigationSource nav = dataflash(log.substr(0, log.size() - 5));
  EXPECT_GE(nav.track.size(), 8u);
  ASSERT_EQ(nav.notes.size(), 3u);
  EXPECT_TRUE(contains(nav.notes[0], "record cut short")) << nav.notes[0];
  EXPECT_TRUE(contains(nav.notes[1], "7 bytes between records skipped")) << nav.notes[1];
  EXPECT_TRUE(contains(fileErrorOf([&] { dataflash("hello"); }), "not an ArduPilot dataflash log"));
  EXPECT_TRUE(contains(fileErrorOf([&] { dataflash(log.substr(0, 89 * 5)); }), "no ATT record in 5 records"));
}

TEST(formatsVehicleLogs, ReadNavigationTellsThemByNameAndContent) {
  test::TempDir dir;
  std::ofstream(dir.file("run.tlog"), std::ios::binary) << telemetry(4);
  std::ofstream(dir.file("00000007.BIN"), std::ios::binary) << ardusubLog(true, true);
  std::ofstream(dir.file("log.dat"), std::ios::binary) << ardusubLog(true, true);
  EXPECT_EQ(readNavigation(dir.file("run.tlog")).track.size(), 4u);
  EXPECT_EQ(readNavigation(dir.file("00000007.BIN")).track.size(), 10u);
  EXPECT_TRUE(contains(readNavigation(dir.file("log.dat")).description, "ArduPilot dataflash log.dat"));
}

TEST(formatsLogClock, TimeZonesDatesAndPingViewerNames) {
  EXPECT_EQ(parseUtcOffset("UTC"), 0.0);
  EXPECT_EQ(parseUtcOffset("Z"), 0.0);
  EXPECT_EQ(parseUtcOffset("+03:30"), 12600.0);
  EXPECT_EQ(parseUtcOffset("UTC-05:00"), -18000.0);
  EXPECT_EQ(parseUtcOffset("+0545"), 20700.0);
  EXPECT_EQ(parseUtcOffset("-02"), -7200.0);
  for (const char* bad : {"Asia/Tehran", "+3:30", "+15:00", "+03:60", "", "03:30", "+03:30x"}) {
    EXPECT_THROW(parseUtcOffset(bad), ValueError) << bad;
  }
  EXPECT_DOUBLE_EQ(*civilSeconds(2024, 8, 14, 10, 15, 2, 123), kAugust14_s);
  EXPECT_DOUBLE_EQ(*civilSeconds(1970, 1, 1, 0, 0, 0, 0), 0.0);
  EXPECT_FALSE(civilSeconds(2023, 2, 29, 0, 0, 0, 0));
  EXPECT_EQ(utcText(kAugust14_s), "2024-08-14 10:15:02.123 UTC");
  EXPECT_DOUBLE_EQ(*pingViewerNameTime_s("logs/20240814-101502123.bin"), kAugust14_s);
  // Extended Arabic-Indic digits, as a Persian Windows writes them
  EXPECT_DOUBLE_EQ(*pingViewerNameTime_s("\u06F2\u06F0\u06F2\u06F4\u06F0\u06F8\u06F1\u06F4-\u06F1\u06F0\u06F1\u06F5\u06F0\u06F2\u06F1\u06F2\u06F3.bin"),
                   kAugust14_s);
  EXPECT_FALSE(pingViewerNameTime_s("ping360_basin.bin"));
  EXPECT_FALSE(pingViewerNameTime_s("20241314-101502123.bin"));
  EXPECT_FALSE(pingViewerNameTime_s("20240814-1015021234.bin"));
}

TEST(formatsLogClock, APingViewerLogsNameAndTheTimeZoneGiveItsClock) {
  test::TempDir dir;
  const std::string log = test::pingViewerLog({{"00:00:02.000", test::ping360Message({})}});
  std::ofstream(dir.file("20240814-134502123.bin"), std::ios::binary) << log;
  std::ofstream(dir.file("renamed.bin"), std::ios::binary) << log;
  LogReadOptions tehran;
  tehran.utc_offset_s = parseUtcOffset("+03:30");
  const SonarLog named = readSonarLog(dir.file("20240814-134502123.bin"), LogFormat::kPing360, tehran);
  ASSERT_TRUE(named.clock_utc_s);
  EXPECT_DOUBLE_EQ(*named.clock_utc_s, kAugust14_s);
  EXPECT_FALSE(readSonarLog(dir.file("renamed.bin")).clock_utc_s);
}

TEST(formatsLogClock, AlignNavigationClockJoinsUtcClocksElseTakesTheOffsetAlone) {
  NavigationSource nav;
  nav.track = {NavSample{kAugust14_s + 10.0}, NavSample{kAugust14_s + 20.0}};
  nav.clock_utc_s = 0.0;
  NavigationSource a = nav;
  const NavClockAlignment both = alignNavigationClock(a, kAugust14_s, 0.5);
  EXPECT_TRUE(both.both_utc);
  EXPECT_NEAR(a.track[0].time_s, 10.5, 1e-6);
  EXPECT_NEAR(a.track[1].time_s, 20.5, 1e-6);
  EXPECT_TRUE(contains(both.how, "both clocks in UTC")) << both.how;
  NavigationSource b = nav;
  const NavClockAlignment one = alignNavigationClock(b, std::nullopt, -kAugust14_s);
  EXPECT_FALSE(one.both_utc);
  EXPECT_NEAR(b.track[0].time_s, 10.0, 1e-6);
  EXPECT_TRUE(contains(one.how, "the sonar log does not say when it started")) << one.how;
  EXPECT_THROW(alignNavigationClock(b, std::nullopt, std::nan("")), ValueError);
}

}  // namespace
}  // namespace sonarmap
