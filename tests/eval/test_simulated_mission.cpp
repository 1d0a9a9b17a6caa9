// The 3D mission of docs/accuracy.md: the Micron on a loop over quay3d with the sonar
// tilted 25° down, mapped at 5 cm with the default volume model and with the planar model. Pins
// the measured rows (docs/accuracy.md, "3D"): the volume model maps the 3D surfaces the planar
// model cannot, clears almost nothing that is not water, and erodes a bounded share.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"

namespace sonarmap {
namespace {

MapperOptions atFiveCentimetres(BeamModel model) {
  MapperOptions options;
  options.resolution_m = 0.05;
  options.beam_model = model;
  return options;
}

TEST(evalSimulatedMission, VolumeModelMapsTheTiltedLoopIn3D) {
  const SimulatedMission mission{"micron", "quay3d", "tilted-loop"};
  const MissionAccuracy planar = evaluateMission(mission, atFiveCentimetres(BeamModel::kPlanar));
  const MissionAccuracy volume = evaluateMission(mission, atFiveCentimetres(BeamModel::kVolume));
  // Measured on this mission: recall 0.018 planar against 0.141 volume; precision 0.403, erosion
  // 0.0000, free accuracy 1.000, median surface error 0.126 m for the volume model.
  EXPECT_GT(volume.truth.recall, 4.0 * planar.truth.recall);
  EXPECT_GT(volume.truth.precision, 0.38);
  EXPECT_LT(volume.truth.erosion, 0.01);  // the target: silent cones clear nothing
  EXPECT_GT(volume.truth.free_accuracy, 0.99);
  EXPECT_LT(volume.truth.surface_error_median_m, 0.15);  // three voxels
  // A 3D map: occupied voxels across metres of height, not one layer.
  EXPECT_GT(volume.truth.z_max_m - volume.truth.z_min_m, 2.0);
}

/// Every leaf of a map: key, depth and log-odds, in visit order.
std::vector<std::tuple<Key16, int, float>> leavesOf(const OcTree16& map) {
  std::vector<std::tuple<Key16, int, float>> leaves;
  map.forEachLeaf([&](const LeafView<16>& leaf) { leaves.emplace_back(leaf.key, leaf.depth, leaf.log_odds); });
  return leaves;
}

// Two threads tracing the free rays give the identical map, for both models, on a moving, tilted
// sonar (the cones of the tilted loop).
TEST(evalSimulatedMission, TwoThreadsGiveTheIdenticalMap) {
  const MissionRun run = simulateMission(SimulatedMission{"micron", "quay3d", "tilted-loop"});
  for (const BeamModel model : {BeamModel::kPlanar, BeamModel::kVolume}) {
    MapperOptions options = atFiveCentimetres(model);
    const SonarMapper serial = mapSonarLog(run.simulation.log, run.simulation.nav, run.options.sonar_to_body, options);
    options.threads = 2;
    const SonarMapper parallel = mapSonarLog(run.simulation.log, run.simulation.nav, run.options.sonar_to_body, options);
    ASSERT_GT(serial.stats().free_updates, 10000U);
    EXPECT_EQ(parallel.stats().free_updates, serial.stats().free_updates);
    EXPECT_EQ(leavesOf(parallel.map()), leavesOf(serial.map()));
  }
}

TEST(evalSimulatedMission, UnknownMissionIsAnError) {
  EXPECT_THROW(simulateMission(SimulatedMission{"micron", "quay3d", "spiral"}), ValueError);
}

}  // namespace
}  // namespace sonarmap
