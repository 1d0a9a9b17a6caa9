// Mapping from a moving vehicle (SonarMapper::integrateSweep with one pose per beam, mapSonarLog
// with navigation) on the simulated tank, scored against the scene's ground truth: per-beam poses
// keep the map as sharp as a static run; one pose per sweep smears it. The measured figures are
// printed so that changes show.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <sstream>

#include "sonarmap/eval/tank_quality.hpp"
#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sonar/polar.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kTurns = 3;  // 25.8 s of a Micron

/// How sharp a map of the tank is: the occupied voxels of the slice z = 0 against the truth.
struct Sharpness {
  double near_surface = 0.0;  ///< share of occupied voxels within 0.1 m of a surface of the scene
  double rms_wall_m = 0.0;    ///< RMS distance of the on-wall voxels to the fitted rectangle
  double side_x_m = 0.0, side_y_m = 0.0;  ///< fitted rectangle (truth: 4.2 × 4.4 m)
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();  ///< fitted centre (truth: (0, 0.4))
};

Sharpness sharpnessOf(const OcTree16& map, const Scene& scene) {
  const std::vector<Eigen::Vector2d> occupied = cellsInSlice(map, 0.0, Occupancy::kOccupied);
  std::size_t near = 0;
  for (const Eigen::Vector2d& cell : occupied) {
    near += distanceToSurface(scene, Eigen::Vector3d(cell.x(), cell.y(), 0.0)) <= 0.1 ? 1 : 0;
  }
  const WallFitReport walls = evaluateTankMap(map, 0.0).walls;
  const bool along_x = std::abs(std::cos(walls.rect.angle_rad)) > 0.5;
  return {static_cast<double>(near) / static_cast<double>(std::max<std::size_t>(1, occupied.size())),
          walls.rms_wall_distance_m, along_x ? walls.rect.width_m : walls.rect.height_m,
          along_x ? walls.rect.height_m : walls.rect.width_m, walls.rect.center_m};
}

std::ostream& operator<<(std::ostream& out, const Sharpness& s) {
  return out << "within 0.1 m " << s.near_surface << ", rms " << s.rms_wall_m << " m, fitted " << s.side_x_m << " x "
             << s.side_y_m << " m at (" << s.center_m.x() << ", " << s.center_m.y() << ")";
}

MsisSimulation simulate(const Trajectory& trajectory) {
  MsisSimulationOptions options;
  options.turns = kTurns;
  options.trajectory = trajectory;
  return simulateMsis(builtinScene("tank"), options);
}

/// The loud echoes only (the background detector): the turning run passes beside the floater, whose
/// weak echo from above the sonar's plane the default detector maps in the plane (a planar model's
/// limit, 0.3 m off the scene's surfaces at z = 0, not a pose error), while the static head hears it
/// loud at 1.95 m in both. Sharpness here measures the poses.
MapperOptions loudEchoes() {
  MapperOptions options;
  selectDetector(options.detector, "background");
  return options;
}

/// Maps `run` ignoring the motion within a sweep: every beam of a sweep gets the sonar's pose at
/// the sweep's middle beam (sweeps split as mapSonarLog splits them).
SonarMapper mapWithOnePosePerSweep(const MsisSimulation& run) {
  SonarMapper mapper(loudEchoes());
  const auto min_beams = static_cast<std::size_t>(mapper.options().detector.background.min_beams);
  for (const SweepRange& sweep : groupSweeps(run.log.beams, min_beams)) {
    PolarImage polar = makePolarImage(run.log.beams, sweep.first, sweep.last_exclusive);
    const std::vector<BeamDetection> detections = mapper.detect(polar);
    const double middle_s = polar.time_s[polar.time_s.size() / 2];
    const Eigen::Isometry3d body_to_ned = *interpolateBodyToNed(run.nav, middle_s);
    mapper.integrateSweep(polar, detections, nedToMap() * body_to_ned * defaultSonarToBody());
  }
  return mapper;
}

