// Live mapping's provisional layer (ProvisionalBeams): beams integrated one by one into their
// sweep's map, drawn over a map, dropped when their sweep is committed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

#include "octree/octree_testing.hpp"
#include "sonarmap/core/errors.hpp"
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
  const SweepCalibration calibration = detector.sweepCalibration(polar);
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

}  // namespace
}  // namespace sonarmap
