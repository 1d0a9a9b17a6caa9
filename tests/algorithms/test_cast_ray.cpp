// castRay: OctoMap's ray-casting check (a 2 m sphere at 5 cm, every direction hits at 2 ± 0.05 m),
// the same hits as OctoMap's castRay, unknown space, range limit, the origin's own voxel, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "octomap_reference.hpp"
#include "sonarmap/algorithms/cast_ray.hpp"
#include "sonarmap/algorithms/point_cloud_insertion.hpp"

namespace sonarmap {
namespace {

using namespace sonarmap::testing;

/// Unit directions on a grid of azimuths × elevations, offset from the sphere's sample grid.
std::vector<Eigen::Vector3d> directions(int azimuths, int elevations) {
  std::vector<Eigen::Vector3d> out;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < azimuths; ++i)
    for (int j = 0; j < elevations; ++j) {
      const double azimuth = 2.0 * pi * (i + 0.25) / azimuths;
      const double elevation = pi * ((j + 0.5) / elevations - 0.5);
      out.emplace_back(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                       std::sin(elevation));
    }
  return out;
}

class algorithmsCastRay : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // OctoMap's test_raycasting: 360 × 360 rays from the origin to a sphere of radius 2 m at 5 cm.
    cloud_ = new PointCloud(sphereCloud({0.0, 0.0, 0.0}, 2.0, 360, 360));
    ours_ = new OcTree16(0.05);
    theirs_ = new octomap::OcTree(0.05);
    insertPointCloud(*ours_, *cloud_, origin());
    theirs_->insertPointCloud(toOctomap(*cloud_), toOctomap(origin()));
  }
  static void TearDownTestSuite() {
    delete cloud_;
    delete ours_;
    delete theirs_;
  }
  static Eigen::Vector3d origin() { return {0.0, 0.0, 0.0}; }

  static PointCloud* cloud_;
  static OcTree16* ours_;
  static octomap::OcTree* theirs_;
};
PointCloud* algorithmsCastRay::cloud_ = nullptr;
OcTree16* algorithmsCastRay::ours_ = nullptr;
octomap::OcTree* algorithmsCastRay::theirs_ = nullptr;

TEST_F(algorithmsCastRay, EveryDirectionHitsTheSphereAtTwoMetres) {
  double sum_m = 0.0;
  std::size_t hits = 0, same_as_octomap = 0;
  const std::vector<Eigen::Vector3d> dirs = directions(360, 360);
  for (const Eigen::Vector3d& dir : dirs) {
    const auto hit = castRay(*ours_, origin(), dir);
    if (!hit) continue;
    ++hits;
    sum_m += hit->norm();
    octomap::point3d end;
    if (theirs_->castRay(toOctomap(origin()), toOctomap(dir), end) && (toOctomap(*hit) - end).norm() < 1e-4) {
      ++same_as_octomap;
    }
  }
  EXPECT_EQ(hits, dirs.size());
  EXPECT_NEAR(sum_m / static_cast<double>(hits), 2.0, 0.05);
  EXPECT_GE(static_cast<double>(same_as_octomap), 0.999 * static_cast<double>(dirs.size()));
  std::printf("[castRay] %zu of %zu directions hit, mean %.4f m, %zu end at OctoMap's voxel\n", hits, dirs.size(),
              sum_m / static_cast<double>(hits), same_as_octomap);
}

TEST_F(algorithmsCastRay, DirectionLengthDoesNotMatter) {
  const Eigen::Vector3d dir(0.3, -0.5, 0.2);
  EXPECT_EQ(*castRay(*ours_, origin(), dir), *castRay(*ours_, origin(), 1000.0 * dir));
}

TEST_F(algorithmsCastRay, RangeLimitAndUnknownSpaceStopTheRay) {
  const Eigen::Vector3d dir(1.0, 0.1, 0.05);
  EXPECT_FALSE(castRay(*ours_, origin(), dir, 1.5).has_value());
  EXPECT_TRUE(castRay(*ours_, origin(), dir, 2.5).has_value());
  // From outside the sphere, into unknown space: nothing, unless unknown space is ignored.
  const Eigen::Vector3d outside(3.0, 0.0, 0.0);
  EXPECT_FALSE(castRay(*ours_, outside, {1.0, 0.0, 0.0}).has_value());
  EXPECT_FALSE(castRay(*ours_, outside, {1.0, 0.0, 0.0}, -1.0, true).has_value());  // reaches the border
  const auto back = castRay(*ours_, outside, {-1.0, 0.0, 0.0}, -1.0, true);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->x(), 2.0, 0.05);
  octomap::point3d end;
  EXPECT_TRUE(theirs_->castRay(toOctomap(outside), {-1.0F, 0.0F, 0.0F}, end, true));
  EXPECT_NEAR((toOctomap(*back) - end).norm(), 0.0, 1e-4);
}

TEST_F(algorithmsCastRay, AnOccupiedOriginVoxelIsTheHit) {
  const Eigen::Vector3d on_sphere = cloud_->front();
  const auto hit = castRay(*ours_, on_sphere, {0.0, 0.0, 1.0});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(*hit, ours_->coder().centerOf(*ours_->coder().keyOf(on_sphere)));
}

TEST_F(algorithmsCastRay, BadInputThrows) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(castRay(*ours_, origin(), {0.0, 0.0, 0.0}), ValueError);
  EXPECT_THROW(castRay(*ours_, origin(), {nan, 0.0, 1.0}), ValueError);
  EXPECT_THROW(castRay(*ours_, origin(), {1.0, 0.0, 0.0}, nan), ValueError);
  EXPECT_THROW(castRay(*ours_, {5000.0, 0.0, 0.0}, {1.0, 0.0, 0.0}), OutOfMapError);
}

}  // namespace
}  // namespace sonarmap
