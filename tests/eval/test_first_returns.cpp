/// Tests of a log's first returns and how many a map holds (eval/first_returns.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/first_returns.hpp"

namespace sonarmap {
namespace {

constexpr double kBinLength_m = 0.05;

/// A beam of 200 bins (10 m) of water at 2 counts with a near-field band of 100 counts in its first
/// 0.5 m, at `bearing_rad`.
Beam waterBeam(double bearing_rad) {
  Beam beam;
  beam.bearing_rad = bearing_rad;
  beam.bin_length_m = kBinLength_m;
  beam.intensities.assign(200, 2);
  for (int c = 0; c < 10; ++c) beam.intensities[static_cast<std::size_t>(c)] = 100;
  return beam;
}

TEST(evalFirstReturns, FindsStepsAndPeaksButNotTheNearFieldOrShortSpikes) {
  SonarLog log;
  Beam step = waterBeam(0.0);  // a step into reverberation at 5.8 m (bin 116), 60 counts to the end
  for (std::size_t c = 116; c < 200; ++c) step.intensities[c] = 60;
  Beam peak = waterBeam(0.5);  // a wall's peak at 3 m (bin 60): 0.25 m of 150 counts, then water
  for (std::size_t c = 60; c < 65; ++c) peak.intensities[c] = 150;
  Beam spike = waterBeam(1.0);  // one loud bin is not a return that stays up
  spike.intensities[80] = 250;
  Beam faint = waterBeam(1.5);  // a step of 4 dB (23 counts at 45 dB) is below the 6 dB rise
  for (std::size_t c = 100; c < 200; ++c) faint.intensities[c] = 25;
  log.beams = {step, peak, spike, faint, waterBeam(2.0)};
  const FirstReturnScore found = findFirstReturns(log);
  ASSERT_EQ(found.returns.size(), 2u);
  EXPECT_EQ(found.returns[0].beam, 0u);
  EXPECT_DOUBLE_EQ(found.returns[0].range_m, 116 * kBinLength_m);
  EXPECT_EQ(found.returns[1].beam, 1u);
  EXPECT_DOUBLE_EQ(found.returns[1].range_m, 60 * kBinLength_m);
  FirstReturnOptions lower;
  lower.rise_db = 3.0;
  EXPECT_EQ(findFirstReturns(log, lower).returns.size(), 3u) << "the faint step rises 4 dB";
}

TEST(evalFirstReturns, AReturnIsMappedWhereAnOccupiedVoxelLiesInItsWedge) {
  SonarLog log;
  Beam step = waterBeam(0.0);
  for (std::size_t c = 116; c < 200; ++c) step.intensities[c] = 60;
  Beam other = waterBeam(std::numbers::pi / 2.0);
  for (std::size_t c = 60; c < 200; ++c) other.intensities[c] = 90;
  log.beams = {step, other};
  OcTree16 map(0.05);
  const FirstReturnScore empty = firstReturns(map, log);
  EXPECT_EQ(empty.returns.size(), 2u);
  EXPECT_EQ(empty.mapped, 0u);
  EXPECT_EQ(empty.share(), 0.0);
  // An occupied voxel at the step's range on bearing 0 (within the tolerance, in the wedge).
  map.integrate(map.coder().keyOfChecked(Eigen::Vector3d(5.82, 0.05, 0.0)), true);
  const FirstReturnScore one = firstReturns(map, log);
  EXPECT_EQ(one.mapped, 1u);
  EXPECT_TRUE(one.returns[0].mapped);
  EXPECT_FALSE(one.returns[1].mapped);
  EXPECT_DOUBLE_EQ(one.share(), 0.5);
  // The same voxel seen from a sonar moved 1 m along x is 1 m too near: not mapped.
  const std::vector<std::optional<Eigen::Isometry3d>> poses{Eigen::Isometry3d(Eigen::Translation3d(1.0, 0.0, 0.0)),
                                                             std::nullopt};
  const FirstReturnScore moved = firstReturns(map, log, poses);
  EXPECT_EQ(moved.beams, 1u) << "a beam without a pose is not placed";
  ASSERT_EQ(moved.returns.size(), 1u);
  EXPECT_FALSE(moved.returns[0].mapped);
}

TEST(evalFirstReturns, RejectsBadOptionsAndPoses) {
  SonarLog log;
  log.beams = {waterBeam(0.0)};
  FirstReturnOptions bad;
  bad.rise_db = 0.0;
  EXPECT_THROW(findFirstReturns(log, bad), ValueError);
  bad = FirstReturnOptions{};
  bad.beam_width_rad = std::numbers::pi;
  EXPECT_THROW(findFirstReturns(log, bad), ValueError);
  OcTree16 map(0.05);
  EXPECT_THROW(firstReturns(map, log, std::vector<std::optional<Eigen::Isometry3d>>(2)), ValueError);
}

}  // namespace
}  // namespace sonarmap
