// The mapper's inverse sensor model and its automatic options: arcs carved by neighbouring beams,
// the range tolerance, the automatic resolution, the work budget per beam, and the warnings a user sees.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

PlannedBeam hitBeam(double bearing_deg, double range_m, double tolerance_m) {
  return {Eigen::Isometry3d::Identity(), bearing_deg * kDegree, range_m - tolerance_m, range_m, true};
}

/// The bearings (degrees) of the hit points of a plan.
std::vector<double> hitBearings(const std::vector<HitPoint>& hits) {
  std::vector<double> bearings;
  for (const HitPoint& hit : hits) bearings.push_back(std::atan2(hit.point_m.y(), hit.point_m.x()) / kDegree);
  return bearings;
}

// "Somewhere occupied, everywhere empty": an arc point is dropped where another beam of the sweep
// cleared water beyond it; where no beam saw farther it stays.
TEST(mappingSensorModel, ArcsAreCarvedWhereNeighboursSawWaterBeyond) {
  std::vector<FreeRay> rays;
  std::vector<HitPoint> hits;
  const double tolerance_m = 0.02;
  // Beam at 10° hits at 2 m; its neighbour at 12° (overlapping 1°) sees water to 3 m.
  std::vector<PlannedBeam> beams{hitBeam(10.0, 2.0, tolerance_m), hitBeam(12.0, 3.0, tolerance_m)};
  planSweep(beams, 3.0 * kDegree, 0.02, tolerance_m, rays, hits);
  double first_max = -1e9, second_min = 1e9;
  for (const HitPoint& hit : hits) {
    const double bearing = std::atan2(hit.point_m.y(), hit.point_m.x()) / kDegree;
    if (hit.point_m.norm() < 2.5) first_max = std::max(first_max, bearing);
    else second_min = std::min(second_min, bearing);
  }
  EXPECT_LT(first_max, 10.6);   // the 2 m arc ends where the 3 m beam's wedge begins (10.5°)
  EXPECT_GT(first_max, 9.9);    // but keeps its own half
  EXPECT_LT(second_min, 10.6);  // the 3 m arc spans its whole width: nothing saw beyond it
  // Two beams seeing the same wall at the same range keep their whole arcs.
  beams = {hitBeam(10.0, 2.0, tolerance_m), hitBeam(12.0, 2.01, tolerance_m)};
  planSweep(beams, 3.0 * kDegree, 0.02, tolerance_m, rays, hits);
  const std::vector<double> bearings = hitBearings(hits);
  EXPECT_LT(*std::min_element(bearings.begin(), bearings.end()), 8.9);  // 8.5° on a grid of 0.35°
  EXPECT_GT(*std::max_element(bearings.begin(), bearings.end()), 13.1);  // 13.5°
}

// A moving sonar: each beam carves with its own pose. The first beam, from the origin, hits at
// 2 m straight along y: its arc spans x = −0.05 … 0.05 m. The second, taken from (0.5, 0) and
// pointing back at 102.7°, sees water 3 m out; at y = 2 m its wedge covers x ≈ 0.00 … 0.10 m,
// the arc's right half. Placed at the origin instead, its wedge would miss the arc entirely.
TEST(mappingSensorModel, ArcsAreCarvedFromEachBeamsOwnPose) {
  std::vector<HitPoint> hits;
  const double tolerance_m = 0.02;
  const PlannedBeam first = hitBeam(90.0, 2.0, tolerance_m);
  PlannedBeam second = hitBeam(102.7, 3.0, tolerance_m);
  auto firstArc = [&] {
    std::vector<double> xs;
    for (const HitPoint& hit : hits) {
      if (hit.point_m.norm() < 2.5) xs.push_back(hit.point_m.x());
    }
    return xs;
  };
  planArcs({first, second}, 3.0 * kDegree, 0.02, tolerance_m, hits);  // both at the origin
  std::vector<double> xs = firstArc();
  EXPECT_GT(*std::max_element(xs.begin(), xs.end()), 0.045);  // whole arc kept
  second.sonar_to_map = Eigen::Isometry3d(Eigen::Translation3d(0.5, 0.0, 0.0));
  planArcs({first, second}, 3.0 * kDegree, 0.02, tolerance_m, hits);
  xs = firstArc();
  ASSERT_FALSE(xs.empty());
  EXPECT_LT(*std::max_element(xs.begin(), xs.end()), 0.01);    // the right half carved
  EXPECT_LT(*std::min_element(xs.begin(), xs.end()), -0.045);  // the left half kept
}

