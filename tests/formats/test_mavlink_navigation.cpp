/// Tests of MavlinkNavigation (mavlink_navigation.hpp): an ArduSub stream emulated frame by frame
/// (mavlink_autopilot.hpp) becomes fixes: one per ATTITUDE, each made when its position source's
/// next sample arrives and never later than max_hold_s; the sources in their order (the EKF's
/// LOCAL_POSITION_NED, a DVL's VISION_POSITION_DELTA, GLOBAL_POSITION_INT, the external pressure
/// sensor) and what happens when one is missing or stops; the clock of the least-delayed frame,
/// reboots; the vehicle among other senders; and the `.tlog` reader giving the same fixes.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/mavlink_navigation.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"
#include "mavlink_autopilot.hpp"

namespace sonarmap {
namespace {

using test::Datagram;
using test::MavlinkSenderStream;

constexpr double kPi = std::numbers::pi;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
std::string joinedNotes(MavlinkNavigation& nav) {
  std::string all;
  for (const std::string& n : nav.takeNotes()) all += n + "\n";
  return all;
}

/// ATTITUDE at 10 Hz from `from_s` to `to_s` (boot time), yaw turning; LOCAL_POSITION_NED at 5 Hz
/// on a line (x = 2 t, y = −t, z = 3 + 0.1 t), each sent after the ATTITUDE of the same time.
std::vector<Datagram> diveWithEkf(double from_s, double to_s, double delay_s = 0.05) {
  std::vector<Datagram> out;
  MavlinkSenderStream ap{.delay_s = delay_s, .out = &out};
  for (int i = 0; from_s + 0.1 * i <= to_s + 1e-9; ++i) {
    const double t = from_s + 0.1 * i;
    ap.attitude(t, 0.01f * i, -0.02f, static_cast<float>(0.05 * i - 1.0));
    if (i % 2 == 0) ap.localPosition(t, static_cast<float>(2 * t), static_cast<float>(-t), static_cast<float>(3 + 0.1 * t));
  }
  return out;
}

TEST(formatsMavlinkNavigation, AFixPerAttitudeWaitsForTheNextPositionAndIsInterpolated) {
  const std::vector<Datagram> stream = diveWithEkf(10.0, 12.0);
  MavlinkNavigation nav("udp://0.0.0.0:14550");
  std::vector<NavSample> fixes;
  for (const Datagram& d : stream) {
    const std::vector<NavSample> made = nav.feed(d.bytes, d.arrival_s);
    fixes.insert(fixes.end(), made.begin(), made.end());
    // A fix is never older than its source's next sample: it is made when that sample arrives.
    for (const NavSample& f : made) EXPECT_LE(f.time_s, d.arrival_s + 1e-9);
    if (!made.empty()) {
      EXPECT_LE(d.arrival_s - made.front().time_s, 0.2 + 1e-9);  // one LOCAL_POSITION_NED period
    }
  }
  EXPECT_TRUE(nav.finish().empty());
  ASSERT_EQ(fixes.size(), 21u);
  for (std::size_t i = 0; i < fixes.size(); ++i) {
    const double t = 10.0 + 0.1 * static_cast<double>(i);
    EXPECT_NEAR(fixes[i].time_s, t + 0.05, 1e-9) << i;  // boot time + the (constant) delay
    EXPECT_NEAR(fixes[i].position_ned_m.x(), 2 * t, 2e-5) << i;  // interpolated between 5 Hz samples
    EXPECT_NEAR(fixes[i].position_ned_m.y(), -t, 1e-5) << i;
    EXPECT_NEAR(fixes[i].position_ned_m.z(), 3 + 0.1 * t, 1e-5) << i;
    EXPECT_FLOAT_EQ(static_cast<float>(fixes[i].roll_rad), 0.01f * static_cast<float>(i));
    EXPECT_FLOAT_EQ(static_cast<float>(fixes[i].yaw_rad), static_cast<float>(0.05 * static_cast<double>(i) - 1.0));
  }
  EXPECT_EQ(nav.description(), "attitude ATTITUDE, position LOCAL_POSITION_NED");
  EXPECT_EQ(nav.vehicle()->system, 1);
  EXPECT_EQ(nav.attitudesWithoutFix(), 0u);
  EXPECT_TRUE(contains(joinedNotes(nav), "udp://0.0.0.0:14550: north and east from boot time 10.000 s: LOCAL_POSITION_NED"));
}

TEST(formatsMavlinkNavigation, TimesAreBootTimesPlusTheLeastDelaySoFarAndStrictlyIncrease) {
  std::vector<Datagram> stream = diveWithEkf(5.0, 8.0);
  // reception jitter of 0–60 ms, the least delay (10 ms) first seen at boot 6.0 s
  for (Datagram& d : stream) {
    const int k = static_cast<int>(std::lround(d.boot_s * 10.0));
    d.arrival_s = d.boot_s + (std::abs(d.boot_s - 6.0) < 1e-9 ? 0.010 : 0.020 + 0.040 * ((k * 7) % 5) / 4.0);
  }
  MavlinkNavigation nav;
  const std::vector<NavSample> fixes = test::decodeAll(nav, stream);
  ASSERT_GE(fixes.size(), 25u);
  for (std::size_t i = 1; i < fixes.size(); ++i) EXPECT_GT(fixes[i].time_s, fixes[i - 1].time_s);
  EXPECT_EQ(fixes.size() + nav.attitudesWithoutFix(), 31u);
  // after the least-delayed frame every fix is at boot time + 10 ms
  for (const NavSample& f : fixes) {
    const double boot_s = std::round((f.time_s - 0.010) * 10.0) / 10.0;
    if (boot_s > 6.05) {
      EXPECT_NEAR(f.time_s, boot_s + 0.010, 1e-9);
    }
  }
  // The .tlog of the same frames puts every fix on the least delay of the whole boot.
  const NavigationSource tlog = parseMavlinkTlogNavigation(test::asTlog(stream, 1723630500.0), "same.tlog");
  ASSERT_EQ(tlog.track.size(), 31u);
  for (std::size_t i = 0; i < tlog.track.size(); ++i) {
    EXPECT_NEAR(tlog.track[i].time_s - 1723630500.0, 5.0 + 0.1 * static_cast<double>(i) + 0.010, 1e-6) << i;
  }
}

TEST(formatsMavlinkNavigation, ATlogOfTheStreamGivesTheLiveFixes) {
  std::vector<Datagram> stream = diveWithEkf(100.0, 103.0);
  for (Datagram& d : stream) d.arrival_s += 0.003 * std::sin(d.boot_s * 37.0) + 0.003;  // jitter ≥ 0: the first frame is least delayed
  stream.front().arrival_s = stream.front().boot_s + 0.05;
  MavlinkNavigation live;
  const std::vector<NavSample> fixes = test::decodeAll(live, stream);
  const NavigationSource tlog = parseMavlinkTlogNavigation(test::asTlog(stream, 1723630000.0), "dive.tlog");
  ASSERT_EQ(fixes.size(), tlog.track.size());
  for (std::size_t i = 0; i < fixes.size(); ++i) {
    EXPECT_NEAR(tlog.track[i].time_s - 1723630000.0, fixes[i].time_s, 1e-6) << i;
    EXPECT_EQ(tlog.track[i].position_ned_m, fixes[i].position_ned_m) << i;
    EXPECT_EQ(tlog.track[i].yaw_rad, fixes[i].yaw_rad) << i;
  }
  EXPECT_EQ(tlog.description, "MAVLink telemetry dive.tlog (" + live.description() + ")");
}

/// ATTITUDE at 10 Hz for `seconds`, and depth messages of the kinds asked for at 5 Hz.
struct DepthOnlyVehicle {
  bool global = false, pressure2 = false, pressure3_temperature = false, pressure1 = false;
  std::vector<Datagram> stream(double seconds) const {
    std::vector<Datagram> out;
    MavlinkSenderStream ap{.out = &out};
    for (int i = 0; 0.1 * i <= seconds + 1e-9; ++i) {
      const double t = 20.0 + 0.1 * i;
      const double depth_m = 2.0 + 0.05 * i;
      ap.attitude(t, 0.0f, 0.0f, 1.0f);
      if (i % 2 != 0) continue;
      if (global) ap.relativeAltitude(t, depth_m + 0.5);  // distinguishable from the pressure's depth
      if (pressure1) ap.pressure(29, t, 1003.0f);          // the enclosure's air
      if (pressure2) ap.pressure(137, t, test::hpaAtDepth(depth_m));
      if (pressure3_temperature) ap.pressure(143, t, 0.0f);  // ArduSub's temperature sensor, no pressure
    }
    return out;
  }
};

TEST(formatsMavlinkNavigation, DepthComesFromGlobalPositionElseTheExternalPressureSensor) {
  const auto fixesOf = [](const DepthOnlyVehicle& v, std::string* description, const MavlinkNavigationOptions& o = {}) {
    MavlinkNavigation nav("serial", o);
    std::vector<NavSample> fixes = test::decodeAll(nav, v.stream(3.0));
    *description = nav.description();
    return fixes;
  };
  std::string words;
  std::vector<NavSample> a = fixesOf({.global = true, .pressure2 = true, .pressure1 = true}, &words);
  ASSERT_EQ(a.size(), 31u);
  EXPECT_NEAR(a[10].position_ned_m.z(), 2.0 + 0.5 + 0.5, 1e-9);
  EXPECT_EQ(a[10].position_ned_m.x(), 0.0);
  EXPECT_EQ(words, "attitude ATTITUDE, depth GLOBAL_POSITION_INT.relative_alt, no horizontal position (north, east 0)");
  std::vector<NavSample> b = fixesOf({.pressure2 = true, .pressure3_temperature = true, .pressure1 = true}, &words);
  ASSERT_EQ(b.size(), 31u);
  EXPECT_NEAR(b[10].position_ned_m.z(), 2.5, 2e-4);  // SCALED_PRESSURE2: the Bar30, before SCALED_PRESSURE (air)
  EXPECT_TRUE(contains(words, "depth SCALED_PRESSURE2")) << words;
  std::vector<NavSample> fresh = fixesOf({.pressure2 = true}, &words, {.pressure = {.water_density_kg_m3 = 997.0}});
  EXPECT_NEAR(fresh[10].position_ned_m.z(), 2.5 * 1025.0 / 997.0, 2e-4);
  // SCALED_PRESSURE3 at 0 hPa carries a temperature, not a pressure: the depth is SCALED_PRESSURE's
  std::vector<NavSample> c = fixesOf({.pressure3_temperature = true, .pressure1 = true}, &words);
  ASSERT_EQ(c.size(), 31u);
  EXPECT_NEAR(c[10].position_ned_m.z(), (100300.0 - 101325.0) / (1025.0 * 9.80665), 1e-4);
  EXPECT_TRUE(contains(words, "depth SCALED_PRESSURE,")) << words;
  EXPECT_THROW(MavlinkNavigation("x", {.pressure = {.surface_pressure_pa = 0.0}}), ValueError);
  EXPECT_THROW(MavlinkNavigation("x", {.pressure = {}, .max_hold_s = 0.0}), ValueError);
}

TEST(formatsMavlinkNavigation, WithoutAHorizontalSourceNorthAndEastAreHeldAtZeroAfterTheSourcesAreLearnt) {
  const std::vector<Datagram> stream = DepthOnlyVehicle{.pressure2 = true}.stream(3.0);
  MavlinkNavigation nav;
  std::vector<NavSample> fixes;
  double first_fix_boot_s = -1.0;
  for (const Datagram& d : stream) {
    const std::vector<NavSample> made = nav.feed(d.bytes, d.arrival_s);
    if (!made.empty() && first_fix_boot_s < 0.0) first_fix_boot_s = d.boot_s;
    fixes.insert(fixes.end(), made.begin(), made.end());
  }
  // the first fixes wait max_hold_s (1 s) for a LOCAL_POSITION_NED that never comes, then all come
  EXPECT_NEAR(first_fix_boot_s, 21.0, 1e-9);
  EXPECT_GE(fixes.size(), 29u);
  for (const NavSample& f : fixes) {
    EXPECT_EQ(f.position_ned_m.x(), 0.0);
    EXPECT_EQ(f.position_ned_m.y(), 0.0);
  }
  const std::string notes = joinedNotes(nav);
  EXPECT_TRUE(contains(notes, "north and east from boot time 20.000 s: held at 0 (no LOCAL_POSITION_NED, VISION_POSITION_DELTA)"))
      << notes;
  EXPECT_TRUE(contains(notes, "depth from boot time 20.000 s: SCALED_PRESSURE2")) << notes;
  EXPECT_EQ(notes.find("held at 0", notes.find("held at 0") + 1), std::string::npos) << notes;  // said once
}

TEST(formatsMavlinkNavigation, ADvlsVisionPositionDeltaIsTurnedIntoNedByTheAttitude) {
  std::vector<Datagram> stream;
  MavlinkSenderStream ap{.out = &stream};
  MavlinkSenderStream dvl{.encoder = MavlinkEncoder(255, 0), .out = &stream};  // BlueOS's mavlink2rest
  MavlinkSenderStream other{.encoder = MavlinkEncoder(3, 197), .out = &stream};
  for (int i = 0; i <= 40; ++i) {
    const double t = 50.0 + 0.1 * i;
    ap.attitude(t, 0.0f, 0.0f, static_cast<float>(kPi / 2));  // heading east
    if (i % 2 == 0) ap.pressure(137, t, test::hpaAtDepth(4.0));
    MavlinkVisionPositionDelta v;  // 0.1 m forward per 100 ms, time_usec unset as BlueOS sends it
    v.time_delta_usec = 100000;
    v.position_delta_m = {0.1f, 0.0f, 0.0f};
    v.confidence_percent = 90.0f;
    dvl.send(t, toMavlinkPayload(v));
    v.position_delta_m = {5.0f, 5.0f, 0.0f};
    other.send(t, toMavlinkPayload(v));  // a second sender of deltas is not added
  }
  MavlinkNavigation nav;
  const std::vector<NavSample> fixes = test::decodeAll(nav, stream);
  ASSERT_GE(fixes.size(), 35u);
  for (const NavSample& f : fixes) {
    const double k = std::round((f.time_s - 0.05 - 50.0) * 10.0);  // the attitude's index
    EXPECT_NEAR(f.position_ned_m.y(), 0.1 * k, 1e-5) << k;  // east: the deltas since the first fix
    EXPECT_NEAR(f.position_ned_m.x(), 0.0, 1e-6);
    EXPECT_NEAR(f.position_ned_m.z(), 4.0, 1e-4);
  }
  EXPECT_EQ(nav.description(), "attitude ATTITUDE, north and east from VISION_POSITION_DELTA, depth from SCALED_PRESSURE2");
}

TEST(formatsMavlinkNavigation, ASilentSourceServesMaxHoldThenGivesWayAndNoFixWaitsLonger) {
  std::vector<Datagram> stream;
  MavlinkSenderStream ap{.out = &stream};
  for (int i = 0; i <= 60; ++i) {
    const double t = 30.0 + 0.1 * i;
    ap.attitude(t, 0.0f, 0.0f, 0.0f);
    if (i % 2 != 0) continue;
    if (t <= 32.0 + 1e-9) ap.localPosition(t, static_cast<float>(t), 1.0f, 2.0f);  // the EKF loses its position at 32 s
    ap.relativeAltitude(t, 7.0);
  }
  MavlinkNavigation nav;
  std::vector<NavSample> fixes;
  for (const Datagram& d : stream) {
    for (const NavSample& f : nav.feed(d.bytes, d.arrival_s)) {
      EXPECT_LE(d.boot_s - (f.time_s - 0.05), 1.0 + 0.1 + 1e-9);  // made within max_hold_s and a frame
      fixes.push_back(f);
    }
  }
  ASSERT_GE(fixes.size(), 50u);
  const auto at = [&fixes](double boot_s) {
    for (const NavSample& f : fixes) {
      if (std::abs(f.time_s - 0.05 - boot_s) < 1e-6) return f;
    }
    ADD_FAILURE() << "no fix at " << boot_s;
    return NavSample{};
  };
  EXPECT_NEAR(at(31.5).position_ned_m.x(), 31.5, 1e-5);
  EXPECT_NEAR(at(32.5).position_ned_m.x(), 32.0, 1e-5);  // the last LOCAL_POSITION_NED, for up to max_hold_s
  EXPECT_NEAR(at(32.5).position_ned_m.z(), 2.0, 1e-5);
  EXPECT_NEAR(at(33.5).position_ned_m.x(), 32.0, 1e-5);  // then north and east held, depth from GLOBAL_POSITION_INT
  EXPECT_NEAR(at(33.5).position_ned_m.z(), 7.0, 1e-9);
  const std::string notes = joinedNotes(nav);
  EXPECT_TRUE(contains(notes, "LOCAL_POSITION_NED (its last sample: the message stopped)")) << notes;
  EXPECT_TRUE(contains(notes, "held at its last value")) << notes;
  EXPECT_TRUE(contains(notes, "depth from boot time 33.100 s: GLOBAL_POSITION_INT.relative_alt")) << notes;
}

TEST(formatsMavlinkNavigation, WhenTheEkfStopsADvlsDeltasCarryNorthAndEastOnWithoutAJump) {
  std::vector<Datagram> stream;
  MavlinkSenderStream ap{.out = &stream};
  MavlinkSenderStream dvl{.encoder = MavlinkEncoder(255, 0), .out = &stream};
  for (int i = 0; i <= 50; ++i) {
    const double t = 30.0 + 0.1 * i;
    ap.attitude(t, 0.0f, 0.0f, 0.0f);  // heading north
    if (i % 2 == 0 && t <= 32.0 + 1e-9) ap.localPosition(t, static_cast<float>(t), 0.0f, 2.0f);
    if (i % 2 == 0) ap.pressure(137, t, test::hpaAtDepth(2.0));
    MavlinkVisionPositionDelta v;
    v.position_delta_m = {0.1f, 0.0f, 0.0f};
    dvl.send(t, toMavlinkPayload(v));
  }
  MavlinkNavigation nav;
  const std::vector<NavSample> fixes = test::decodeAll(nav, stream);
  ASSERT_EQ(fixes.size(), 51u);
  const auto northAt = [&fixes](double boot_s) { return fixes[static_cast<std::size_t>(std::lround((boot_s - 30.0) * 10))].position_ned_m.x(); };
  EXPECT_NEAR(northAt(31.9), 31.9, 1e-5);  // LOCAL_POSITION_NED
  EXPECT_NEAR(northAt(33.0), 32.0, 1e-5);  // its last sample, up to max_hold_s after it
  EXPECT_NEAR(northAt(33.1), 32.0, 1e-5);  // then the deltas, from there
  EXPECT_NEAR(northAt(34.0), 32.9, 1e-5);
  EXPECT_NEAR(fixes.back().position_ned_m.z(), 2.0, 1e-4);
  EXPECT_EQ(nav.description(),
            "attitude ATTITUDE, north and east from LOCAL_POSITION_NED and VISION_POSITION_DELTA, depth from "
            "LOCAL_POSITION_NED and SCALED_PRESSURE2");
}

TEST(formatsMavlinkNavigation, TheVehicleIsTheFirstAttitudesSenderAndItsEarlierFramesCount) {
  std::vector<Datagram> stream;
  MavlinkSenderStream gcs{.encoder = MavlinkEncoder(255, 190), .out = &stream};
  MavlinkSenderStream ap{.out = &stream};
  MavlinkSenderStream companion{.encoder = MavlinkEncoder(2, 1), .out = &stream};
  gcs.heartbeat(0.0, 6);
  ap.heartbeat(60.0);
  ap.localPosition(60.0, 1.0f, 2.0f, 3.0f);  // before the first ATTITUDE: kept, then read
  for (int i = 0; i <= 10; ++i) {
    const double t = 60.0 + 0.1 * i;
    ap.attitude(t, 0.1f, 0.2f, 0.3f);
    companion.attitude(t, 3.0f, 3.0f, 3.0f);
    if (i % 2 == 0 && i > 0) ap.localPosition(t, 1.0f, 2.0f, 3.0f);
  }
  MavlinkNavigation nav;
  const std::vector<NavSample> fixes = test::decodeAll(nav, stream);
  ASSERT_EQ(fixes.size(), 11u);  // the first ATTITUDE has its LOCAL_POSITION_NED
  for (const NavSample& f : fixes) EXPECT_FLOAT_EQ(static_cast<float>(f.roll_rad), 0.1f);
  EXPECT_EQ(nav.vehicle()->system, 1);
  EXPECT_EQ(nav.vehicle()->component, 1);
}

TEST(formatsMavlinkNavigation, AnAttitudeJustBeforeItsSourceBeginsGivesNoFix) {
  std::vector<Datagram> stream;
  MavlinkSenderStream ap{.out = &stream};
  ap.attitude(70.0, 0.0f, 0.0f, 0.0f);
  for (int i = 1; i <= 10; ++i) {
    const double t = 70.0 + 0.1 * i;
    if (i % 2 == 1) ap.localPosition(t - 0.05, 5.0f, 5.0f, 5.0f);
    ap.attitude(t, 0.0f, 0.0f, 0.0f);
  }
  MavlinkNavigation nav;
  const std::vector<NavSample> fixes = test::decodeAll(nav, stream);
  // the first attitude (50 ms before the first position) and the last two (after the last) give none
  ASSERT_EQ(fixes.size(), 8u);
  EXPECT_EQ(nav.attitudesWithoutFix(), 3u);
  for (const NavSample& f : fixes) EXPECT_EQ(f.position_ned_m, Eigen::Vector3d(5, 5, 5));
}

TEST(formatsMavlinkNavigation, ARebootStartsTheClockAnew) {
  std::vector<Datagram> stream = diveWithEkf(40.0, 41.0, 0.05);
  std::vector<Datagram> after = diveWithEkf(3.0, 4.0, 0.05);  // rebooted: boot time 3 s, received from 50 s on
  for (Datagram& d : after) d.arrival_s += 47.0;
  stream.insert(stream.end(), after.begin(), after.end());
  MavlinkNavigation nav;
  const std::vector<NavSample> fixes = test::decodeAll(nav, stream);
  ASSERT_EQ(fixes.size(), 22u);
  EXPECT_NEAR(fixes[10].time_s, 41.05, 1e-9);
  EXPECT_NEAR(fixes[11].time_s, 50.05, 1e-9);
  EXPECT_NEAR(fixes[11].position_ned_m.x(), 6.0, 1e-5);
  EXPECT_TRUE(contains(joinedNotes(nav), "the autopilot rebooted (boot time 3.000 s after 41.000 s)"));
}

TEST(formatsMavlinkNavigation, BytesInAnyChunksWithNoiseGiveTheSameFixes) {
  const std::vector<Datagram> stream = diveWithEkf(10.0, 13.0);
  MavlinkNavigation whole;
  const std::vector<NavSample> expected = test::decodeAll(whole, stream);
  MavlinkNavigation cut;
  std::vector<NavSample> fixes;
  std::uint32_t state = 12345;
  const std::vector<std::uint8_t> noise{'x', 0xFD, 0x05, 0x00, 0x00, 'y', 0xFE, 0x01, '\n'};
  for (const Datagram& d : stream) {
    std::vector<std::uint8_t> bytes = noise;
    bytes.insert(bytes.end(), d.bytes.begin(), d.bytes.end());
    for (std::size_t at = 0; at < bytes.size();) {
      state = state * 1664525U + 1013904223U;
      const std::size_t n = std::min<std::size_t>(bytes.size() - at, 1 + (state >> 24) % 13);
      for (const NavSample& f : cut.feed(std::span(bytes).subspan(at, n), d.arrival_s)) fixes.push_back(f);
      at += n;
    }
  }
  for (const NavSample& f : cut.finish()) fixes.push_back(f);
  ASSERT_EQ(fixes.size(), expected.size());
  for (std::size_t i = 0; i < fixes.size(); ++i) {
    EXPECT_EQ(fixes[i].time_s, expected[i].time_s);
    EXPECT_EQ(fixes[i].position_ned_m, expected[i].position_ned_m);
  }
  EXPECT_EQ(cut.streamCounts().frames, whole.streamCounts().frames);
  EXPECT_GT(cut.streamCounts().noise_bytes, 0u);
}

TEST(formatsMavlinkNavigation, FinishMakesTheWaitingFixesItCanAndThenNothingMore) {
  std::vector<Datagram> stream = diveWithEkf(10.0, 11.0);
  MavlinkSenderStream ap{.out = &stream};
  ap.attitude(11.05, 0.0f, 0.0f, 0.0f);  // after the last position: no fix
  MavlinkNavigation nav;
  const std::vector<NavSample> fixes = test::decodeAll(nav, stream);
  EXPECT_EQ(fixes.size(), 11u);
  EXPECT_EQ(nav.attitudesWithoutFix(), 1u);
  EXPECT_TRUE(nav.feed(stream.front().bytes, 99.0).empty());
  EXPECT_TRUE(nav.finish().empty());
  EXPECT_THROW(nav.feed(stream.front().bytes, NAN), ValueError);
}

}  // namespace
}  // namespace sonarmap
