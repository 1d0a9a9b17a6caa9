/// Tests of the depth of MavlinkNavigation's fixes (mavlink_navigation.hpp, "Depth"): one source at
/// a time, with hysteresis, and the pressure fallback in the autopilot's own calibration. The
/// vehicle holds still at 5.70 m: ArduSub's GLOBAL_POSITION_INT at 0.5 Hz (SRx_POSITION 0.5 Hz
/// beside SRx_RAW_SENS 10 Hz, as issue 79 found it on a BlueROV2), the Bar30's SCALED_PRESSURE2
/// at 10 Hz in fresh water under an atmosphere of 1004 hPa, which the options' defaults (101325
/// Pa, 1025 kg/m³) read 0.29 m shallower.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sonarmap/formats/mavlink_navigation.hpp"
#include "mavlink_autopilot.hpp"

namespace sonarmap {
namespace {

using test::Datagram;
using test::MavlinkSenderStream;

constexpr double kDepth_m = 5.70;
constexpr double kAtmosphere_pa = 100400.0;
/// ArduSub's water barometer: 9800 Pa a metre times BARO_SPEC_GRAV (AP_Baro::update), 1.0 fresh.
constexpr double kPascalsPerMetre = 9800.0;

/// ATTITUDE and SCALED_PRESSURE2 at 10 Hz from boot time 20 s for `seconds`; GLOBAL_POSITION_INT
/// about every 2 s, its intervals 2.12 and 1.88 s in turn (the autopilot's scheduling), except in
/// [silent_from_s, silent_to_s).
std::vector<Datagram> holdingStill(double seconds, double silent_from_s = 1e9, double silent_to_s = 1e9,
                                   bool global = true) {
  std::vector<Datagram> out;
  MavlinkSenderStream ap{.out = &out};
  for (int i = 0; 0.1 * i <= seconds + 1e-9; ++i) {
    const double t = 20.0 + 0.1 * i;
    ap.attitude(t, 0.0f, 0.0f, 1.0f);
    ap.pressure(137, t, static_cast<float>((kAtmosphere_pa + kPascalsPerMetre * kDepth_m) / 100.0));
  }
  for (int k = 0; global && 2.0 * k <= seconds; ++k) {
    const double t = 20.0 + 2.0 * k + (k % 2 == 1 ? 0.12 : 0.0);
    if (!(t >= silent_from_s && t < silent_to_s)) ap.relativeAltitude(t, kDepth_m);
  }
  return out;
}

std::vector<std::string> depthNotes(MavlinkNavigation& nav) {
  std::vector<std::string> notes;
  for (const std::string& n : nav.takeNotes()) {
    if (n.find("depth from boot time") != std::string::npos) notes.push_back(n);
  }
  return notes;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string all;
  for (const std::string& l : lines) all += l + "\n";
  return all;
}

/// The smallest and largest depth of the fixes.
std::pair<double, double> depthSpan(const std::vector<NavSample>& fixes) {
  double low = INFINITY, high = -INFINITY;
  for (const NavSample& f : fixes) {
    low = std::min(low, f.position_ned_m.z());
    high = std::max(high, f.position_ned_m.z());
  }
  return {low, high};
}

TEST(formatsMavlinkDepthSource, AHalfHertzGlobalPositionKeepsTheDepthBesideATenHertzPressure) {
  MavlinkNavigation nav("udp://:14550");
  const std::vector<NavSample> fixes = test::decodeAll(nav, holdingStill(20.0));
  EXPECT_GE(fixes.size(), 190u);
  const std::vector<std::string> notes = depthNotes(nav);
  ASSERT_EQ(notes.size(), 1u) << joined(notes);  // chosen once, never switched
  EXPECT_NE(notes[0].find("GLOBAL_POSITION_INT.relative_alt"), std::string::npos) << notes[0];
  const auto [low, high] = depthSpan(fixes);
  EXPECT_NEAR(low, kDepth_m, 0.01);
  EXPECT_NEAR(high, kDepth_m, 0.01);
  EXPECT_EQ(nav.description(), "attitude ATTITUDE, depth GLOBAL_POSITION_INT.relative_alt, no horizontal position (north, east 0)");
}

TEST(formatsMavlinkDepthSource, ASilentGlobalPositionGivesWayToThePressureInItsCalibrationAndIsTakenBackOnceSteady) {
  // GLOBAL_POSITION_INT's last sample before the silence is at 34.12 s, its first after it at 50.12 s.
  MavlinkNavigation nav("udp://:14550");
  std::vector<NavSample> fixes;
  for (const Datagram& d : [] {
         std::vector<Datagram> s = holdingStill(50.0, 35.0, 50.0);
         std::stable_sort(s.begin(), s.end(), [](const Datagram& a, const Datagram& b) { return a.arrival_s < b.arrival_s; });
         return s;
       }()) {
    for (const NavSample& f : nav.feed(d.bytes, d.arrival_s)) {
      EXPECT_LE(d.boot_s - (f.time_s - 0.05), 1.0 + 0.12 + 1e-9) << f.time_s - 0.05;  // max_hold_s and the next frame at most
      fixes.push_back(f);
    }
  }
  for (const NavSample& f : nav.finish()) fixes.push_back(f);
  EXPECT_GE(fixes.size(), 490u);
  const std::vector<std::string> notes = depthNotes(nav);
  ASSERT_EQ(notes.size(), 3u) << joined(notes);
  // Silent for 3 of its intervals (median 2.12 s): the pressure from 40.5 s, its offset measured
  // against the autopilot's depth while both came.
  EXPECT_NE(notes[1].find("depth from boot time 40.500 s: SCALED_PRESSURE2"), std::string::npos) << notes[1];
  EXPECT_NE(notes[1].find("GLOBAL_POSITION_INT.relative_alt's calibration"), std::string::npos) << notes[1];
  // Back after it has come for 3 of its intervals again.
  EXPECT_NE(notes[2].find("depth from boot time 56.500 s: GLOBAL_POSITION_INT.relative_alt"), std::string::npos) << notes[2];
  const auto [low, high] = depthSpan(fixes);
  EXPECT_NEAR(low, kDepth_m, 0.02);
  EXPECT_NEAR(high, kDepth_m, 0.02);
}

TEST(formatsMavlinkDepthSource, WithoutTheAutopilotsDepthThePressureTakesItsParameters) {
  std::vector<Datagram> stream = holdingStill(10.0, 1e9, 1e9, false);
  MavlinkSenderStream ap{.out = &stream};
  // QGroundControl's parameter download, early in the stream: BARO2 is the Bar30 (SCALED_PRESSURE2).
  ap.send(20.05, toMavlinkPayload(MavlinkParamValue{static_cast<float>(kAtmosphere_pa), 900, 120, "BARO2_GND_PRESS", 9}));
  ap.send(20.05, toMavlinkPayload(MavlinkParamValue{1.0f, 900, 121, "BARO_SPEC_GRAV", 9}));
  MavlinkNavigation nav("udp://:14550");
  const std::vector<NavSample> fixes = test::decodeAll(nav, stream);
  EXPECT_GE(fixes.size(), 95u);
  const auto [low, high] = depthSpan(fixes);
  EXPECT_NEAR(low, kDepth_m, 0.005);
  EXPECT_NEAR(high, kDepth_m, 0.005);
  const std::vector<std::string> notes = depthNotes(nav);
  ASSERT_EQ(notes.size(), 1u) << joined(notes);
  EXPECT_NE(notes[0].find("BARO2_GND_PRESS"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("BARO_SPEC_GRAV"), std::string::npos) << notes[0];

  // Without them: the options' 101325 Pa and 1025 kg/m³, said so.
  MavlinkNavigation bare("udp://:14550");
  const std::vector<NavSample> guessed = test::decodeAll(bare, holdingStill(10.0, 1e9, 1e9, false));
  const double expected_m = (kAtmosphere_pa + kPascalsPerMetre * kDepth_m - 101325.0) / (1025.0 * 9.80665);
  EXPECT_NEAR(guessed.front().position_ned_m.z(), expected_m, 0.005);
  const std::vector<std::string> bare_notes = depthNotes(bare);
  ASSERT_EQ(bare_notes.size(), 1u) << joined(bare_notes);
  EXPECT_NE(bare_notes[0].find("101325 Pa"), std::string::npos) << bare_notes[0];
}

}  // namespace
}  // namespace sonarmap