// The range tolerance: a beam's free space ends before its obstacle, so an earlier sweep's echo of
// the same wall a little nearer is not cleared.
TEST(mappingSensorModel, FreeSpaceEndsTheToleranceBeforeTheObstacle) {
  MapperOptions options;
  options.resolution_m = 0.02;
  options.beam_width_rad = 0.0;
  options.range_tolerance_m = 0.05;
  SonarMapper mapper(options);
  PolarImage polar;
  polar.intensities = cv::Mat::zeros(1, 150, CV_8U);
  polar.valid_bins = {150};
  polar.bearing_rad = {0.0};
  polar.time_s = {0.0};
  polar.bin_length_m = 0.02;
  mapper.integrateSweep(polar, {BeamDetection{99, 200, 1.99}});  // sweep 1: the wall at 1.99 m
  mapper.integrateSweep(polar, {BeamDetection{101, 200, 2.03}});  // sweep 2: 4 cm farther
  EXPECT_EQ(mapper.map().occupancyAt({1.99, 0.01, 0.0}), Occupancy::kOccupied);  // not cleared by sweep 2
  EXPECT_EQ(mapper.map().occupancyAt({2.03, 0.01, 0.0}), Occupancy::kOccupied);
  EXPECT_EQ(mapper.map().occupancyAt({1.90, 0.01, 0.0}), Occupancy::kFree);
}

// One echo outweighs the clamped free evidence of earlier sweeps (P(hit) 0.9): a target that moves
// into cleared water is occupied after the first sweep that sees it.
TEST(mappingSensorModel, OneEchoMakesClearedWaterOccupied) {
  MapperOptions options;
  options.resolution_m = 0.02;
  options.beam_width_rad = 0.0;
  SonarMapper mapper(options);
  PolarImage polar;
  polar.intensities = cv::Mat::zeros(1, 150, CV_8U);
  polar.valid_bins = {150};
  polar.bearing_rad = {0.0};
  polar.time_s = {0.0};
  polar.bin_length_m = 0.02;
  BeamDetection water;
  water.water_range_m = 3.0;
  for (int sweep = 0; sweep < 20; ++sweep) mapper.integrateSweep(polar, {water});  // clamped free
  EXPECT_EQ(mapper.map().occupancyAt({1.99, 0.01, 0.0}), Occupancy::kFree);
  mapper.integrateSweep(polar, {BeamDetection{99, 200, 1.99}});
  EXPECT_EQ(mapper.map().occupancyAt({1.99, 0.01, 0.0}), Occupancy::kOccupied);
  EXPECT_FLOAT_EQ(mapper.map().model().hit, logOdds(0.9));
}

