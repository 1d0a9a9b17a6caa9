// The surface a mission's beams could hear (heard_surface.hpp): every voxel of the oracle's map
// holds a surface point, the geometry alone finds every surface in the beams, a level head's
// grazing seabed drops out when its echo must reach the receiver's floor while a loud face stays,
// and the scores of a real mission follow from it. The same surface from the log and true
// navigation on disk, and a map's heard recall and heard F1 against it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <tuple>
#include <vector>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/eval/heard_surface.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/nav/navigation.hpp"
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
// water surface and the seabed most (sonarmap_mission_reach: 0.956 → 0.798).
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

/// Keys ordered by z, then y, then x.
bool keyOrder(const Key16& a, const Key16& b) { return std::tie(a[2], a[1], a[0]) < std::tie(b[2], b[1], b[0]); }

/// The occupied finest voxels of `map`, sorted by keyOrder.
std::vector<Key16> occupiedKeys(const OcTree16& map) {
  std::vector<Key16> keys;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (map.model().classify(leaf.log_odds) != Occupancy::kOccupied) return;
    leaf.forEachVoxel([&](const Key16& key) { keys.push_back(key); });
  });
  std::sort(keys.begin(), keys.end(), keyOrder);
  return keys;
}

// What a user has on disk (the log's beams.csv, its truth_nav.csv, the mounting's six numbers and
// the preset) gives the mission's own heard surface: voxel for voxel with the run's own beams, but
// for hits on a voxel's face with the beams read back; beams outside the navigation's span are
// skipped and counted; a log the head did not record is refused.
TEST(evalHeardSurface, TheLogAndTrueNavigationOnDiskGiveTheMissionsHeardSurface) {
  const MissionRun run = simulateMission(SimulatedMission{"micron", "quay3d", "tilted-loop"});
  const test::TempDir dir;
  writeBeamCsv(dir.file("beams.csv"), run.simulation.log);
  writeNavCsv(dir.file("truth_nav.csv"), run.simulation.nav);
  const SonarLog log = readSonarLog(dir.file("beams.csv"));
  const NavTrack nav = readNavCsv(dir.file("truth_nav.csv"));
  const Eigen::Isometry3d sonar_to_body =
      sonarToBodyOfMounting(std::vector<double>(run.mounting.begin(), run.mounting.end()));
  const SonarPreset micron = sonarPreset("micron");
  const HeardSurfaceOptions coarse{0.2, 0.0};  // 20 cm voxels: a few rays per beam, fast
  HeardSurfaceStats mission_stats, disk_stats;
  const OcTree16 mission = heardSurfaceMap(run, coarse, &mission_stats);
  // The run's own beams with the navigation and mounting from disk: voxel for voxel.
  const OcTree16 same = heardSurfaceMap(run.simulation.log, nav, sonar_to_body, run.simulation.scene, micron.head,
                                        micron.echo, coarse, &disk_stats);
  const std::vector<Key16> mission_keys = occupiedKeys(mission);
  EXPECT_GT(mission_keys.size(), 1000U);
  EXPECT_EQ(occupiedKeys(same), mission_keys);
  EXPECT_EQ(disk_stats.voxels, mission_keys.size());
  EXPECT_EQ(disk_stats.beams, log.beams.size());
  EXPECT_EQ(disk_stats.beams_without_nav, 0U);
  EXPECT_EQ(disk_stats.heard_hits, mission_stats.heard_hits);
  // The beams read back: the CSV holds bearings in degrees, back in radians within 1e-15 rad, which
  // moves a hit lying on a voxel's face to its neighbour: the water surface at z = 0 lies on one
  // (27 of 4,365 voxels differ, 26 of them beside it).
  const std::vector<Key16> disk_keys = occupiedKeys(
      heardSurfaceMap(log, nav, sonar_to_body, run.simulation.scene, micron.head, micron.echo, coarse));
  std::vector<Key16> differ;
  std::set_symmetric_difference(disk_keys.begin(), disk_keys.end(), mission_keys.begin(), mission_keys.end(),
                                std::back_inserter(differ), keyOrder);
  EXPECT_LE(differ.size(), mission_keys.size() / 100) << differ.size() << " voxels differ";

  // The first half of the navigation: the later beams have no pose.
  const NavTrack first_half(nav.begin(), nav.begin() + static_cast<std::ptrdiff_t>(nav.size() / 2));
  HeardSurfaceStats half_stats;
  const OcTree16 half = heardSurfaceMap(log, first_half, sonar_to_body, run.simulation.scene, micron.head, micron.echo,
                                        coarse, &half_stats);
  EXPECT_GT(half_stats.beams_without_nav, log.beams.size() / 3);
  EXPECT_EQ(half_stats.beams + half_stats.beams_without_nav, log.beams.size());
  EXPECT_LT(half_stats.voxels, disk_stats.voxels);

  // The SeaKing's head records 10 cm bins, not the Micron's 1.25 cm: the log is refused.
  const SonarPreset seaking = sonarPreset("seaking-30");
  EXPECT_THROW(heardSurfaceMap(log, nav, sonar_to_body, run.simulation.scene, seaking.head, seaking.echo, coarse),
               ValueError);
}

// Without navigation the sonar stays at the map origin, upright, as mapSonarLog places a static
// log: the static run's heard surface, whose true pose is the identity.
TEST(evalHeardSurface, AStaticLogIsHeardFromTheMapOrigin) {
  const MissionRun run = levelHeadBeforeAQuay();
  const OcTree16 mission = heardSurfaceMap(run, {0.05, 0.0});
  const OcTree16 fixed = heardSurfaceMap(run.simulation.log, NavTrack{}, Eigen::Isometry3d::Identity(),
                                         run.simulation.scene, run.options.head, run.options.echo, {0.05, 0.0});
  EXPECT_EQ(occupiedKeys(fixed), occupiedKeys(mission));
}

