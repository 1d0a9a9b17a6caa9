// The 3D mission of docs/accuracy.md (issue 11): the Micron on a loop over quay3d with the sonar
// tilted 25° down, mapped at 5 cm with the default volume model and with the planar model. Pins
// the measured rows (docs/accuracy.md, "3D"): the volume model maps the 3D surfaces the planar
// model cannot, clears almost nothing that is not water, and erodes a bounded share.
#include <gtest/gtest.h>

#include "sonarmap/eval/simulated_mission.hpp"

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
  // Measured (docs/accuracy.md): recall 0.022 planar against 0.136 volume; precision 0.51, erosion
  // 0.19, free accuracy 0.98 for the volume model.
  EXPECT_GT(volume.truth.recall, 4.0 * planar.truth.recall);
  EXPECT_GT(volume.truth.precision, 0.45);
  EXPECT_LT(volume.truth.erosion, 0.25);
  EXPECT_GT(volume.truth.free_accuracy, 0.97);
  EXPECT_LT(volume.truth.surface_error_median_m, 0.1);  // two voxels
  // A 3D map: occupied voxels across metres of height, not one layer.
  EXPECT_GT(volume.truth.z_max_m - volume.truth.z_min_m, 2.0);
}

TEST(evalSimulatedMission, UnknownMissionIsAnError) {
  EXPECT_THROW(simulateMission(SimulatedMission{"micron", "quay3d", "spiral"}), ValueError);
}

}  // namespace
}  // namespace sonarmap
