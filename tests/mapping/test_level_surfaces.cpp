// Level surfaces mapped from pooled looks (mapping/level_surfaces.hpp): a tilted head's beams
// whose cells are loud where their shells cross a sloping plane put that plane's columns at its
// height, and nowhere else; water alone (speckle) calls almost no column heard; the tilted loop
// over quay3d maps its seabed and its water surface where they were heard.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/mapping/level_surfaces.hpp"

namespace sonarmap {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// A head 3 m above the map origin, its sonar frame (x ahead, y starboard, z down) pitched 25°
/// down in the map frame (x north, y west, z up), turning about its own z.
Eigen::Isometry3d tiltedHead() {
  Eigen::Isometry3d sonar_to_map = Eigen::Isometry3d::Identity();
  sonar_to_map.translation() = Eigen::Vector3d(0.0, 0.0, 3.0);
  const Eigen::Matrix3d frd_to_nwu = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  sonar_to_map.linear() = frd_to_nwu * Eigen::AngleAxisd(-25.0 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return sonar_to_map;
}

/// Where the axis-plane ray of elevation `e_rad` of the beam at `bearing_rad` meets `plane`, range.
double crossingRange_m(const Eigen::Isometry3d& sonar_to_map, double bearing_rad, double e_rad, const LevelPlane& plane) {
  const Eigen::Vector3d u = sonar_to_map.linear() *
                            Eigen::Vector3d(std::cos(e_rad) * std::cos(bearing_rad), std::cos(e_rad) * std::sin(bearing_rad), std::sin(e_rad));
  const double closing = -plane.normal.dot(u);
  const double height_m = plane.normal.dot(sonar_to_map.translation() - plane.point_m);
  return closing > 0.0 ? height_m / closing : INFINITY;
}

TEST(mappingLevelSurfaces, LoudCellsWhereTheShellsCrossASlopePutItsColumnsOnIt) {
  const double res_m = 0.05, width_rad = 3.0 * kDeg, aperture_rad = 35.0 * kDeg;
  const Eigen::Isometry3d head = tiltedHead();
  // A seabed sloping 7° down to the north, 5 m under the origin.
  const LevelPlane seabed{{0.0, 0.0, -2.0}, Eigen::Vector3d(std::sin(7.0 * kDeg), 0.0, std::cos(7.0 * kDeg))};
  LevelSurfaceEvidence evidence(res_m);
  const std::size_t cells = 200;  // 10 m
  for (int b = 0; b < 400; ++b) {
    const double bearing_rad = 2.0 * std::numbers::pi * b / 400.0;
    // The cells loud from where the aperture's lower edge meets the seabed to where its upper edge does.
    const double near_m = crossingRange_m(head, bearing_rad, 0.5 * aperture_rad, seabed);
    const double far_m = crossingRange_m(head, bearing_rad, -0.5 * aperture_rad, seabed);
    std::vector<float> power(cells, 1.0f);
    for (std::size_t k = 0; k < cells; ++k) {
      const double range_m = (static_cast<double>(k) + 0.5) * res_m;
      if (range_m >= near_m && range_m <= far_m) power[k] = 10.0f;
    }
    evidence.addBeam(head, bearing_rad, width_rad, aperture_rad, power, 4.0, seabed);
  }
  std::size_t heard = 0;
  double worst_m = 0.0;
  evidence.drainHeard([&](const Eigen::Vector3d& point_m) {
    ++heard;
    worst_m = std::max(worst_m, std::abs(seabed.normal.dot(point_m - seabed.point_m)));
  });
  EXPECT_GT(heard, 1000U);
  EXPECT_LT(worst_m, 1e-9);  // every heard column on the plane
  EXPECT_EQ(heard, evidence.heardColumns());
  std::size_t again = 0;
  evidence.drainHeard([&](const Eigen::Vector3d&) { ++again; });
  EXPECT_EQ(again, 0U);  // each column is reported once
}

TEST(mappingLevelSurfaces, WaterAloneCallsAlmostNoColumnHeard) {
  const double res_m = 0.05, width_rad = 3.0 * kDeg, aperture_rad = 35.0 * kDeg;
  const Eigen::Isometry3d head = tiltedHead();
  const LevelPlane seabed{{0.0, 0.0, -2.0}, Eigen::Vector3d::UnitZ()};
  const int bins_per_cell = 4;
  LevelSurfaceEvidence evidence(res_m);
  std::mt19937_64 random(7);
  std::exponential_distribution<double> speckle(1.0);
  for (int sweep = 0; sweep < 3; ++sweep) {
    for (int b = 0; b < 400; ++b) {
      std::vector<float> power(200);
      for (float& cell : power) {  // the mean of four exponential bins of mean 1
        double sum = 0.0;
        for (int i = 0; i < bins_per_cell; ++i) sum += speckle(random);
        cell = static_cast<float>(sum / bins_per_cell);
      }
      evidence.addBeam(head, 2.0 * std::numbers::pi * b / 400.0, width_rad, aperture_rad, power, bins_per_cell, seabed);
    }
  }
  ASSERT_GT(evidence.columns(), 10000U);
  // The sequential test's false alarm is at most α = 10⁻³ per column however many looks it gets
  // (twice that here: the count itself scatters by its square root).
  EXPECT_LE(static_cast<double>(evidence.heardColumns()), 2e-3 * static_cast<double>(evidence.columns()));
}

TEST(mappingLevelSurfaces, InvalidParametersAreRefused) {
  EXPECT_THROW(LevelSurfaceEvidence(0.0), ValueError);
  EXPECT_THROW(LevelSurfaceEvidence(0.05, NAN), ValueError);
  EXPECT_THROW(LevelSurfaceEvidence(0.05, 0.0, 0.0), ValueError);
  EXPECT_THROW(LevelSurfaceEvidence(0.05, 0.0, 0.5), ValueError);
  LevelSurfaceEvidence evidence(0.05);
  const std::vector<float> power(10, 1.0f);
  EXPECT_THROW(evidence.addBeam(tiltedHead(), 0.0, 0.05, 0.6, power, 0.5, LevelPlane{}), ValueError);
}

// The tilted loop over quay3d: the seabed (primitive 1) and the water surface (primitive 0) are
// found where every beam's looks at them, pooled, say they were heard.
TEST(mappingLevelSurfaces, TheTiltedLoopMapsItsSeabedAndItsWaterSurface) {
  MapperOptions options;
  options.resolution_m = 0.05;
  options.beam_model = BeamModel::kVolume;
  const MissionAccuracy accuracy = evaluateMission(SimulatedMission{"micron", "quay3d", "tilted-loop"}, options);
  auto recall = [&](std::size_t primitive) {
    for (const SurfaceRecall& surface : accuracy.truth.recall_by_surface) {
      if (surface.primitive == primitive) {
        return static_cast<double>(surface.found_voxels) / static_cast<double>(surface.visible_voxels);
      }
    }
    return 0.0;
  };
  // 0.660 and 0.310 when written; 0.630 and 0.266 from the level traces alone.
  EXPECT_GT(recall(1), 0.645);
  EXPECT_GT(recall(0), 0.29);
  EXPECT_GT(accuracy.truth.precision, 0.70);  // 0.707
}

}  // namespace
}  // namespace sonarmap