/// Static, moving with per-beam poses, moving with one pose per sweep: the figures of one trajectory.
void expectPerBeamPosesAsSharpAsStatic(const Trajectory& trajectory, const char* label) {
  const MsisSimulation still = simulate(staticTrajectory());
  const Sharpness static_map = sharpnessOf(mapSonarLog(still.log, loudEchoes()).map(), still.scene);
  const MsisSimulation moving = simulate(trajectory);
  const SonarMapper per_beam = mapSonarLog(moving.log, moving.nav, defaultSonarToBody(), loudEchoes());
  const Sharpness per_beam_map = sharpnessOf(per_beam.map(), moving.scene);
  const Sharpness per_sweep_map = sharpnessOf(mapWithOnePosePerSweep(moving).map(), moving.scene);
  std::cout << "[ " << label << " ] static: " << static_map << "\n[ " << label << " ] per-beam poses: " << per_beam_map
            << "\n[ " << label << " ] one pose per sweep: " << per_sweep_map << "\n";
  EXPECT_EQ(per_beam.stats().beams_used, moving.log.beams.size());
  EXPECT_EQ(per_beam.stats().beams_without_nav, 0U);
  // As sharp as the static run (within a few percent) ...
  EXPECT_GT(per_beam_map.near_surface, static_map.near_surface - 0.03);
  EXPECT_LT(per_beam_map.rms_wall_m, static_map.rms_wall_m + 0.01);
  EXPECT_NEAR(per_beam_map.side_x_m, 4.2, 0.15);
  EXPECT_NEAR(per_beam_map.side_y_m, 4.4, 0.15);
  EXPECT_NEAR(per_beam_map.center_m.x(), 0.0, 0.05);
  EXPECT_NEAR(per_beam_map.center_m.y(), 0.4, 0.05);
  // ... and clearly sharper than ignoring the motion within a sweep.
  EXPECT_GT(per_beam_map.near_surface, per_sweep_map.near_surface + 0.1);
  EXPECT_LT(per_beam_map.rms_wall_m, per_sweep_map.rms_wall_m);
}

NavSample at(double north_m, double east_m, double yaw_rad = 0.0) {
  NavSample fix;
  fix.position_ned_m = Eigen::Vector3d(north_m, east_m, 0.0);
  fix.yaw_rad = yaw_rad;
  return fix;
}

TEST(mappingMoving, StraightRunAcrossTheTankIsAsSharpAsStatic) {
  // 0.1 m/s north for 25.8 s: from 1.2 m south to 1.4 m north of the tank's middle line.
  expectPerBeamPosesAsSharpAsStatic(constantVelocityTrajectory(at(-1.2, -0.4), Eigen::Vector3d(0.1, 0.0, 0.0)),
                                    "straight 0.1 m/s");
}

TEST(mappingMoving, TurningRunIsAsSharpAsStatic) {
  // 0.15 m/s while turning 5°/s clockwise (an arc of radius 1.7 m, 129° in 25.8 s).
  const double yaw_rate_radps = 5.0 * std::numbers::pi / 180.0;
  expectPerBeamPosesAsSharpAsStatic(
      constantVelocityTrajectory(at(-1.0, 0.0), Eigen::Vector3d(0.15, 0.0, 0.0), yaw_rate_radps), "turning 0.15 m/s");
}

std::string bytesOf(const OcTree16& map) {
  std::ostringstream out;
  writeBinary(map, out);
  return out.str();
}

TEST(mappingMoving, StaticLogWithConstantNavigationMapsAsWithoutNavigation) {
  const MsisSimulation still = simulate(staticTrajectory());
  ASSERT_FALSE(still.nav.empty());
  const SonarMapper without = mapSonarLog(still.log);
  const SonarMapper with = mapSonarLog(still.log, still.nav, defaultSonarToBody());
  EXPECT_EQ(bytesOf(with.map()), bytesOf(without.map()));
  EXPECT_EQ(with.map().counts().leaves, without.map().counts().leaves);
  EXPECT_EQ(with.stats().free_updates, without.stats().free_updates);
  EXPECT_EQ(with.stats().beams_used, without.stats().beams_used);
}

