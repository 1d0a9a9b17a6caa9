// The sonar mapper on synthetic sweeps: free space to the first obstacle, the obstacle occupied,
// beams without an obstacle, per-sweep deduplication, the beam fan and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sonarmap/mapping/sonar_mapper.hpp"
#include "polar_fixtures.hpp"

namespace sonarmap {
namespace {

constexpr double kBin = 0.02;

/// A sweep of `beams` beams over a full turn, all with `bins` bins of 2 cm.
PolarImage makeSweep(int beams, int bins) { return testing::makeFullTurnSweep(beams, bins, kBin); }

/// An obstacle whose leading edge is at the centre of `bin` (2 cm bins).
BeamDetection obstacleAt(int bin, std::uint8_t intensity = 200) { return {bin, intensity, (bin + 0.5) * kBin}; }

/// No obstacle, and the beam's echo shows water up to `water_m` (detection.hpp).
BeamDetection noObstacle(double water_m) {
  BeamDetection detection;
  detection.water_range_m = water_m;
  return detection;
}

/// 2 cm voxels, no range tolerance: free space ends at the obstacle's voxel.
MapperOptions fanOptions() {
  MapperOptions options;
  options.resolution_m = 0.02;
  options.range_tolerance_m = 0.0;
  return options;
}

MapperOptions singleRay() {
  MapperOptions options = fanOptions();
  options.beam_width_rad = 0.0;
  return options;
}

Occupancy at(const SonarMapper& mapper, double x, double y) { return mapper.map().occupancyAt({x, y, 0.0}); }

TEST(mappingSonarMapper, FreeUpToTheObstacleWhichIsOccupied) {
  SonarMapper mapper(singleRay());
  PolarImage polar = makeSweep(4, 150);
  std::vector<BeamDetection> detections(4, obstacleAt(99, 200));  // 2.0 m: bin 99 spans 1.98–2.00
  mapper.integrateSweep(polar, detections);
  EXPECT_EQ(at(mapper, 1.0, 0.01), Occupancy::kFree);
  EXPECT_EQ(at(mapper, 1.99, 0.01), Occupancy::kOccupied);
  EXPECT_EQ(at(mapper, 2.5, 0.01), Occupancy::kUnknown);  // behind the obstacle: never seen
  EXPECT_EQ(at(mapper, 0.01, 1.5), Occupancy::kFree);     // beam at 90°
  EXPECT_EQ(mapper.stats().obstacles, 4U);
  EXPECT_EQ(mapper.stats().beams_used, 4U);
  EXPECT_EQ(mapper.stats().occupied_updates, 4U);
}

TEST(mappingSonarMapper, BeamWithoutObstacleClearsToItsRangeOnly) {
  SonarMapper mapper(singleRay());
  PolarImage polar = makeSweep(1, 100);  // 2 m of bins
  mapper.integrateSweep(polar, {noObstacle(2.0)});
  EXPECT_EQ(at(mapper, 1.9, 0.01), Occupancy::kFree);
  EXPECT_EQ(at(mapper, 2.1, 0.01), Occupancy::kUnknown);
  EXPECT_EQ(mapper.stats().obstacles, 0U);
  EXPECT_EQ(mapper.stats().occupied_updates, 0U);
}

// The no-echo rule: a beam without an obstacle clears only as far as its echo shows water (a weak
// echo it did not accept, or the minimum range when it shows nothing beyond it, stops it).
TEST(mappingSonarMapper, BeamWithoutObstacleClearsOnlyWhereItsEchoShowsWater) {
  SonarMapper mapper(singleRay());
  PolarImage polar = makeSweep(2, 100);  // 2 m of bins
  polar.bearing_rad = {0.0, std::numbers::pi / 2};
  mapper.integrateSweep(polar, {noObstacle(1.0), noObstacle(0.0)});
  EXPECT_EQ(at(mapper, 0.9, 0.01), Occupancy::kFree);
  EXPECT_EQ(at(mapper, 1.5, 0.01), Occupancy::kUnknown);  // beyond its water: a wall may stand there
  EXPECT_EQ(at(mapper, 0.01, 0.5), Occupancy::kUnknown);  // the second beam proved nothing
}

// OctoMap's maxrange: a beam longer than max_range_m clears up to it, its far obstacle dropped.
TEST(mappingSonarMapper, BeamsAreUsedUpToTheMaxRangeOnly) {
  MapperOptions options = singleRay();
  options.max_range_m = 1.5;
  SonarMapper mapper(options);
  PolarImage polar = makeSweep(2, 150);  // 3 m of bins
  mapper.integrateSweep(polar, {obstacleAt(99, 200), obstacleAt(40, 200)});  // 2.0 m, 0.81 m
  EXPECT_EQ(at(mapper, 1.4, 0.01), Occupancy::kFree);
  EXPECT_EQ(at(mapper, 1.99, 0.01), Occupancy::kUnknown);  // beyond the limit: not occupied, not free
  EXPECT_EQ(at(mapper, -0.81, 0.01), Occupancy::kOccupied);  // the second beam's obstacle is within it
  EXPECT_EQ(mapper.stats().beams_clipped, 1U);
  EXPECT_EQ(mapper.stats().obstacles, 1U);
  options.max_range_m = 0.0;
  EXPECT_THROW(SonarMapper{options}, ValueError);
}

TEST(mappingSonarMapper, ObstacleOfOneBeamIsNotClearedByAnotherInTheSameSweep) {
  SonarMapper mapper(singleRay());
  PolarImage polar = makeSweep(2, 150);
  polar.bearing_rad = {0.0, 0.0};  // two beams along +x
  mapper.integrateSweep(polar, {obstacleAt(49, 200), obstacleAt(99, 200)});
  EXPECT_EQ(at(mapper, 0.99, 0.01), Occupancy::kOccupied);  // hit of beam 0, crossed by beam 1
  EXPECT_EQ(at(mapper, 1.99, 0.01), Occupancy::kOccupied);
  // Each cell is updated once per sweep, although both rays cross the first metre.
  EXPECT_FLOAT_EQ(*mapper.map().search(*mapper.map().coder().keyOf({0.5, 0.01, 0.0})), mapper.map().model().miss);
}

// A detection is the detector's decision: weak and strong echoes earn the same hit (P 0.7).
TEST(mappingSonarMapper, EveryDetectedEchoEarnsTheFullHit) {
  SonarMapper mapper(singleRay());
  PolarImage polar = makeSweep(2, 150);
  polar.bearing_rad = {0.0, std::numbers::pi / 2};
  mapper.integrateSweep(polar, {obstacleAt(99, 160), obstacleAt(99, 40)});
  const auto strong = mapper.map().search(*mapper.map().coder().keyOf({1.99, 0.01, 0.0}));
  const auto weak = mapper.map().search(*mapper.map().coder().keyOf({0.01, 1.99, 0.0}));
  EXPECT_FLOAT_EQ(*strong, mapper.map().model().hit);
  EXPECT_FLOAT_EQ(*weak, mapper.map().model().hit);
}

TEST(mappingSonarMapper, ObstacleWithoutAPositiveRangeIsRejected) {
  SonarMapper mapper(singleRay());
  PolarImage polar = makeSweep(1, 150);
  EXPECT_THROW(mapper.integrateSweep(polar, {BeamDetection{99, 200}}), ValueError);  // range_m left at 0
}

TEST(mappingSonarMapper, BeamFanFillsTheWedgeBetweenBeams) {
  PolarImage polar = makeSweep(200, 200);  // 1.8° apart, 4 m
  const std::vector<BeamDetection> detections(200, obstacleAt(149, 200));  // a 3 m circle
  SonarMapper single(singleRay());
  single.integrateSweep(polar, detections);
  SonarMapper fan(fanOptions());  // 3° beams
  fan.integrateSweep(polar, detections);
  std::size_t free_single = 0, free_fan = 0, samples = 0;
  for (double angle = 0.0; angle < 2.0 * std::numbers::pi; angle += 0.001, ++samples) {
    const double x = 2.5 * std::cos(angle), y = 2.5 * std::sin(angle);
    free_single += at(single, x, y) == Occupancy::kFree ? 1 : 0;
    free_fan += at(fan, x, y) == Occupancy::kFree ? 1 : 0;
  }
  EXPECT_LT(free_single, samples / 2);  // single rays 7.8 cm apart at 2.5 m leave gaps
  EXPECT_EQ(free_fan, samples);         // the fan covers the whole circle
  EXPECT_EQ(at(fan, 2.99 * std::cos(0.3), 2.99 * std::sin(0.3)), Occupancy::kOccupied);
}

TEST(mappingSonarMapper, BresenhamAndDdaBothMapTheBeam) {
  MapperOptions options = singleRay();
  options.ray = RayAlgorithm::kBresenham;
  SonarMapper mapper(options);
  PolarImage polar = makeSweep(1, 150);
  polar.bearing_rad = {0.7};
  mapper.integrateSweep(polar, {obstacleAt(99, 200)});
  EXPECT_EQ(mapper.map().occupancyAt({1.99 * std::cos(0.7), 1.99 * std::sin(0.7), 0.0}), Occupancy::kOccupied);
  EXPECT_EQ(mapper.map().occupancyAt({std::cos(0.7), std::sin(0.7), 0.0}), Occupancy::kFree);
  EXPECT_EQ(parseRayAlgorithm("bresenham"), RayAlgorithm::kBresenham);
  EXPECT_THROW(parseRayAlgorithm("laser"), ValueError);
}

TEST(mappingSonarMapper, BeamsLeavingTheMapAreSkippedAndCounted) {
  MapperOptions options = singleRay();
  options.resolution_m = 0.0001;  // depth 16 at 0.1 mm: the map spans ±3.28 m
  SonarMapper mapper(options);
  PolarImage polar = makeSweep(2, 250);  // 5 m beams
  mapper.integrateSweep(polar, {noObstacle(5.0), obstacleAt(99, 100)});
  EXPECT_EQ(mapper.stats().out_of_map, 1U);
  EXPECT_EQ(mapper.stats().beams_used, 1U);
}

// Every beam of the sweep leaves the map (a hostile bin length in a valid log): nothing is
// marked, nothing is written out of bounds, and the beams are counted.
TEST(mappingSonarMapper, SweepWhoseBeamsAllLeaveTheMapChangesNothing) {
  MapperOptions options = singleRay();
  options.resolution_m = 0.0001;  // the map spans ±3.28 m
  SonarMapper mapper(options);
  PolarImage polar = makeSweep(3, 250);  // 5 m beams
  mapper.integrateSweep(polar, {noObstacle(5.0), noObstacle(5.0), noObstacle(5.0)});
  EXPECT_EQ(mapper.stats().out_of_map, 3U);
  EXPECT_EQ(mapper.stats().beams_used, 0U);
  EXPECT_EQ(mapper.map().counts().nodes, 0U);
}

TEST(mappingSonarMapper, PoseMovesTheBeams) {
  SonarMapper mapper(singleRay());
  PolarImage polar = makeSweep(1, 150);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(10.0, -3.0, 1.0);
  pose.rotate(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
  mapper.integrateSweep(polar, {obstacleAt(99, 200)}, pose);  // bearing 0 now points to +y
  EXPECT_EQ(mapper.map().occupancyAt({10.0, -3.0 + 1.99, 1.0}), Occupancy::kOccupied);
  EXPECT_EQ(mapper.map().occupancyAt({10.0, -2.0, 1.0}), Occupancy::kFree);
}

TEST(mappingSonarMapper, BadInputThrows) {
  SonarMapper mapper(fanOptions());
  PolarImage polar = makeSweep(3, 10);
  EXPECT_THROW(mapper.integrateSweep(polar, {BeamDetection{}}), ValueError);
  MapperOptions options;
  options.resolution_m = 0.0;
  EXPECT_THROW(SonarMapper{options}, ValueError);
  options = {};
  options.beam_width_rad = -0.1;
  EXPECT_THROW(SonarMapper{options}, ValueError);
  options = {};
  options.range_tolerance_m = -0.01;
  EXPECT_THROW(SonarMapper{options}, ValueError);
  options = {};
  options.max_voxel_updates_per_beam = 0.0;
  EXPECT_THROW(SonarMapper{options}, ValueError);
}

TEST(mappingSweeps, ShortFragmentsJoinTheirNeighbourOfTheSameHeadSetting) {
  std::vector<Beam> beams(403);
  for (Beam& beam : beams) beam.bin_length_m = 0.01;
  const std::vector<SweepRange> sweeps{{0, 200}, {200, 400}, {400, 403}};
  EXPECT_EQ(mergeShortSweeps(beams, sweeps, 20), (std::vector<SweepRange>{{0, 200}, {200, 403}}));
  const std::vector<SweepRange> leading{{0, 5}, {5, 205}};
  EXPECT_EQ(mergeShortSweeps(beams, leading, 20), (std::vector<SweepRange>{{0, 205}}));
  EXPECT_EQ(mergeShortSweeps(beams, sweeps, 1), sweeps);
  // A range change (beams 0-4 at another bin length) or a gain change (the last 3) is never joined:
  // those groups stay short.
  std::vector<Beam> range_change = beams;
  for (std::size_t i = 0; i < 5; ++i) range_change[i].bin_length_m = 0.05;
  EXPECT_EQ(mergeShortSweeps(range_change, leading, 20), leading);
  for (std::size_t i = 400; i < 403; ++i) beams[i].gain_setting = 2;
  EXPECT_EQ(mergeShortSweeps(beams, sweeps, 20), sweeps);
}

TEST(mappingSweeps, ANarrowSectorsShortPassesAreGroupedAFewAtATime) {
  // Passes of 8 beams (a narrow sector): joined until a group holds 20 beams, then the next passes
  // start a group of their own, so the map takes them as the head goes, not all at the stream's end.
  std::vector<Beam> beams(56);
  for (Beam& beam : beams) beam.bin_length_m = 0.01;
  std::vector<SweepRange> passes;
  for (std::size_t first = 0; first < beams.size(); first += 8) passes.push_back({first, first + 8});
  EXPECT_EQ(mergeShortSweeps(beams, passes, 20), (std::vector<SweepRange>{{0, 24}, {24, 48}, {48, 56}}));
  // one beam at a time: the first group is final when the fourth pass begins
  SweepGrouper grouper(20);
  std::vector<std::size_t> final_at;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    if (grouper.add(i > 0 && i % 8 == 0, headSettingOf(beams[i])) > 0) final_at.push_back(i);
  }
  EXPECT_EQ(final_at, (std::vector<std::size_t>{24, 48}));
  EXPECT_EQ(grouper.finish(), 8u);
}

}  // namespace
}  // namespace sonarmap