TEST(mappingSensorModel, AutomaticResolutionFollowsTheReach) {
  EXPECT_DOUBLE_EQ(autoResolution_m(5.0), 0.02);   // Micron: the paper's 2 cm
  EXPECT_DOUBLE_EQ(autoResolution_m(30.0), 0.1);   // SeaKing at 30 m
  EXPECT_DOUBLE_EQ(autoResolution_m(50.0), 0.2);   // Ping360, SeaKing at 50 m
  EXPECT_DOUBLE_EQ(autoResolution_m(10.2), 0.05);  // the SeaNet sector log
  EXPECT_DOUBLE_EQ(autoResolution_m(0.01), 0.001);
  EXPECT_THROW(autoResolution_m(0.0), ValueError);
  // A mapper without a resolution takes it from its first sweep's reach.
  SonarMapper mapper;
  PolarImage polar;
  polar.intensities = cv::Mat::zeros(3, 300, CV_8U);
  polar.valid_bins = {300, 300, 300};
  polar.bearing_rad = {0.0, 1.0, 2.0};
  polar.time_s = {0.0, 0.1, 0.2};
  polar.bin_length_m = 0.1;  // 30 m
  mapper.integrateSweep(polar, std::vector<BeamDetection>(3));
  EXPECT_DOUBLE_EQ(mapper.map().resolution_m(), 0.1);
  EXPECT_DOUBLE_EQ(*mapper.options().resolution_m, 0.1);
}

SonarLog logOf(std::size_t beams, int bins, double bin_m) {
  SonarLog log;
  for (std::size_t i = 0; i < beams; ++i) {
    Beam beam;
    beam.time_s = 0.05 * static_cast<double>(i);
    beam.bearing_rad = std::fmod(1.8 * kDegree * static_cast<double>(i), 2.0 * std::numbers::pi);
    beam.bin_length_m = bin_m;
    beam.intensities.assign(static_cast<std::size_t>(bins), 0);
    log.beams.push_back(beam);
  }
  return log;
}

// A beam's work is its wedge (planar) or cone (volume) over the voxel: estimated from the beam's
// own geometry, whatever the log's length.
TEST(mappingSensorModel, VoxelUpdatesPerBeamAreTheBeamsWedgeOrCone) {
  MapperOptions options;
  options.resolution_m = 0.02;
  // A 3° wedge of 5 m: width × R² / 2 over res², plus its line of R / res voxels.
  EXPECT_DOUBLE_EQ(estimateVoxelUpdatesPerBeam(options, 5.0), 3.0 * kDegree * 25.0 / (2.0 * 0.0004) + 5.0 / 0.02);
  EXPECT_DOUBLE_EQ(estimateVoxelUpdatesPerBeam(options, 10.0), 3.0 * kDegree * 100.0 / (2.0 * 0.0004) + 10.0 / 0.02);
  // A beam longer than max_range_m counts up to it.
  options.max_range_m = 5.0;
  EXPECT_DOUBLE_EQ(estimateVoxelUpdatesPerBeam(options, 50.0), estimateVoxelUpdatesPerBeam(options, 5.0));
  // The volume model: the free cone (3° × half the 35° aperture) × R³ / 3 over res³, plus the shell.
  options.beam_model = BeamModel::kVolume;
  const double cone = 3.0 * kDegree * 17.5 * kDegree * 125.0 / (3.0 * 0.02 * 0.02 * 0.02);
  const double shell = 35.0 * kDegree * 25.0 / (0.02 * 0.02);
  EXPECT_DOUBLE_EQ(estimateVoxelUpdatesPerBeam(options, 5.0), cone + shell);
  // A ray (beam width 0) is a voxel wide.
  options.beam_model = BeamModel::kPlanar;
  options.beam_width_rad = 0.0;
  EXPECT_DOUBLE_EQ(estimateVoxelUpdatesPerBeam(options, 5.0), 0.02 * 5.0 / (2.0 * 0.0004) + 5.0 / 0.02);
  options.resolution_m.reset();
  EXPECT_THROW(estimateVoxelUpdatesPerBeam(options, 5.0), ValueError);
}

