// ping360_settings.hpp: Ping Viewer's rules for the sample period, the samples and the transmit
// duration (checked against the settings Ping Viewer wrote in the shared logs), the scan's angles,
// and the settings refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <string>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/devices/ping360_settings.hpp"
#include "sonarmap/formats/ping360_reader.hpp"

namespace sonarmap {
namespace {

constexpr double kGradian = std::numbers::pi / 200.0;
constexpr double kDegree = std::numbers::pi / 180.0;

HeadSettings withRange(double range_m) {
  HeadSettings settings;
  settings.range_m = range_m;
  return settings;
}

TEST(devicesPing360Settings, PingViewersRangeRule) {
  // Ping Viewer's own numbers: its power-on 2 m is 88 ticks and 11 µs (_viewerDefaultSamplePeriod,
  // _viewerDefaultTransmitDuration).
  const Ping360Settings two = ping360Settings(withRange(2.0));
  EXPECT_EQ(two.sampling.samples, 1200);
  EXPECT_EQ(two.sampling.sample_period_ticks, 88);
  EXPECT_EQ(two.transmit_duration_us, 11);
  const Ping360Settings fifty = ping360Settings(withRange(50.0));
  EXPECT_EQ(fifty.sampling.sample_period_ticks, 2222);
  EXPECT_EQ(fifty.transmit_duration_us, 267);  // the `ping360` preset's 267 µs
  EXPECT_NEAR(fifty.range_m(), 49.995, 1e-9);
  // Below 1.8 m the period would fall under 80 ticks: fewer samples instead.
  const Ping360Settings near = ping360Settings(withRange(0.75));
  EXPECT_EQ(near.sampling.sample_period_ticks, 80);
  EXPECT_EQ(near.sampling.samples, 500);
  EXPECT_EQ(near.transmit_duration_us, 5);
  EXPECT_EQ(ping360Sampling(1.0, 1500.0).samples, 666);
  // The default range, 20 m.
  const Ping360Settings standard = ping360Settings(HeadSettings{});
  EXPECT_EQ(standard.sampling.samples, 1200);
  EXPECT_EQ(standard.sampling.sample_period_ticks, 888);
  EXPECT_EQ(standard.transmit_duration_us, 107);
  EXPECT_EQ(standard.gain_setting, 1);
  EXPECT_EQ(standard.transmit_frequency_khz, 750);
  // The firmware's cap: min(500 µs, 64 sample periods).
  EXPECT_EQ(ping360MaxTransmitDuration_us(80), 128);
  EXPECT_EQ(ping360MaxTransmitDuration_us(2222), 500);
  // A slower sound speed: the same range takes longer periods.
  HeadSettings fresh = withRange(20.0);
  fresh.sound_speed_m_s = 1450.0;
  EXPECT_EQ(ping360Settings(fresh).sampling.sample_period_ticks, 919);
}

// The shared Ping Viewer logs recorded 2, 10, 15, 20, 30, 40, 50 and 60 m: each range's sample
// period and transmit duration there are what the rule gives (at Ping Viewer's 1500 m/s).
TEST(devicesPing360Settings, TheSharedLogsSettingsAreTheRules) {
  std::map<std::pair<int, int>, int> seen;  // (sample period ticks, transmit duration µs) → beams
  for (const char* name : {"ping360_harbour_range_changes.bin", "ping360_basin.bin"}) {
    const std::string path = std::string(SONARMAP_SHARED_DATA) + "/" + name;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
    for (const Beam& beam : readPing360(path).beams) {
      ASSERT_EQ(beam.intensities.size(), 1200u);
      const int ticks = static_cast<int>(std::lround(2.0 * beam.bin_length_m / (1500.0 * 25e-9)));
      const int duration = static_cast<int>(std::lround(*beam.pulse_length_m * 2.0 / 1500.0 * 1e6));
      ++seen[{ticks, duration}];
    }
  }
  std::set<std::pair<int, int>> expected;
  for (const double range_m : {2.0, 10.0, 15.0, 20.0, 30.0, 40.0, 50.0, 60.0}) {
    const Ping360Settings settings = ping360Settings(withRange(range_m));
    EXPECT_EQ(settings.sampling.samples, 1200);
    expected.insert({settings.sampling.sample_period_ticks, settings.transmit_duration_us});
  }
  std::set<std::pair<int, int>> found;
  for (const auto& [key, beams] : seen) found.insert(key);
  EXPECT_EQ(found, expected);
}

TEST(devicesPing360Settings, AnglesOfFullTurnsAndSectors) {
  HeadSettings asked;
  const Ping360Settings turns = ping360Settings(asked);
  EXPECT_TRUE(turns.full_turns);
  for (int i = 0; i < 400; ++i) EXPECT_EQ(turns.angleOf(i), i);
  EXPECT_EQ(turns.angleOf(400), 0);
  asked.step_rad = 3 * kGradian;
  asked.sector_center_rad = -10 * kGradian;
  const Ping360Settings by3 = ping360Settings(asked);
  EXPECT_EQ(by3.angleOf(0), 390);
  EXPECT_EQ(by3.angleOf(4), 2);  // on across 0, not back
  EXPECT_EQ(by3.angleOf(134), (390 + 134 * 3) % 400);

  // A 90° sector ahead, 1 gradian steps: 100 steps between 350 and 50, as Ping Viewer's (its
  // limits at ±sector/2 of the centre, each pinged once per reversal).
  HeadSettings sector;
  sector.sector_width_rad = 90.0 * kDegree;
  const Ping360Settings ahead = ping360Settings(sector);
  EXPECT_FALSE(ahead.full_turns);
  EXPECT_EQ(ahead.sector_steps, 100);
  EXPECT_EQ(ahead.first_grad, 350);
  EXPECT_EQ(ahead.angleOf(0), 350);
  EXPECT_EQ(ahead.angleOf(50), 0);
  EXPECT_EQ(ahead.angleOf(100), 50);
  EXPECT_EQ(ahead.angleOf(101), 49);
  EXPECT_EQ(ahead.angleOf(200), 350);
  EXPECT_EQ(ahead.angleOf(201), 351);
  // An odd span: 3 gradian steps over 100 gradians is 33 steps (99 gradians), from centre − 49.
  sector.step_rad = 3 * kGradian;
  sector.sector_center_rad = 100 * kGradian;
  const Ping360Settings odd = ping360Settings(sector);
  EXPECT_EQ(odd.sector_steps, 33);
  EXPECT_EQ(odd.angleOf(0), 51);
  EXPECT_EQ(odd.angleOf(33), 150);
  EXPECT_EQ(odd.angleOf(34), 147);
}

TEST(devicesPing360Settings, AppliedNamesEachSettingWithItsUnit) {
  HeadSettings asked;
  asked.gain = "HIGH";
  asked.sector_width_rad = 45.0 * kDegree;
  asked.sector_center_rad = 90.0 * kDegree;
  asked.step_rad = 2 * kGradian;
  asked.frequency_khz = 800.0;
  const AppliedSettings applied = ping360Settings(asked).applied();
  EXPECT_EQ(applied.text(),
            "Ping360: range_m 19.98, gain high, sector_deg 45, sector_center_deg 90, step_deg 1.8, frequency_khz "
            "800, transmit_duration_us 107, sample_period_ns 22200, samples 1200, sound_speed_m_s 1500");
  EXPECT_EQ(ping360GainSetting("medium"), 1);
  EXPECT_EQ(ping360GainSetting("0"), 0);
  EXPECT_EQ(ping360GainWord(2), "high");
}

// docs/commands.md: a step is rounded to the head's unit (1 gradian, 0.9 degrees) and said.
TEST(devicesPing360Settings, AStepBetweenGradiansIsRoundedAndSaid) {
  const auto stepOf = [](double step_deg) {
    HeadSettings asked;
    asked.step_rad = step_deg * kDegree;
    return ping360Settings(asked);
  };
  const Ping360Settings one = stepOf(1.0);
  EXPECT_EQ(one.step_grad, 1);
  EXPECT_EQ(one.applied().value("step_deg"), "0.9");
  ASSERT_EQ(one.notes.size(), 1u);
  EXPECT_EQ(one.notes[0],
            "--step 1 degrees rounded to 1 gradian = 0.9 degrees (the Ping360 steps in whole gradians of 0.9 degrees)");
  EXPECT_EQ(stepOf(1.5).step_grad, 2);    // 1.67 gradians
  EXPECT_EQ(stepOf(0.1).step_grad, 1);    // finer than the head: its finest
  EXPECT_EQ(stepOf(9.4).step_grad, 10);   // 10.44 gradians: its coarsest
  EXPECT_EQ(stepOf(5.0).notes.size(), 1u);
  // A whole number of gradians is taken as it is, without a note.
  EXPECT_EQ(stepOf(2.7).step_grad, 3);
  EXPECT_TRUE(stepOf(2.7).notes.empty());
  EXPECT_TRUE(ping360Settings(HeadSettings{}).notes.empty());
  // A sector is counted in the rounded steps: 90 degrees at 1 degree is 100 steps of 0.9.
  HeadSettings sector;
  sector.step_rad = 1.0 * kDegree;
  sector.sector_width_rad = 90.0 * kDegree;
  EXPECT_EQ(ping360Settings(sector).sector_steps, 100);
}

TEST(devicesPing360Settings, SettingsTheHeadCannotTakeAreRefused) {
  const auto refused = [](const HeadSettings& settings, const std::string& words) {
    try {
      ping360Settings(settings);
      ADD_FAILURE() << "accepted, expected: " << words;
    } catch (const ValueError& error) {
      EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
    }
  };
  refused(withRange(0.5), "--range 0.5 m is outside the Ping360's 0.75–60 m");
  refused(withRange(61.0), "--range 61 m");
  refused(withRange(std::nan("")), "--range nan m");
  HeadSettings gain;
  gain.gain = "loud";
  refused(gain, "--gain 'loud' is not a Ping360 gain setting: expected low, normal, high (or 0, 1, 2)");
  HeadSettings step;
  step.step_rad = 11 * kGradian;
  refused(step, "--step 9.9 degrees is not a step of the Ping360: expected above 0 and up to 9 degrees");
  step.step_rad = 9.5 * kDegree;
  refused(step, "--step 9.5 degrees");
  step.step_rad = 0.0;
  refused(step, "--step 0 degrees");
  step.step_rad = -1.0 * kDegree;
  refused(step, "--step -1 degrees");
  HeadSettings frequency;
  frequency.frequency_khz = 1001.0;
  refused(frequency, "--frequency 1001 kHz is outside the Ping360's 500–1000 kHz");
  HeadSettings speed;
  speed.sound_speed_m_s = 340.0;
  refused(speed, "--sound-speed 340 m/s is outside 1400–1600 m/s");
  HeadSettings narrow;
  narrow.sector_width_rad = 0.5 * kDegree;
  refused(narrow, "--sector 0.5 degrees is narrower than one step (0.9 degrees)");
  narrow.sector_width_rad = -1.0;
  refused(narrow, "is outside (0, 360]");
  HeadSettings centre;
  centre.sector_center_rad = INFINITY;
  refused(centre, "--sector-center inf degrees is not a finite bearing");
}

TEST(devicesPing360Settings, AngleDistanceIsTheShortestWay) {
  EXPECT_EQ(ping360AngleDistance(0, 399), 1);
  EXPECT_EQ(ping360AngleDistance(399, 0), 1);
  EXPECT_EQ(ping360AngleDistance(0, 200), 200);
  EXPECT_EQ(ping360AngleDistance(10, 250), 160);
}

}  // namespace
}  // namespace sonarmap
