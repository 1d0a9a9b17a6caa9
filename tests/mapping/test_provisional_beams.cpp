// Live mapping's provisional layer (ProvisionalBeams; OnlineMapper with
// OnlineIntegration::kProvisionalBeams): each beam is shown as it arrives and dropped when its sweep
// is committed; the committed map is mapSonarLog's map of the sweeps final so far at every moment,
// and the final map is mapSonarLog's (live = batch), on simulated runs with navigation and on every
// shared log.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <iostream>
#include <string>
#include <optional>
#include <vector>

#include "octree/octree_testing.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/mapping/provisional_beams.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {
namespace {

using testing::leavesOf;

/// `turns` turns of the simulated Micron in the tank, moving north at 0.1 m/s while turning.
MsisSimulation movingRun(std::size_t turns) {
  MsisSimulationOptions options;
  options.turns = turns;
  options.trajectory = constantVelocityTrajectory(NavSample{}, Eigen::Vector3d(0.1, 0.0, 0.0), 0.02);
  return simulateMsis(builtinScene("tank"), options);
}

MapperOptions atTwoCentimetres() {
  MapperOptions options;
  options.resolution_m = 0.02;
  return options;
}

/// The run's beams [first, last) as ProvisionalBeams takes them: detected one by one with the
/// calibration of the run's first sweep, placed by the run's navigation.
struct DetectedRows {
  std::vector<PolarImage> rows;
  std::vector<BeamDetection> detections;
  std::vector<std::optional<Eigen::Isometry3d>> poses;
};

DetectedRows detectedRows(const MsisSimulation& run, std::size_t first, std::size_t last) {
  const SonarMapper detector(atTwoCentimetres());
  const SweepRange sweep = splitSweeps(run.log.beams).front();
  PolarImage polar = makePolarImage(run.log.beams, sweep.first, sweep.last_exclusive);
  const SweepCalibration calibration = detector.detectSweep(polar).calibration;
  const NavInterpolator navigation(run.nav);
  DetectedRows out;
  for (std::size_t i = first; i < last; ++i) {
    PolarImage row = makePolarImage(run.log.beams, i, i + 1);
    out.detections.push_back(detector.detectRows(row, calibration).detections.front());
    out.rows.push_back(std::move(row));
    const std::optional<Eigen::Isometry3d> body = navigation.bodyToNedAt(run.log.beams[i].time_s);
    out.poses.push_back(nedToMap() * *body * defaultSonarToBody());
  }
  return out;
}

/// A layer of beams [first, last) of `rows` (beam k of `rows` is the stream's beam `offset` + k), a
/// new sweep at each index in `sweep_starts`.
ProvisionalBeams layerOf(const DetectedRows& rows, std::size_t offset, std::size_t first, std::size_t last,
                         const std::vector<std::size_t>& sweep_starts, double resolution_m = 0.02) {
  ProvisionalBeams layer(atTwoCentimetres());
  layer.atResolution(resolution_m);
  for (std::size_t i = first; i < last; ++i) {
    const bool starts = std::find(sweep_starts.begin(), sweep_starts.end(), i) != sweep_starts.end();
    layer.add(i, starts, rows.rows[i - offset], rows.detections[i - offset], rows.poses[i - offset]);
  }
  return layer;
}

OcTree16 overlaid(const ProvisionalBeams& layer, double resolution_m = 0.02) {
  OcTree16 map(resolution_m);
  layer.overlay(map);
  return map;
}

// One sweep of the layer drawn on an empty map is the map of its beams, each integrated on its own.
TEST(mappingProvisionalBeams, OverlayOnAnEmptyMapIsTheBeamsIntegratedOneByOne) {
  const MsisSimulation run = movingRun(2);
  const DetectedRows rows = detectedRows(run, 200, 260);
  SonarMapper alone(atTwoCentimetres());
  for (std::size_t k = 0; k < rows.rows.size(); ++k) alone.integrateBeams(rows.rows[k], {rows.detections[k]}, {rows.poses[k]});
  const ProvisionalBeams layer = layerOf(rows, 200, 200, 260, {200});
  EXPECT_EQ(layer.size(), 60U);
  ASSERT_GT(alone.map().counts().leaves, 100U);
  EXPECT_EQ(leavesOf(overlaid(layer)), leavesOf(alone.map()));
}

// Dropping the beams a committed sweep holds: whole sweeps go, a sweep cut by the boundary is
// integrated again from its remaining beams.
TEST(mappingProvisionalBeams, DroppedBeamsLeaveTheLayer) {
  const MsisSimulation run = movingRun(2);
  const DetectedRows rows = detectedRows(run, 200, 260);
  ProvisionalBeams layer = layerOf(rows, 200, 200, 260, {200, 230});
  layer.dropBefore(230);
  EXPECT_EQ(layer.size(), 30U);
  EXPECT_EQ(leavesOf(overlaid(layer)), leavesOf(overlaid(layerOf(rows, 200, 230, 260, {230}))));
  layer.dropBefore(245);
  EXPECT_EQ(layer.size(), 15U);
  EXPECT_EQ(leavesOf(overlaid(layer)), leavesOf(overlaid(layerOf(rows, 200, 245, 260, {245}))));
  layer.dropBefore(260);
  EXPECT_EQ(layer.size(), 0U);
  EXPECT_TRUE(overlaid(layer).empty());
}

// The committed map coarsened (a longer range scale): the beams shown are integrated again at its
// resolution.
TEST(mappingProvisionalBeams, ANewResolutionIntegratesTheShownBeamsAgain) {
  const MsisSimulation run = movingRun(2);
  const DetectedRows rows = detectedRows(run, 200, 240);
  ProvisionalBeams layer = layerOf(rows, 200, 200, 240, {200});
  layer.atResolution(0.04);
  EXPECT_EQ(leavesOf(overlaid(layer, 0.04)), leavesOf(overlaid(layerOf(rows, 200, 200, 240, {200}, 0.04), 0.04)));
  OcTree16 finer(0.02);
  EXPECT_THROW(layer.overlay(finer), ValueError);
}

TEST(mappingProvisionalBeams, MisuseIsRefused) {
  const MsisSimulation run = movingRun(1);
  const DetectedRows rows = detectedRows(run, 10, 12);
  ProvisionalBeams layer(atTwoCentimetres());
  EXPECT_THROW(layer.add(10, true, rows.rows[0], rows.detections[0], rows.poses[0]), ValueError);  // no resolution
  EXPECT_THROW(layer.atResolution(0.0), ValueError);
  layer.atResolution(0.02);
  layer.add(10, true, rows.rows[0], rows.detections[0], rows.poses[0]);
  EXPECT_THROW(layer.add(10, false, rows.rows[1], rows.detections[1], rows.poses[1]), ValueError);  // not after
  PolarImage two = makePolarImage(run.log.beams, 11, 13);
  EXPECT_THROW(layer.add(11, false, two, rows.detections[1], rows.poses[1]), ValueError);  // not one beam
  OcTree16 empty(0.02);
  layer.dropBefore(11);
  layer.overlay(empty);
  EXPECT_TRUE(empty.empty());
}

// The default live integration on a moving run, each fix given as soon as its time has come and the
// next one too: after the first sweep every beam is shown on arrival, the committed map equals
// mapSonarLog's map of the beams of the sweeps committed so far after every beam, and the final
// map (committed and shown) is the batch's.
TEST(mappingProvisionalBeams, LiveEqualsBatchAtEveryCommitAndAtTheEnd) {
  const MsisSimulation run = movingRun(4);
  const std::vector<SweepRange> sweeps = splitSweeps(run.log.beams);
  const Eigen::Isometry3d mounting = defaultSonarToBody();
  OnlineMapper live(atTwoCentimetres(), mounting, OnlineIntegration::kProvisionalBeams);
  std::size_t next_fix = 0, unshown_after_first_sweep = 0, commits_checked = 0, shown_more = 0;
  for (std::size_t i = 0; i < run.log.beams.size(); ++i) {
    const Beam& beam = run.log.beams[i];
    while (next_fix < run.nav.size() && run.nav[next_fix].time_s <= beam.time_s) live.addNavFix(run.nav[next_fix++]);
    if (next_fix < run.nav.size()) live.addNavFix(run.nav[next_fix++]);
    const std::size_t sweeps_before = live.sweepsIntegrated();
    live.addBeam(beam);
    if (i >= sweeps[1].first + 20) unshown_after_first_sweep += live.beamsUnshown();  // 20: min_beams
    if (live.sweepsIntegrated() > sweeps_before) {
      SonarLog committed;
      committed.beams.assign(run.log.beams.begin(), run.log.beams.begin() + static_cast<std::ptrdiff_t>(i + 1 - live.beamsPending()));
      EXPECT_EQ(leavesOf(live.mapSnapshot()), leavesOf(mapSonarLog(committed, run.nav, mounting, atTwoCentimetres()).map()))
          << "after beam " << i;
      ++commits_checked;
    }
    shown_more += live.shownSnapshot().counts().leaves != live.mapSnapshot().counts().leaves ? 1 : 0;
  }
  EXPECT_EQ(unshown_after_first_sweep, 0U);
  EXPECT_EQ(commits_checked, 3U);  // the last turn ends with the stream
  EXPECT_GT(shown_more, sweeps[1].size());
  live.finish();
  const SonarMapper batch = mapSonarLog(run.log, run.nav, mounting, atTwoCentimetres());
  EXPECT_EQ(live.beamsPending(), 0U);
  EXPECT_EQ(live.beamsUnshown(), 0U);
  EXPECT_EQ(leavesOf(live.mapper().map()), leavesOf(batch.map()));
  EXPECT_EQ(leavesOf(live.shownSnapshot()), leavesOf(batch.map()));
  EXPECT_EQ(live.mapper().stats().beams_used, batch.stats().beams_used);
}

// A beam is shown once the navigation covers it (a fix at or after its time), in order.
// A beam after the last fix is shown at that fix's pose for up to a second (the navigation lags the
// sonar); later ones wait for a fix, and are shown when it comes.
TEST(mappingProvisionalBeams, ABeamWaitsForTheNavigationThatCoversIt) {
  const MsisSimulation run = movingRun(3);
  const std::vector<SweepRange> sweeps = splitSweeps(run.log.beams);
  OnlineMapper live(atTwoCentimetres(), defaultSonarToBody(), OnlineIntegration::kProvisionalBeams);
  const std::size_t last = sweeps[1].first + 60;
  double covered_s = 0.0;
  for (const NavSample& fix : run.nav) {
    if (fix.time_s > run.log.beams[last - 50].time_s) break;  // 50 beams, about 2.1 s, before the last
    live.addNavFix(fix);
    covered_s = fix.time_s;
  }
  std::size_t held = 0, waiting = 0;
  for (std::size_t i = 0; i < last; ++i) {
    live.addBeam(run.log.beams[i]);
    const double after_s = run.log.beams[i].time_s - covered_s;
    held += after_s > 0.0 && after_s <= 1.0 ? 1 : 0;
    waiting += after_s > 1.0 ? 1 : 0;
  }
  EXPECT_EQ(live.sweepsIntegrated(), 1U);
  ASSERT_GE(held, 10U);
  ASSERT_GE(waiting, 10U);
  EXPECT_EQ(live.beamsUnshown(), waiting);  // shown at the held pose: those within a second of the last fix
  for (const NavSample& fix : run.nav) {
    if (fix.time_s > covered_s) live.addNavFix(fix);
  }
  EXPECT_EQ(live.beamsUnshown(), 0U);
  EXPECT_EQ(live.beamsPending(), 60U);
}

// Every shared log fed beam by beam in the default live integration: mapSonarLog's map leaf for
// leaf at a given resolution (range changes, power-on pings, a sector head, a ROS bag, the CRAS
// .mat), the beams shown before their sweep is committed counted.
TEST(mappingProvisionalBeams, SharedLogsEndOnTheBatchMap) {
  const struct {
    const char* file;
    double resolution_m;
  } logs[] = {{"cras_micron_tank_static.mat", 0.02},    {"seanet_sector_target.V4LOG", 0.05},
              {"micron_pool_ros1.bag", 0.05},           {"ping360_basin.bin", 0.1},
              {"ping360_harbour_range_changes.bin", 0.1}};
  for (const auto& [file, resolution_m] : logs) {
    const std::string path = std::string(SONARMAP_SHARED_DATA) + "/" + file;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
    const SonarLog log = readSonarLog(path);
    MapperOptions options;
    options.resolution_m = resolution_m;
    const SonarMapper batch = mapSonarLog(log, options);
    OnlineMapper live(options, OnlineIntegration::kProvisionalBeams);
    std::size_t shown_early = 0;
    for (const Beam& beam : log.beams) {
      live.addBeam(beam);
      shown_early += live.beamsUnshown() == 0 && live.beamsPending() > 0 ? 1 : 0;
    }
    live.finish();
    EXPECT_EQ(leavesOf(live.mapper().map()), leavesOf(batch.map())) << file;
    EXPECT_EQ(leavesOf(live.shownSnapshot()), leavesOf(batch.map())) << file;
    std::cout << file << ": " << shown_early << " of " << log.beams.size()
              << " beams shown on arrival before their sweep was committed\n";
    EXPECT_GT(shown_early, log.beams.size() / 2) << file;
  }
}

}  // namespace
}  // namespace sonarmap