namespace sonarmap {
namespace {

TEST(mappingSonarMapper, MapSweepCleansDetectsAndIntegrates) {
  // A sweep as it arrives: walls whose range changes with bearing (2.0–3.0 m: a room, not a ring,
  // which the detector's per-range background would remove) behind a bright self-reflection band.
  PolarImage polar = makeSweep(100, 200);
  polar.intensities.colRange(0, 10).setTo(250);  // 0–0.2 m: the vehicle's own echo
  std::vector<double> wall_m;
  for (int row = 0; row < 100; ++row) {
    wall_m.push_back(2.0 + std::abs(std::sin(2.0 * polar.bearing_rad[static_cast<std::size_t>(row)])));
    const int bin = static_cast<int>(wall_m.back() / kBin);
    polar.intensities.row(row).colRange(bin, bin + 15).setTo(200);
  }
  SonarMapper mapper;
  const std::vector<BeamDetection> detections = mapper.mapSweep(polar);
  ASSERT_EQ(detections.size(), 100U);
  for (std::size_t row = 0; row < detections.size(); ++row) {
    ASSERT_TRUE(detections[row].hasObstacle()) << "beam " << row;
    // The 11 × 11 Gaussian smooths across ±5 beams: the detection lies between the nearest wall
    // of those neighbours and this beam's own wall, give or take the blur along the beam
    // (σ 2.3 bins: the rise can move by about 2σ, so 5 bins of slack).
    double nearest_m = wall_m[row];
    for (std::size_t k = 0; k <= 10; ++k) nearest_m = std::min(nearest_m, wall_m[(row + 95 + k) % 100]);
    const double detected_m = detections[row].obstacle_bin * kBin;
    EXPECT_GE(detected_m, nearest_m - 5 * kBin) << "beam " << row;
    EXPECT_LE(detected_m, wall_m[row] + 5 * kBin) << "beam " << row;
  }
  EXPECT_EQ(polar.intensities.at<unsigned char>(0, 2), 0);  // self-reflection removed in place
  EXPECT_EQ(at(mapper, 1.5, 0.0), Occupancy::kFree);
  EXPECT_EQ(mapper.stats().sweeps, 1U);
  EXPECT_EQ(mapper.stats().obstacles, 100U);
}

}  // namespace
}  // namespace sonarmap