// Every sonar preset at its automatic resolution fits the default budget with a wide margin
// (planar and volume), so that no log of any length is refused with the defaults.
TEST(mappingSensorModel, EveryPresetAtItsAutomaticResolutionFitsTheDefaultBudgetTwentyTimesOver) {
  for (const std::string& name : sonarPresetNames()) {
    const SonarPreset preset = sonarPreset(name);
    for (const BeamModel model : {BeamModel::kPlanar, BeamModel::kVolume}) {
      MapperOptions options;
      options.beam_model = model;
      options.beam_width_rad = preset.head.horizontal_beam_width_rad;
      options.vertical_aperture_rad = preset.head.vertical_beam_width_rad;
      options.resolution_m = autoResolution_m(preset.head.range_m);
      EXPECT_LT(20.0 * estimateVoxelUpdatesPerBeam(options, preset.head.range_m), options.max_voxel_updates_per_beam)
          << name << (model == BeamModel::kVolume ? " volume" : " planar");
    }
  }
}

/// `beams` beams of `bins` bins of `bin_m` metres, 0.9° apart (a SeaKing's 400 beams a turn).
SonarLog longLog(std::size_t beams, int bins, double bin_m) {
  SonarLog log;
  log.beams.resize(beams);
  for (std::size_t i = 0; i < beams; ++i) {
    Beam& beam = log.beams[i];
    beam.time_s = 0.07 * static_cast<double>(i);
    beam.bearing_rad = std::fmod(0.9 * kDegree * static_cast<double>(i), 2.0 * std::numbers::pi);
    beam.bin_length_m = bin_m;
    beam.intensities.assign(static_cast<std::size_t>(bins), 0);
  }
  return log;
}

// A log of hours is not refused for its length: 120,000 beams of a SeaKing at 30 m (2.3 h), mapped
// in 3D at the automatic 0.1 m, once needed 1.2e10 voxel updates in all, beyond a whole-log budget
// of 1e10; each beam needs about 2e5.
TEST(mappingSensorModel, ALongLogIsNotRefusedForItsLength) {
  const SonarLog log = longLog(120000, 300, 0.1);
  MapperOptions options;
  options.beam_model = BeamModel::kVolume;
  const AutoResolution chosen = autoResolutionForLog(log, options);
  EXPECT_DOUBLE_EQ(chosen.resolution_m, 0.1);
  EXPECT_FALSE(chosen.coarsened);
  EXPECT_NO_THROW(checkWorkBudget(log, options));
  options.resolution_m = 0.1;
  EXPECT_LT(estimateVoxelUpdatesPerBeam(options, 30.0), 3e5);
}

// A mistaken resolution is still refused before mapping, naming the option that raises the budget
// and the finest resolution that fits: 1 mm voxels on a 50 m Ping360.
TEST(mappingSensorModel, AMistakenResolutionIsRefusedNamingTheFinestThatFits) {
  const SonarLog log = longLog(400, 1200, 50.0 / 1200.0);
  for (const BeamModel model : {BeamModel::kPlanar, BeamModel::kVolume}) {
    MapperOptions options;
    options.beam_model = model;
    options.beam_width_rad = 2.0 * kDegree;
    options.vertical_aperture_rad = 25.0 * kDegree;
    options.resolution_m = 0.001;
    std::string message;
    try {
      checkWorkBudget(log, options);
      ADD_FAILURE() << "1 mm voxels on a 50 m log should be refused";
    } catch (const ValueError& error) {
      message = error.what();
    }
    EXPECT_NE(message.find("--max-voxel-updates-per-beam"), std::string::npos) << message;
    EXPECT_NE(message.find("auto: 0.2 m"), std::string::npos) << message;
    const std::string lead = "use a resolution of at least ";
    const std::size_t at = message.find(lead);
    ASSERT_NE(at, std::string::npos) << message;
    const double fits_m = std::stod(message.substr(at + lead.size()));
    // It fits, and a finer one (by 1 %, more than its rounding to three digits) does not.
    options.resolution_m = fits_m;
    EXPECT_LE(estimateVoxelUpdatesPerBeam(options, 50.0), options.max_voxel_updates_per_beam) << message;
    EXPECT_NO_THROW(checkWorkBudget(log, options));
    options.resolution_m = 0.99 * fits_m;
    EXPECT_GT(estimateVoxelUpdatesPerBeam(options, 50.0), options.max_voxel_updates_per_beam) << message;
    options.resolution_m = 0.001;
    EXPECT_THROW(mapSonarLog(log, options), ValueError);
    options.max_voxel_updates_per_beam = 1e13;
    EXPECT_NO_THROW(checkWorkBudget(log, options));
  }
}