TEST(mappingMoving, BeamsOutsideTheNavigationAreSkippedAndCounted) {
  const MsisSimulation run = simulate(constantVelocityTrajectory(at(-1.2, -0.4), Eigen::Vector3d(0.1, 0.0, 0.0)));
  // Keep the fixes from 5 s to 20 s only.
  NavTrack nav;
  std::copy_if(run.nav.begin(), run.nav.end(), std::back_inserter(nav),
               [](const NavSample& fix) { return fix.time_s >= 5.0 - 1e-9 && fix.time_s <= 20.0 + 1e-9; });
  const auto outside = static_cast<std::size_t>(std::count_if(run.log.beams.begin(), run.log.beams.end(), [&](const Beam& beam) {
    return beam.time_s < nav.front().time_s || beam.time_s > nav.back().time_s;
  }));
  ASSERT_GT(outside, 200U);
  const SonarMapper mapper = mapSonarLog(run.log, nav, defaultSonarToBody());
  const MappingStats& stats = mapper.stats();
  EXPECT_EQ(stats.beams_without_nav, outside);
  EXPECT_EQ(stats.beams_used + stats.out_of_map + stats.beams_without_nav, run.log.beams.size());
  EXPECT_EQ(stats.sweeps, kTurns);  // detection stays per sweep

  EXPECT_THROW(mapSonarLog(run.log, NavTrack{}, defaultSonarToBody()), ValueError);
  NavTrack backwards = nav;
  std::swap(backwards[0], backwards[1]);
  EXPECT_THROW(mapSonarLog(run.log, backwards, defaultSonarToBody()), ValueError);
}

// ---------------------------------------------------------------------------------------------
// integrateSweep with one pose per row, on a synthetic sweep
// ---------------------------------------------------------------------------------------------

/// An obstacle at 1.0 m: the centre of bin 49 of 2 cm.
const BeamDetection kObstacleAt1m{49, 200, 0.99};

/// 2 cm voxels and no range tolerance: the hit is in the voxel of the detected range.
MapperOptions twoCentimetres() {
  MapperOptions options;
  options.resolution_m = 0.02;
  options.range_tolerance_m = 0.0;
  return options;
}

PolarImage twoBeams() {
  PolarImage polar;
  polar.intensities = cv::Mat::zeros(2, 150, CV_8U);
  polar.valid_bins = {150, 150};
  polar.bearing_rad = {0.0, 0.5 * std::numbers::pi};
  polar.time_s = {0.0, 1.0};
  polar.bin_length_m = 0.02;
  return polar;
}

Eigen::Isometry3d translation(double x_m, double y_m) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x_m, y_m, 0.0);
  return pose;
}

TEST(mappingMoving, EachRowIsPlacedWithItsOwnPose) {
  SonarMapper mapper(twoCentimetres());
  // Both obstacles at 1.0 m (bin 49); the second beam's sonar has moved 1 m along +x.
  mapper.integrateSweep(twoBeams(), {kObstacleAt1m, kObstacleAt1m},
                        std::vector<Eigen::Isometry3d>{translation(0.0, 0.0), translation(1.0, 0.0)});
  const auto at = [&](double x, double y) { return mapper.map().occupancyAt({x, y, 0.01}); };
  EXPECT_EQ(at(0.99, 0.0), Occupancy::kOccupied);  // first beam: from the origin along +x
  EXPECT_EQ(at(1.0, 0.99), Occupancy::kOccupied);  // second beam: from (1, 0) along +y
  EXPECT_EQ(at(1.0, 0.5), Occupancy::kFree);
  EXPECT_EQ(at(0.0, 0.99), Occupancy::kUnknown);   // where one pose for both would have put it
  EXPECT_EQ(mapper.stats().beams_used, 2U);
}

TEST(mappingMoving, RowsWithoutPoseAreSkippedAndCountedAndLengthsChecked) {
  SonarMapper mapper(twoCentimetres());
  const std::vector<BeamDetection> detections{kObstacleAt1m, kObstacleAt1m};
  mapper.integrateSweep(twoBeams(), detections,
                        std::vector<std::optional<Eigen::Isometry3d>>{std::nullopt, translation(0.0, 0.0)});
  EXPECT_EQ(mapper.stats().beams_without_nav, 1U);
  EXPECT_EQ(mapper.stats().beams_used, 1U);
  EXPECT_EQ(mapper.map().occupancyAt({0.99, 0.0, 0.01}), Occupancy::kUnknown);
  EXPECT_EQ(mapper.map().occupancyAt({0.0, 0.99, 0.01}), Occupancy::kOccupied);
  EXPECT_THROW(mapper.integrateSweep(twoBeams(), detections, std::vector<Eigen::Isometry3d>{translation(0.0, 0.0)}),
               ValueError);
}

}  // namespace
}  // namespace sonarmap
