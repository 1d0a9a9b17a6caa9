/// Tests of a live run's recording (dive_recorder.hpp): beams and fixes read back by `map`'s
/// readers bit for bit, with what the head reported; a run that ends without finishing leaves its
/// partial file and no log; times as they come back.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/formats/dive_recorder.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"

namespace sonarmap {
namespace {

/// A moving mission on a clock of seconds since 1970, its times as a recording gives them back.
MissionRun recordableMission() {
  MissionRun run = simulateMission(SimulatedMission{"micron", "quay3d", "tilted-loop"});
  for (Beam& beam : run.simulation.log.beams) beam.time_s = DiveRecorder::recordedTime(beam.time_s + 1.79e9 + 1e-4 / 3);
  for (NavSample& fix : run.simulation.nav) fix.time_s = DiveRecorder::recordedTime(fix.time_s + 1.79e9 + 1e-4 / 3);
  return run;
}

TEST(formatsDiveRecorder, BeamsAndFixesReadBackBitForBit) {
  const test::TempDir dir;
  MissionRun run = recordableMission();
  SonarLog& written = run.simulation.log;
  // What heads report: a gain setting, a pulse, an intensity span; and a beam that reports none.
  for (std::size_t i = 0; i < written.beams.size(); ++i) {
    if (i % 3 == 0) written.beams[i].gain_setting = static_cast<int>(i % 7);
    if (i % 5 == 0) written.beams[i].pulse_length_m = 0.0123456789;
    if (i % 2 == 0) written.beams[i].intensity_span_db = 80.0 * 149 / 255;
  }
  const std::string path = dir.file("dive.mcap");
  {
    DiveRecorder recorder(path, {.chunk_bytes = 64 * 1024});
    recorder.addMetadata("sonarmap.head", {{"head", "Ping360"}, {"range_m", "50"}});
    std::size_t f = 0;
    const NavTrack& nav = run.simulation.nav;
    for (const Beam& beam : written.beams) {  // interleaved as a live run receives them
      while (f < nav.size() && nav[f].time_s <= beam.time_s + 0.05) recorder.addNavFix(nav[f++]);
      recorder.addBeam(beam);
    }
    while (f < nav.size()) recorder.addNavFix(nav[f++]);
    EXPECT_TRUE(std::filesystem::exists(recorder.partialPath()));
    EXPECT_FALSE(std::filesystem::exists(path));
    recorder.finish();
    EXPECT_EQ(recorder.beams(), written.beams.size());
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".part"));
  const SonarLog read = readSonarLog(path);
  ASSERT_EQ(read.beams.size(), written.beams.size());
  for (std::size_t i = 0; i < read.beams.size(); ++i) {
    const Beam& a = read.beams[i];
    const Beam& b = written.beams[i];
    ASSERT_EQ(a.time_s, b.time_s) << i;
    ASSERT_EQ(a.bearing_rad, b.bearing_rad) << i;
    ASSERT_EQ(a.bin_length_m, b.bin_length_m) << i;
    ASSERT_EQ(a.intensities, b.intensities) << i;
    ASSERT_EQ(a.gain_setting, b.gain_setting) << i;
    ASSERT_EQ(a.pulse_length_m, b.pulse_length_m) << i;
    ASSERT_EQ(a.intensity_span_db, b.intensity_span_db) << i;
  }
  const std::optional<RosBagNavigation> nav = readRosBagNavigation(path);
  ASSERT_TRUE(nav.has_value());
  EXPECT_EQ(nav->frame, "NED");
  ASSERT_EQ(nav->track.size(), run.simulation.nav.size());
  for (std::size_t i = 0; i < nav->track.size(); ++i) {
    const NavSample& a = nav->track[i];
    const NavSample& b = run.simulation.nav[i];
    ASSERT_EQ(a.time_s, b.time_s);
    ASSERT_EQ(a.position_ned_m, b.position_ned_m);
    ASSERT_EQ(a.roll_rad, b.roll_rad);
    ASSERT_EQ(a.pitch_rad, b.pitch_rad);
    ASSERT_EQ(a.yaw_rad, b.yaw_rad);
  }
}

TEST(formatsDiveRecorder, ARunEndedWithoutFinishingLeavesItsPartialFileOnly) {
  const test::TempDir dir;
  const std::string path = dir.file("dive.mcap");
  std::ofstream(path) << "an older log stays untouched";
  const MissionRun run = recordableMission();
  {
    DiveRecorder recorder(path, {.chunk_bytes = 16 * 1024});
    for (std::size_t i = 0; i < 500; ++i) recorder.addBeam(run.simulation.log.beams[i]);
    recorder.flush();
  }
  EXPECT_GT(std::filesystem::file_size(path + ".part"), 16U * 1024U);
  std::ifstream old(path);
  std::string text;
  std::getline(old, text);
  EXPECT_EQ(text, "an older log stays untouched");
}

TEST(formatsDiveRecorder, TimesComeBackAsTheReadersComputeThem) {
  EXPECT_EQ(DiveRecorder::recordedTime(1.79e9 + 0.25), 1.79e9 + 0.25);
  const double t = DiveRecorder::recordedTime(1790000000.123456789123);
  EXPECT_NEAR(t, 1790000000.123456789, 1e-6);
  EXPECT_EQ(DiveRecorder::recordedTime(t), t);  // a recorded time is recorded as itself
  EXPECT_EQ(DiveRecorder::recordedTime(1.79e9 + 0.9999999999), 1.79e9 + 1.0);
  EXPECT_THROW(DiveRecorder::recordedTime(-1.0), ValueError);
  EXPECT_THROW(DiveRecorder::recordedTime(std::nan("")), ValueError);
  EXPECT_THROW(DiveRecorder::recordedTime(3e9), ValueError);
}

TEST(formatsDiveRecorder, RefusesAFolderThatIsNotThere) {
  EXPECT_THROW(DiveRecorder("/nonexistent-folder/dive.mcap"), FileError);
}

}  // namespace
}  // namespace sonarmap