// A map no beam fits in is an error naming the resolution that fits, not an empty success.
TEST(mappingSensorModel, MapNoBeamFitsInIsAnError) {
  SonarLog log = logOf(200, 399, 0.0125);
  log.beams[0].intensities.assign(399, 0);
  MapperOptions options;
  options.resolution_m = 1e-5;  // the map spans ±0.33 m
  options.max_voxel_updates_per_beam = 1e16;
  try {
    mapSonarLog(log, options);
    FAIL() << "every beam reaches 5 m, outside a ±0.33 m map";
  } catch (const ValueError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("no beam could be mapped"), std::string::npos) << message;
    EXPECT_NE(message.find("resolution of at least"), std::string::npos) << message;
  }
}

// The warnings name the likely cause of an empty map.
TEST(mappingSensorModel, WarningsSayWhyTheMapIsEmpty) {
  MappingStats stats;
  stats.beams_used = 200;
  stats.detection.beams = 200;
  stats.detection.reach_m = 5.0;
  stats.calibration = {0.3, 1.0, 1.0, 16.9, 45.0};
  auto warnings = mappingWarnings(stats, MapperOptions{}, 0.02);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_NE(warnings[0].find("no obstacle in 200 beams"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("--false-alarm"), std::string::npos) << warnings[0];
  stats.detection.echoes_before_min_range = 150;  // walls nearer than the minimum range
  stats.detection.hidden_from_m = 0.3;             // in sweeps whose band ended at 0.3 m
  stats.detection.hidden_to_m = 1.0;               // and whose minimum range was 1 m
  warnings = mappingWarnings(stats, MapperOptions{}, 0.02);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_NE(warnings[0].find("minimum range (0.30 .. 1.00 m in their sweeps)"), std::string::npos) << warnings[0];
  stats.calibration.min_range_m = 6.0;  // beyond the reach
  warnings = mappingWarnings(stats, MapperOptions{}, 0.02);
  EXPECT_NE(warnings[0].find("beyond the log's reach"), std::string::npos) << warnings[0];
  // Most beams outside the map: the resolution that fits.
  stats = {};
  stats.beams_used = 10;
  stats.out_of_map = 90;
  stats.farthest_m = 100.0;
  warnings = mappingWarnings(stats, MapperOptions{}, 0.001);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_NE(warnings[0].find("90 of 100 beams reach outside the map"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("0.00305"), std::string::npos) << warnings[0];  // 100 m / 32767
  // A good map says nothing.
  stats = {};
  stats.beams_used = 200;
  stats.detection.beams = 200;
  stats.detection.obstacles = 190;
  EXPECT_TRUE(mappingWarnings(stats, MapperOptions{}, 0.02).empty());
}

TEST(mappingSensorModel, OptionsThatCannotWorkWithTheLogAreNamed) {
  const SonarLog log = logOf(10, 399, 0.0125);  // 5 m
  MapperOptions options;
  EXPECT_TRUE(optionWarnings(options, log).empty());
  options.self_reflection_range_m = 1e9;
  options.detector.min_range_m = 6.0;
  options.resolution_m = 2.0;
  const std::vector<std::string> warnings = optionWarnings(options, log);
  ASSERT_EQ(warnings.size(), 2U);  // the minimum range once: the farther of the two near-field settings
  EXPECT_NE(warnings[0].find("--min-range) 1e+09 m"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("auto would choose 0.02 m"), std::string::npos) << warnings[1];
}

}  // namespace
}  // namespace sonarmap
