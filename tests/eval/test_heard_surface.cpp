// The surface a mission's beams could hear (heard_surface.hpp): every voxel of the oracle's map
// holds a surface point, the geometry alone finds every surface in the beams, a level head's
// grazing seabed drops out when its echo must reach the receiver's floor while a loud face stays,
// and the scores of a real mission follow from it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/eval/heard_surface.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

/// One turn of a level Micron 2 m over a seabed (primitive 0), a quay block 3 m ahead (1).
MissionRun levelHeadBeforeAQuay() {
  MissionRun run;
  const SonarPreset preset = sonarPreset("micron");
  run.options.head = preset.head;
  run.options.echo = preset.echo;
  run.options.turns = 1;
  const Scene scene{{Plane{{0.0, 0.0, -2.0}, Eigen::Vector3d::UnitZ(), 0.5},
                     Box{{3.5, 0.0, -1.0}, {1.0, 4.0, 4.0}, 0.0, 0.9}}};
  run.simulation = simulateMsis(scene, run.options);
  return run;
}

/// Occupied voxels of `map` nearest each of the scene's two primitives, and the largest distance
/// from an occupied voxel's centre to the scene.
struct Split {
  std::size_t seabed = 0, quay = 0;
  double farthest_m = 0.0;
};

Split split(const OcTree16& map, const Scene& scene) {
  Split counts;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (map.model().classify(leaf.log_odds) != Occupancy::kOccupied) return;
    leaf.forEachVoxel([&](const Key16& key) {  // a pruned leaf: every voxel in it
      const Eigen::Vector3d centre = map.coder().centerOf(key);
      const double seabed_m = distanceToSurface(scene.primitives[0], centre);
      const double quay_m = distanceToSurface(scene.primitives[1], centre);
      (seabed_m < quay_m ? counts.seabed : counts.quay) += 1;
      counts.farthest_m = std::max(counts.farthest_m, std::min(seabed_m, quay_m));
    });
  });
  return counts;
}

TEST(evalHeardSurface, AGrazingSeabedDropsOutWhereALoudFaceStays) {
  const MissionRun run = levelHeadBeforeAQuay();
  HeardSurfaceStats geometric_stats, heard_stats;
  const OcTree16 geometric = heardSurfaceMap(run, {0.05, kMinusInfinity}, &geometric_stats);
  const OcTree16 heard = heardSurfaceMap(run, {0.05, 0.0}, &heard_stats);
  const Split all = split(geometric, run.simulation.scene);
  const Split loud = split(heard, run.simulation.scene);
  // Every voxel holds a surface point: its centre lies within half a voxel diagonal of a surface.
  EXPECT_LE(all.farthest_m, 0.5 * std::sqrt(3.0) * 0.05 + 1e-9);
  EXPECT_LE(loud.farthest_m, 0.5 * std::sqrt(3.0) * 0.05 + 1e-9);
  // The rays reach the seabed past 4.5 m (26° down), under the flat of the pattern: heard at the
  // geometry, under the floor at 0 dB. The quay's face, square to the level beams, stays.
  EXPECT_GT(all.seabed, 1000U);
  EXPECT_LT(loud.seabed, all.seabed / 10);
  EXPECT_GT(all.quay, 1000U);
  EXPECT_GT(loud.quay, all.quay * 9 / 10);
  EXPECT_EQ(geometric_stats.beams, run.simulation.log.beams.size());
  EXPECT_EQ(heard_stats.rays, geometric_stats.rays);
  EXPECT_EQ(geometric_stats.heard_hits, geometric_stats.surface_hits);
  EXPECT_LT(heard_stats.heard_hits, geometric_stats.heard_hits);
}

TEST(evalHeardSurface, NothingHeardAndBadOptionsThrow) {
  const MissionRun run = levelHeadBeforeAQuay();
  EXPECT_THROW(heardSurfaceMap(run, {0.05, 200.0}), ValueError);
  EXPECT_THROW(heardSurfaceMap(run, {0.0, 0.0}), ValueError);
  EXPECT_THROW(heardSurfaceMap(run, {0.05, std::numeric_limits<double>::quiet_NaN()}), ValueError);
  EXPECT_THROW(heardSurfaceMap(run, {0.05, std::numeric_limits<double>::infinity()}), ValueError);
}

// The tilted loop of the Micron (the demo's 3D mission), scored as sonarmap_accuracy_3d scores a
// map: the surfaces a ray meets are nearly all the truth's visible voxels (its field of view is the
// same aperture), precision is 1 by construction, and demanding the echo reach the floor costs the
// water surface and the seabed most (sonarmap_heard_surface: 0.956 → 0.798).
TEST(evalHeardSurface, TheTiltedLoopsHeardSurfaceBoundsItsRecall) {
  const MissionRun run = simulateMission(SimulatedMission{"micron", "quay3d", "tilted-loop"});
  const GroundTruthOptions truth = missionTruthOptions(run);
  const GroundTruthReport geometric =
      evaluateAgainstScene(heardSurfaceMap(run, {0.05, kMinusInfinity}), run.simulation.scene, truth);
  const GroundTruthReport heard = evaluateAgainstScene(heardSurfaceMap(run, {0.05, 0.0}), run.simulation.scene, truth);
  EXPECT_DOUBLE_EQ(geometric.precision, 1.0);
  EXPECT_DOUBLE_EQ(heard.precision, 1.0);
  EXPECT_GT(geometric.recall, 0.95);
  EXPECT_NEAR(heard.recall, 0.798, 0.01);
}

}  // namespace
}  // namespace sonarmap