/// A voxel of the 0.1 m grid by its indices from the origin (centre (i + 0.5) · 0.1 m, …).
Key16 gridKey(const OcTree16& map, int i, int j, int k) {
  return map.coder().keyOfChecked({(i + 0.5) * 0.1, (j + 0.5) * 0.1, (k + 0.5) * 0.1});
}

// The definition on a hand-made case: T = 0.173 m at 0.1 m voxels; a heard voxel counts when a
// mapped voxel of the evaluated slab has its centre within T of its centre.
TEST(evalHeardSurface, HeardRecallCountsHeardVoxelsWithAMappedVoxelWithinTheTolerance) {
  OcTree16 heard(0.1), map(0.1);
  heard.integrate(gridKey(heard, 0, 0, 0), true);
  heard.integrate(gridKey(heard, 5, 0, 0), true);
  map.integrate(gridKey(map, 1, 1, 0), true);  // 0.141 m from the first: found
  map.integrate(gridKey(map, 3, 0, 0), true);  // 0.200 m from the second: beyond T
  map.integrate(gridKey(map, 5, 1, 1), true);  // 0.141 m from the second, but outside the slab z ≤ 0.1 m
  GroundTruthReport truth;
  truth.tolerance_m = std::sqrt(3.0) * 0.1;
  truth.z_min_m = 0.05;
  truth.z_max_m = 0.1;
  truth.precision = 0.5;
  const HeardSurfaceScore score = scoreAgainstHeardSurface(map, truth, heard);
  EXPECT_EQ(score.heard_voxels, 2U);
  EXPECT_EQ(score.heard_voxels_found, 1U);
  EXPECT_DOUBLE_EQ(score.recall, 0.5);
  EXPECT_DOUBLE_EQ(score.precision, 0.5);
  EXPECT_DOUBLE_EQ(score.f1, 0.5);
  truth.z_max_m = 0.5;  // the slab now holds the voxel beside the second
  EXPECT_EQ(scoreAgainstHeardSurface(map, truth, heard).heard_voxels_found, 2U);
  // Other voxel sizes, an empty heard surface or a tolerance that is no distance are refused.
  EXPECT_THROW(scoreAgainstHeardSurface(OcTree16(0.05), truth, heard), ValueError);
  EXPECT_THROW(scoreAgainstHeardSurface(map, truth, OcTree16(0.1)), ValueError);
  truth.tolerance_m = 0.0;
  EXPECT_THROW(scoreAgainstHeardSurface(map, truth, heard), ValueError);
}

// The heard surface scored as a map against itself finds all it heard (recall 1, and precision 1
// against the scene: F1 1); without half the quay's face it finds the rest and little more; a map
// that holds no occupied voxel finds nothing.
TEST(evalHeardSurface, TheHeardSurfaceFindsItselfAndLessWithVoxelsRemoved) {
  const MissionRun run = levelHeadBeforeAQuay();
  const Scene& scene = run.simulation.scene;
  HeardSurfaceStats stats;
  const OcTree16 heard = heardSurfaceMap(run, {0.05, 0.0}, &stats);
  const HeardSurfaceScore itself = scoreAgainstHeardSurface(heard, evaluateAgainstScene(heard, scene), heard);
  EXPECT_EQ(itself.heard_voxels, stats.voxels);
  EXPECT_EQ(itself.heard_voxels_found, stats.voxels);
  EXPECT_DOUBLE_EQ(itself.recall, 1.0);
  EXPECT_DOUBLE_EQ(itself.precision, 1.0);
  EXPECT_DOUBLE_EQ(itself.f1, 1.0);

  OcTree16 half(0.05);  // the heard voxels but those of the quay's face left of the beam (y > 0.2 m)
  std::size_t kept = 0;
  for (const Key16& key : occupiedKeys(heard)) {
    const Eigen::Vector3d centre = heard.coder().centerOf(key);
    if (centre.x() > 2.5 && centre.y() > 0.2) continue;
    half.integrate(key, true);
    ++kept;
  }
  const double kept_share = static_cast<double>(kept) / static_cast<double>(stats.voxels);
  ASSERT_GT(kept_share, 0.2);
  ASSERT_LT(kept_share, 0.8);
  const GroundTruthReport half_truth = evaluateAgainstScene(half, scene);
  const HeardSurfaceScore part = scoreAgainstHeardSurface(half, half_truth, heard);
  EXPECT_GE(part.heard_voxels_found, kept);  // what is kept, and its rim within T of the removed voxels
  EXPECT_LT(part.recall, kept_share + 0.05);
  EXPECT_DOUBLE_EQ(part.f1, 2.0 * half_truth.precision * part.recall / (half_truth.precision + part.recall));

  OcTree16 water(0.05);  // free voxels only: known, nothing occupied
  for (int i = 0; i < 20; ++i) water.integrate(water.coder().keyOfChecked({0.05 * i, 0.0, 0.0}), false);
  const GroundTruthReport water_truth = evaluateAgainstScene(water, scene);
  const HeardSurfaceScore nothing = scoreAgainstHeardSurface(water, water_truth, heard);
  EXPECT_EQ(nothing.heard_voxels, stats.voxels);
  EXPECT_EQ(nothing.heard_voxels_found, 0U);
  EXPECT_DOUBLE_EQ(nothing.recall, 0.0);
  EXPECT_DOUBLE_EQ(nothing.f1, 0.0);
}

}  // namespace
}  // namespace sonarmap
