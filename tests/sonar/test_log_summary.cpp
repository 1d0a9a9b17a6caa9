/// Tests of summarizeLog on hand-built logs: full turns, sector scans, range and gain changes,
/// skip reasons, navigation coverage, an empty log; and on the CRAS log when the shared data is there.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <vector>

#include "sonarmap/formats/mat_reader.hpp"
#include "sonarmap/sonar/log_summary.hpp"

namespace sonarmap {
namespace {

constexpr double kPi = std::numbers::pi;

/// Appends beams at `bearings_deg` (wrapped to [0, 360)), `seconds_apart` after the log's last
/// beam, each with `bins` bins of `bin_length_m` and the gain setting `gain`.
void addBeams(SonarLog& log, const std::vector<double>& bearings_deg, double bin_length_m = 0.01,
              std::optional<int> gain = std::nullopt, std::size_t bins = 10, double seconds_apart = 0.1) {
  for (const double deg : bearings_deg) {
    double wrapped = std::fmod(deg, 360.0);
    if (wrapped < 0.0) wrapped += 360.0;
    const double time_s = log.beams.empty() ? 0.0 : log.beams.back().time_s + seconds_apart;
    Beam beam;
    beam.time_s = time_s;
    beam.bearing_rad = wrapped * kPi / 180.0;
    beam.bin_length_m = bin_length_m;
    beam.intensities.assign(bins, 0);
    beam.gain_setting = gain;
    log.beams.push_back(std::move(beam));
  }
}

/// `count` bearings from `start_deg` in steps of `step_deg`.
std::vector<double> steps(double start_deg, double step_deg, int count) {
  std::vector<double> out;
  for (int i = 0; i < count; ++i) out.push_back(start_deg + step_deg * i);
  return out;
}

TEST(sonarLogSummary, TwoFullTurns) {
  SonarLog log;
  addBeams(log, steps(90.0, 1.8, 400), 0.0125, std::nullopt, 400, 0.05);  // starts at 90°: wraps through 0 inside a turn
  const LogSummary s = summarizeLog(log);
  EXPECT_EQ(s.beams, 400U);
  EXPECT_DOUBLE_EQ(s.first_time_s, 0.0);
  EXPECT_NEAR(s.last_time_s, 399 * 0.05, 1e-9);
  EXPECT_NEAR(s.duration_s, 399 * 0.05, 1e-9);
  ASSERT_TRUE(s.beam_rate_hz);
  EXPECT_NEAR(*s.beam_rate_hz, 20.0, 1e-9);
  ASSERT_EQ(s.sweeps.size(), 2U);
  EXPECT_EQ(s.full_turns, 2U);
  EXPECT_EQ(s.sector_passes, 0U);
  EXPECT_EQ(s.partial_turns, 0U);
  for (const SweepSummary& sweep : s.sweeps) {
    EXPECT_EQ(sweep.kind, SweepKind::kFullTurn);
    EXPECT_EQ(sweep.beams, 200U);
    EXPECT_EQ(sweep.direction, 1);
    EXPECT_NEAR(sweep.span_deg, 358.2, 1e-6);
  }
  EXPECT_NEAR(s.sweeps[1].first_bearing_deg, 90.0, 1e-9);
  EXPECT_EQ(s.beams_per_turn, 200U);
  ASSERT_TRUE(s.full_turn_s);
  EXPECT_NEAR(*s.full_turn_s, 10.0, 1e-9);  // 200 beams of 50 ms
  EXPECT_TRUE(s.bearings.full_circle);
  EXPECT_DOUBLE_EQ(s.bearings.span_deg, 360.0);
  EXPECT_NEAR(s.step_deg, 1.8, 1e-9);
  EXPECT_DOUBLE_EQ(s.sector_arc.span_deg, 0.0);
  ASSERT_EQ(s.settings.size(), 1U);
  EXPECT_EQ(s.settings[0].bins, 400U);
  EXPECT_NEAR(s.settings[0].reach_m, 5.0, 1e-12);
  EXPECT_FALSE(s.settings[0].setting.gain_setting);
  ASSERT_TRUE(s.followed_scale);
  EXPECT_EQ(s.followed_scale->beams, 400U);
  EXPECT_FALSE(s.nav);
}

TEST(sonarLogSummary, TurnCutByTheLogsEndIsPartial) {
  SonarLog log;
  addBeams(log, steps(0.0, 1.8, 300));
  const LogSummary s = summarizeLog(log);
  EXPECT_EQ(s.full_turns, 1U);
  EXPECT_EQ(s.partial_turns, 1U);
  EXPECT_EQ(s.sweeps.back().kind, SweepKind::kPartialTurn);
  EXPECT_NEAR(s.sweeps.back().span_deg, 99 * 1.8, 1e-6);
}

TEST(sonarLogSummary, SectorScanGivesSectorPassesAndTheirSpan) {
  // A 90° sector around bearing 0 (−45°…45°: it crosses the wrap), 0.9° steps, four passes.
  SonarLog log;
  addBeams(log, steps(-45.0, 0.9, 101));  // −45 … 45
  addBeams(log, steps(44.1, -0.9, 99));   // 44.1 … −44.1
  addBeams(log, steps(-45.0, 0.9, 101));  // −45 … 45
  addBeams(log, steps(44.1, -0.9, 99));
  const LogSummary s = summarizeLog(log);
  EXPECT_EQ(s.full_turns, 0U);
  EXPECT_EQ(s.partial_turns, 0U);
  EXPECT_EQ(s.sector_passes, s.sweeps.size());
  EXPECT_GE(s.sector_passes, 4U);
  EXPECT_EQ(s.sweeps.front().direction, 1);
  EXPECT_NEAR(s.sweeps.front().span_deg, 90.0, 1e-6);
  EXPECT_FALSE(s.sector_arc.full_circle);
  EXPECT_NEAR(s.sector_arc.span_deg, 90.0, 1e-6);
  EXPECT_NEAR(s.sector_arc.from_deg, 315.0, 1e-6);
  EXPECT_NEAR(s.sector_arc.to_deg, 45.0, 1e-6);
  EXPECT_FALSE(s.bearings.full_circle);
  EXPECT_NEAR(s.bearings.span_deg, 90.0, 1e-6);
  EXPECT_NEAR(s.step_deg, 0.9, 1e-9);
  EXPECT_FALSE(s.full_turn_s);
}

TEST(sonarLogSummary, SectorArcLeavesOutThePassIntoTheSector) {
  // Half a turn clockwise from 180° to 0°, then a 60° sector 0°…60° back and forth: the pass into
  // the sector ends in a reversal but is not part of the sector the head sweeps.
  SonarLog log;
  addBeams(log, steps(180.0, -1.8, 101));  // 180 … 0
  for (int pass = 0; pass < 3; ++pass) {
    addBeams(log, steps(1.8, 1.8, 33));  // 1.8 … 59.4 … 60 (the last step 0.6°: clamp at 60)
    addBeams(log, {60.0});
    addBeams(log, steps(58.2, -1.8, 33));  // 58.2 … 0.6
    addBeams(log, {0.0});
  }
  const LogSummary s = summarizeLog(log);
  EXPECT_EQ(s.full_turns, 0U);
  EXPECT_EQ(s.sweeps.front().kind, SweepKind::kSectorPass);  // it ends in a reversal
  EXPECT_NEAR(s.sector_arc.from_deg, 0.0, 1e-6);
  EXPECT_NEAR(s.sector_arc.to_deg, 60.0, 1e-6);
  EXPECT_NEAR(s.sector_arc.span_deg, 60.0, 1e-6);
  EXPECT_NEAR(s.bearings.span_deg, 180.0, 1e-6);
}

TEST(sonarLogSummary, RangeAndGainChangesListEachSettingInOrderOfFirstUse) {
  SonarLog log;
  addBeams(log, steps(0.0, 1.8, 50), 0.002, 1, 1000);    // 2 m at power-on, gain 1
  addBeams(log, steps(90.0, 1.8, 300), 0.01, 1, 1000);   // the user's 10 m
  addBeams(log, steps(270.0, 1.8, 100), 0.01, 2, 1000);  // gain raised
  addBeams(log, steps(90.0, 1.8, 10), 0.002, 1, 1000);   // back to 2 m for a moment
  for (std::size_t i = 50; i < 450; ++i) log.beams[i].pulse_length_m = i < 60 ? 0.045 : 0.04;  // the 10 m pings'
  const LogSummary s = summarizeLog(log);
  ASSERT_EQ(s.settings.size(), 3U);
  EXPECT_FALSE(s.settings[0].pulse_length_m);  // no 2 m beam records its pulse
  EXPECT_EQ(s.settings[1].pulse_length_m, 0.04);  // the shortest of the setting's beams
  EXPECT_EQ(s.settings[2].pulse_length_m, 0.04);
  const HeadSettingUse& two = s.settings[0];
  EXPECT_DOUBLE_EQ(two.setting.bin_length_m, 0.002);
  EXPECT_EQ(two.setting.gain_setting, 1);
  EXPECT_EQ(two.beams, 60U);
  EXPECT_EQ(two.first_beam, 0U);
  EXPECT_EQ(two.stretches, 2U);
  EXPECT_NEAR(two.reach_m, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(two.first_time_s, 0.0);
  EXPECT_NEAR(two.last_time_s, 459 * 0.1, 1e-9);
  const HeadSettingUse& ten = s.settings[1];
  EXPECT_DOUBLE_EQ(ten.setting.bin_length_m, 0.01);
  EXPECT_EQ(ten.setting.gain_setting, 1);
  EXPECT_EQ(ten.beams, 300U);
  EXPECT_EQ(ten.first_beam, 50U);
  EXPECT_EQ(ten.stretches, 1U);
  EXPECT_EQ(ten.bins, 1000U);
  EXPECT_NEAR(ten.reach_m, 10.0, 1e-12);
  EXPECT_NEAR(ten.first_time_s, 5.0, 1e-9);
  EXPECT_NEAR(ten.last_time_s, 34.9, 1e-9);
  const HeadSettingUse& gain = s.settings[2];
  EXPECT_EQ(gain.setting.gain_setting, 2);
  EXPECT_EQ(gain.beams, 100U);
  EXPECT_EQ(gain.first_beam, 350U);
  // Two range scales (bin lengths); the automatic resolution follows the 10 m one (400 beams).
  ASSERT_EQ(s.range_scales.size(), 2U);
  ASSERT_TRUE(s.followed_scale);
  EXPECT_DOUBLE_EQ(s.followed_scale->bin_length_m, 0.01);
  EXPECT_EQ(s.followed_scale->beams, 400U);
  EXPECT_NEAR(s.followed_scale->reach_m, 10.0, 1e-12);
  // Every change cuts a sweep: the only whole turn is the first 200 of the 300 beams at 10 m, gain 1.
  EXPECT_EQ(s.full_turns, 1U);
  EXPECT_EQ(s.partial_turns, s.sweeps.size() - 1);
}

TEST(sonarLogSummary, ShorterBeamsOfASettingGiveItsFewestBins) {
  SonarLog log;
  addBeams(log, steps(0.0, 1.8, 5), 0.0125, std::nullopt, 399);
  addBeams(log, {9.0}, 0.0125, std::nullopt, 186);
  const LogSummary s = summarizeLog(log);
  ASSERT_EQ(s.settings.size(), 1U);
  EXPECT_EQ(s.settings[0].bins, 399U);
  EXPECT_EQ(s.settings[0].min_bins, 186U);
}

TEST(sonarLogSummary, SkipReasonsDifferingInNumbersAreGrouped) {
  SonarLog log;
  addBeams(log, steps(0.0, 1.8, 3));
  log.skipped_beams = 4;
  log.skip_reasons = {"f.bin: byte 10 to byte 20: 11 bytes outside any message", "f.bin: record 3: time unreadable",
                      "f.bin: byte 300 to byte 3000: 2701 bytes outside any message",
                      "f.bin: byte 5000 to byte 5001: 2 bytes outside any message"};
  log.notes = {"f.bin: the clock wrapped once"};
  log.sonar = "Ping360 (firmware 3.1.1)";
  const LogSummary s = summarizeLog(log);
  EXPECT_EQ(s.skipped_beams, 4U);
  ASSERT_EQ(s.skip_reasons.size(), 2U);
  EXPECT_EQ(s.skip_reasons[0].count, 3U);
  EXPECT_EQ(s.skip_reasons[0].first_reason, log.skip_reasons[0]);
  EXPECT_EQ(s.skip_reasons[0].pattern, "f.bin: byte N to byte N: N bytes outside any message");
  EXPECT_EQ(s.skip_reasons[1].count, 1U);
  EXPECT_EQ(s.skip_reasons[1].first_reason, "f.bin: record 3: time unreadable");
  EXPECT_EQ(s.notes, log.notes);
  EXPECT_EQ(s.sonar, log.sonar);
}

TEST(sonarLogSummary, NavigationCoverageCountsTheBeamsOutsideTheTrack) {
  SonarLog log;
  addBeams(log, steps(0.0, 1.8, 100), 0.01, std::nullopt, 10, 0.125);  // times 0 … 12.375 s, exact in binary
  log.beams[50].time_s = std::numeric_limits<double>::quiet_NaN();
  NavTrack nav;
  for (int i = 1; i <= 8; ++i) {  // fixes at 1 … 8 s, moving 1 m east per second
    NavSample fix;
    fix.time_s = i;
    fix.position_ned_m = Eigen::Vector3d(0.0, i, 0.0);
    nav.push_back(fix);
  }
  const LogSummary s = summarizeLog(log, nav);
  ASSERT_TRUE(s.nav);
  EXPECT_EQ(s.nav->fixes, 8U);
  EXPECT_DOUBLE_EQ(s.nav->first_time_s, 1.0);
  EXPECT_DOUBLE_EQ(s.nav->last_time_s, 8.0);
  EXPECT_DOUBLE_EQ(s.nav->duration_s, 7.0);
  EXPECT_NEAR(s.nav->distance_m, 7.0, 1e-12);
  EXPECT_EQ(s.nav->beams_before, 8U);   // 0 … 0.875 s
  EXPECT_EQ(s.nav->beams_after, 35U);   // 8.125 … 12.375 s; 8 s itself is covered
  EXPECT_EQ(s.nav->beams_outside, 8U + 35U + 1U);  // and the NaN time
  EXPECT_FALSE(s.nav->coversBeams());
  // The NaN time is left out of the log's times.
  EXPECT_DOUBLE_EQ(s.first_time_s, 0.0);
  EXPECT_DOUBLE_EQ(s.last_time_s, 12.375);

  NavSample late = nav.back();
  late.time_s = 12.5;
  nav.push_back(late);
  nav.insert(nav.begin(), NavSample{});  // a fix at 0 s
  log.beams[50].time_s = 5.0;
  const LogSummary covered = summarizeLog(log, nav);
  ASSERT_TRUE(covered.nav);
  EXPECT_EQ(covered.nav->beams_outside, 0U);
  EXPECT_TRUE(covered.nav->coversBeams());
}

TEST(sonarLogSummary, EmptyLog) {
  SonarLog log;
  log.skipped_beams = 1;
  log.skip_reasons = {"x: nothing readable"};
  const LogSummary s = summarizeLog(log);
  EXPECT_EQ(s.beams, 0U);
  EXPECT_EQ(s.skipped_beams, 1U);
  EXPECT_EQ(s.skip_reasons.size(), 1U);
  EXPECT_DOUBLE_EQ(s.duration_s, 0.0);
  EXPECT_FALSE(s.beam_rate_hz);
  EXPECT_TRUE(s.sweeps.empty());
  EXPECT_EQ(s.full_turns + s.sector_passes + s.partial_turns, 0U);
  EXPECT_TRUE(s.settings.empty());
  EXPECT_TRUE(s.range_scales.empty());
  EXPECT_FALSE(s.followed_scale);
  EXPECT_FALSE(s.full_turn_s);
  EXPECT_DOUBLE_EQ(s.bearings.span_deg, 0.0);
  EXPECT_FALSE(s.nav);
  const LogSummary with_nav = summarizeLog(log, NavTrack{NavSample{}});
  ASSERT_TRUE(with_nav.nav);
  EXPECT_EQ(with_nav.nav->fixes, 1U);
  EXPECT_TRUE(with_nav.nav->coversBeams());
}

TEST(sonarLogSummary, CaptureWithoutClockHasNoRates) {
  SonarLog log;
  addBeams(log, steps(0.0, 1.8, 450), 0.01, std::nullopt, 10, 0.0);  // all at 0 s
  const LogSummary s = summarizeLog(log);
  EXPECT_EQ(s.full_turns, 2U);
  EXPECT_FALSE(s.beam_rate_hz);
  EXPECT_FALSE(s.full_turn_s);
  EXPECT_EQ(s.beams_per_turn, 200U);
}

TEST(sonarLogSummary, CrasTankLogIs28FullTurnsOfOneRangeScale) {
  const std::filesystem::path path = std::filesystem::path(SONARMAP_SHARED_DATA) / "cras_micron_tank_static.mat";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
  const SonarLog log = readCrasMat(path.string());
  const LogSummary s = summarizeLog(log);
  EXPECT_EQ(s.beams, log.beams.size());
  EXPECT_EQ(s.beams + s.skipped_beams, 5604U);  // ../shared/data/README.md
  EXPECT_EQ(s.full_turns, 28U);
  EXPECT_EQ(s.beams_per_turn, 200U);
  ASSERT_TRUE(s.full_turn_s);
  EXPECT_NEAR(*s.full_turn_s, 8.6, 0.2);
  EXPECT_TRUE(s.bearings.full_circle);
  EXPECT_NEAR(s.step_deg, 1.8, 1e-3);
  ASSERT_EQ(s.settings.size(), 1U);
  EXPECT_EQ(s.settings[0].bins, 399U);
  EXPECT_NEAR(s.settings[0].reach_m, 5.0, 0.01);
  EXPECT_EQ(s.range_scales.size(), 1U);
}

}  // namespace
}  // namespace sonarmap
