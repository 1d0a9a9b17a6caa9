// OnlineMapper: beams fed one at a time give mapSonarLog's map (the batch is a loop over it), a
// sweep is integrated as soon as it is final and the navigation covers it, the map can be read
// from another thread while beams arrive, and bad input is refused (the provisional layer:
// test_provisional_beams.cpp).
#include <gtest/gtest.h>

#include <atomic>
#include <iostream>
#include <cstddef>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {
namespace {

/// Three turns of the simulated Micron in the tank, moving north at 0.1 m/s while turning.
MsisSimulation movingRun(std::size_t turns = 3) {
  MsisSimulationOptions options;
  options.turns = turns;
  options.trajectory = constantVelocityTrajectory(NavSample{}, Eigen::Vector3d(0.1, 0.0, 0.0), 0.02);
  return simulateMsis(builtinScene("tank"), options);
}

std::vector<std::tuple<Key16, int, float>> leavesOf(const OcTree16& map) {
  std::vector<std::tuple<Key16, int, float>> leaves;
  map.forEachLeaf([&](const LeafView<16>& leaf) { leaves.emplace_back(leaf.key, leaf.depth, leaf.log_odds); });
  return leaves;
}

MapperOptions atTwoCentimetres(bool pipeline) {
  MapperOptions options;
  options.resolution_m = 0.02;
  options.pipeline_detection = pipeline;
  return options;
}

// Fed beam by beam, with the fixes first or interleaved with the beams (each fix as soon as its
// time has come), with or without pipelined detection, one or three sweeps detected ahead: the
// batch's map, leaf for leaf.
TEST(mappingOnlineMapper, BeamByBeamGivesTheBatchMap) {
  const MsisSimulation run = movingRun();
  const Eigen::Isometry3d mounting = defaultSonarToBody();
  const SonarMapper batch = mapSonarLog(run.log, run.nav, mounting, atTwoCentimetres(true));
  const auto expected = leavesOf(batch.map());
  ASSERT_GT(expected.size(), 1000U);
  for (const auto& [pipeline, ahead] : {std::pair{false, 1U}, std::pair{true, 1U}, std::pair{true, 3U}}) {
    OnlineMapper online(atTwoCentimetres(pipeline), mounting);
    online.setDetectionsAhead(ahead);
    std::size_t next_fix = 0;
    for (const Beam& beam : run.log.beams) {
      while (next_fix < run.nav.size() && run.nav[next_fix].time_s <= beam.time_s) online.addNavFix(run.nav[next_fix++]);
      online.addBeam(beam);
    }
    while (next_fix < run.nav.size()) online.addNavFix(run.nav[next_fix++]);
    online.finish();
    EXPECT_EQ(online.sweepsIntegrated(), batch.stats().sweeps) << "pipeline " << pipeline << ", ahead " << ahead;
    EXPECT_EQ(online.beamsPending(), 0U);
    EXPECT_EQ(leavesOf(online.mapper().map()), expected) << "pipeline " << pipeline << ", ahead " << ahead;
    EXPECT_EQ(online.mapper().stats().beams_used, batch.stats().beams_used);
  }
}

// A live stream that falls silent (commitHeld) has the batch's map without finish(): the sweep
// being received is committed as finish() would, and the mapper still takes beams afterwards.
TEST(mappingOnlineMapper, CommittingHeldBeamsAtSilenceGivesTheBatchMap) {
  const MsisSimulation run = movingRun(2);
  const Eigen::Isometry3d mounting = defaultSonarToBody();
  const SonarMapper batch = mapSonarLog(run.log, run.nav, mounting, atTwoCentimetres(false));
  OnlineMapper online(atTwoCentimetres(false), mounting);
  for (const NavSample& fix : run.nav) online.addNavFix(fix);
  for (const Beam& beam : run.log.beams) online.addBeam(beam);
  ASSERT_GT(online.beamsPending(), 0U);  // the last sweep waits for the next one
  online.commitHeld(true);
  EXPECT_EQ(online.beamsPending(), 0U);
  EXPECT_EQ(online.sweepsIntegrated(), batch.stats().sweeps);
  EXPECT_EQ(leavesOf(online.mapSnapshot()), leavesOf(batch.map()));
  online.commitHeld(true);  // nothing held: nothing changes
  EXPECT_EQ(online.sweepsIntegrated(), batch.stats().sweeps);
  Beam again = run.log.beams.front();
  again.time_s = run.nav.back().time_s;
  EXPECT_NO_THROW(online.addBeam(again));  // unlike finish(), beams may follow
  EXPECT_EQ(online.beamsPending(), 1U);
}

// With three sweeps detected ahead, a sweep waits for three more to be final, then is
// integrated; none is detected ahead is refused.
TEST(mappingOnlineMapper, SweepsDetectedAheadWaitForTheirTurn) {
  const MsisSimulation run = movingRun(5);
  const std::vector<SweepRange> sweeps = splitSweeps(run.log.beams);
  ASSERT_EQ(sweeps.size(), 5U);
  OnlineMapper online(atTwoCentimetres(true));
  EXPECT_THROW(online.setDetectionsAhead(0), ValueError);
  online.setDetectionsAhead(3);
  const std::size_t min_beams = static_cast<std::size_t>(atTwoCentimetres(true).detector.background.min_beams);
  // Sweeps 0..3 final (sweep 4 has its min_beams beams): four in detection, the first integrated.
  for (std::size_t i = 0; i < sweeps[4].first + min_beams; ++i) online.addBeam(run.log.beams[i]);
  EXPECT_EQ(online.sweepsIntegrated(), 1U);
  online.finish();
  EXPECT_EQ(online.sweepsIntegrated(), 5U);
}

// Without pipelining a sweep is integrated once the next sweep has the detector's min_beams
// beams (it can no longer be joined to it), not at the end of the stream.
TEST(mappingOnlineMapper, SweepIsIntegratedWhenTheNextOneCannotJoinIt) {
  const MsisSimulation run = movingRun(2);
  MapperOptions options = atTwoCentimetres(false);
  const std::size_t min_beams = static_cast<std::size_t>(options.detector.background.min_beams);
  const std::vector<SweepRange> sweeps = splitSweeps(run.log.beams);
  ASSERT_EQ(sweeps.size(), 2U);
  OnlineMapper online(options);
  for (std::size_t i = 0; i < sweeps[1].first + min_beams - 1; ++i) online.addBeam(run.log.beams[i]);
  EXPECT_EQ(online.sweepsIntegrated(), 0U);  // the second sweep might still end short
  EXPECT_EQ(online.beamsPending(), sweeps[1].first + min_beams - 1);
  online.addBeam(run.log.beams[sweeps[1].first + min_beams - 1]);
  EXPECT_EQ(online.sweepsIntegrated(), 1U);
  EXPECT_EQ(online.beamsPending(), min_beams);
  EXPECT_GT(online.mapSnapshot().counts().leaves, 100U);
  online.finish();
  EXPECT_EQ(online.sweepsIntegrated(), 2U);
}

// With navigation a final sweep waits for a fix at or after its last beam.
TEST(mappingOnlineMapper, SweepWaitsForNavigationThatCoversIt) {
  const MsisSimulation run = movingRun(2);
  const std::vector<SweepRange> sweeps = splitSweeps(run.log.beams);
  OnlineMapper online(atTwoCentimetres(false), defaultSonarToBody());
  online.addNavFix(run.nav.front());
  for (const Beam& beam : run.log.beams) online.addBeam(beam);
  EXPECT_EQ(online.sweepsIntegrated(), 0U);  // the first sweep is final, but not covered
  const double first_sweep_end_s = run.log.beams[sweeps[0].last_exclusive - 1].time_s;
  for (const NavSample& fix : run.nav) {
    if (fix.time_s <= run.nav.front().time_s) continue;
    online.addNavFix(fix);
    if (fix.time_s < first_sweep_end_s) {
      EXPECT_EQ(online.sweepsIntegrated(), 0U);
    }
  }
  EXPECT_EQ(online.sweepsIntegrated(), 1U);
  online.finish();
  EXPECT_EQ(online.sweepsIntegrated(), 2U);
  EXPECT_EQ(online.mapper().stats().beams_without_nav, 0U);
}

// A second thread reads the map while beams arrive: every snapshot is a whole number of sweeps
// (its known voxels never shrink), and the last equals the final map.
TEST(mappingOnlineMapper, MapCanBeReadFromAnotherThreadWhileBeamsArrive) {
  const MsisSimulation run = movingRun();
  OnlineMapper online(atTwoCentimetres(true), defaultSonarToBody());
  for (const NavSample& fix : run.nav) online.addNavFix(fix);
  std::atomic<bool> done{false};
  std::size_t snapshots = 0;
  bool shrank = false;
  std::thread reader([&] {
    std::size_t previous = 0;
    while (!done.load()) {
      const OcTree16 map = online.mapSnapshot();
      std::size_t known = 0;
      map.forEachLeaf([&](const LeafView<16>& leaf) { known += static_cast<std::size_t>(leaf.edgeVoxels()) * leaf.edgeVoxels(); });
      shrank = shrank || known < previous;
      previous = known;
      ++snapshots;
      std::this_thread::yield();
    }
  });
  for (const Beam& beam : run.log.beams) online.addBeam(beam);
  online.finish();
  done = true;
  reader.join();
  EXPECT_GT(snapshots, 0U);
  EXPECT_FALSE(shrank);
  EXPECT_EQ(leavesOf(online.mapSnapshot()), leavesOf(online.mapper().map()));
  EXPECT_EQ(online.statsSnapshot().sweeps, 3U);
}

TEST(mappingOnlineMapper, BadInputIsRefused) {
  OnlineMapper still(atTwoCentimetres(false));
  EXPECT_THROW(still.addNavFix(NavSample{}), ValueError);  // no navigation constructor
  Beam beam;
  beam.bin_length_m = 0.0;
  beam.intensities.assign(10, 0);
  EXPECT_THROW(still.addBeam(beam), ValueError);
  beam.bin_length_m = 0.01;
  // What the head recorded is unset when not recorded, and valid when set: a NaN is no span.
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), 0.0, -1.0, std::numeric_limits<double>::infinity()}) {
    Beam with_span = beam;
    with_span.intensity_span_db = bad;
    EXPECT_THROW(still.addBeam(with_span), ValueError);
    Beam with_pulse = beam;
    with_pulse.pulse_length_m = bad;
    EXPECT_THROW(still.addBeam(with_pulse), ValueError);
  }
  still.addBeam(beam);
  still.finish();
  EXPECT_THROW(still.addBeam(beam), ValueError);  // after finish()

  OnlineMapper moving(atTwoCentimetres(false), defaultSonarToBody());
  NavSample fix;
  fix.time_s = 1.0;
  moving.addNavFix(fix);
  EXPECT_THROW(moving.addNavFix(fix), ValueError);  // not after the previous one
  fix.time_s = 2.0;
  fix.yaw_rad = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(moving.addNavFix(fix), ValueError);
  Eigen::Isometry3d broken = Eigen::Isometry3d::Identity();
  broken(0, 0) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(OnlineMapper(atTwoCentimetres(false), broken), ValueError);

  // Beams to show only: with kProvisionalBeams, never mixed with addBeam, in increasing order.
  Beam valid;
  valid.bin_length_m = 0.01;
  valid.intensities.assign(10, 0);
  OnlineMapper sweeps_only(atTwoCentimetres(false), defaultSonarToBody());
  EXPECT_THROW(sweeps_only.showBeam(0, valid), ValueError);
  OnlineMapper fed(atTwoCentimetres(false), defaultSonarToBody(), OnlineIntegration::kProvisionalBeams);
  fed.addBeam(valid);
  EXPECT_THROW(fed.showBeam(1, valid), ValueError);
  OnlineMapper shows(atTwoCentimetres(false), defaultSonarToBody(), OnlineIntegration::kProvisionalBeams);
  shows.showBeam(3, valid);
  EXPECT_THROW(shows.showBeam(3, valid), ValueError);  // not after the previous one
  EXPECT_THROW(shows.addBeam(valid), ValueError);
  valid.bin_length_m = 0.0;
  EXPECT_THROW(shows.showBeam(4, valid), ValueError);
  EXPECT_EQ(shows.beamsUnshown(), 1U);  // no calibration yet
  EXPECT_TRUE(shows.shownSnapshot().empty());
}

}  // namespace
}  // namespace sonarmap
