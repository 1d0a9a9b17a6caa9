/// Tests of splitSweeps: full turns, wraps through bearing 0, sector reversals, range changes, real data.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "sonarmap/formats/mat_reader.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {
namespace {

constexpr double kPi = std::numbers::pi;

/// Beams at the given bearings in degrees (wrapped to [0, 360)), 10 bins of 1 cm.
std::vector<Beam> beamsAt(const std::vector<double>& bearings_deg, double bin_length_m = 0.01) {
  std::vector<Beam> beams;
  for (double deg : bearings_deg) {
    double wrapped = std::fmod(deg, 360.0);
    if (wrapped < 0.0) wrapped += 360.0;
    beams.push_back(Beam{static_cast<double>(beams.size()), wrapped * kPi / 180.0, bin_length_m,
                         std::vector<std::uint8_t>(10, 0)});
  }
  return beams;
}

std::vector<double> steps(double start_deg, double step_deg, int count) {
  std::vector<double> out;
  for (int i = 0; i < count; ++i) out.push_back(start_deg + step_deg * i);
  return out;
}

TEST(sonarSweeps, EmptyAndSingleBeam) {
  EXPECT_TRUE(splitSweeps({}).empty());
  EXPECT_EQ(splitSweeps(beamsAt({42.0})), (std::vector<SweepRange>{{0, 1}}));
}

TEST(sonarSweeps, FullTurnsStartingAtZero) {
  // 2.5 turns of 1.8° steps from 0°: sweeps of 200, 200 and 100 beams.
  const auto sweeps = splitSweeps(beamsAt(steps(0.0, 1.8, 500)));
  EXPECT_EQ(sweeps, (std::vector<SweepRange>{{0, 200}, {200, 400}, {400, 500}}));
}

TEST(sonarSweeps, FullTurnsDoNotDependOnWhereBearingZeroIs) {
  // Starting at 100°: the bearing wraps through 0 inside each sweep, which still holds a full turn.
  const auto sweeps = splitSweeps(beamsAt(steps(100.0, 1.8, 450)));
  EXPECT_EQ(sweeps, (std::vector<SweepRange>{{0, 200}, {200, 400}, {400, 450}}));
}

TEST(sonarSweeps, ClockwiseRotationWraps) {
  const auto sweeps = splitSweeps(beamsAt(steps(0.0, -3.6, 250)));
  EXPECT_EQ(sweeps, (std::vector<SweepRange>{{0, 100}, {100, 200}, {200, 250}}));
}

TEST(sonarSweeps, SectorScanEndsWhereRotationReverses) {
  // A 90° sector around bearing 0 (−45°…45°, so it crosses the wrap), 0.9° steps, there and back.
  std::vector<double> bearings = steps(-45.0, 0.9, 101);                 // −45 … 45
  for (double b : steps(45.0 - 0.9, -0.9, 100)) bearings.push_back(b);   // 44.1 … −45
  for (double b : steps(-45.0 + 0.9, 0.9, 50)) bearings.push_back(b);    // −44.1 … 0
  const auto sweeps = splitSweeps(beamsAt(bearings));
  EXPECT_EQ(sweeps, (std::vector<SweepRange>{{0, 101}, {101, 201}, {201, 251}}));
}

TEST(sonarSweeps, RepeatedBearingAtTheTurnDoesNotReverse) {
  const auto sweeps = splitSweeps(beamsAt({0.0, 1.0, 2.0, 2.0, 1.0, 0.0}));
  EXPECT_EQ(sweeps, (std::vector<SweepRange>{{0, 4}, {4, 6}}));
}

TEST(sonarSweeps, BinLengthChangeStartsASweep) {
  auto beams = beamsAt(steps(0.0, 1.8, 20));
  for (std::size_t i = 10; i < beams.size(); ++i) beams[i].bin_length_m = 0.02;
  EXPECT_EQ(splitSweeps(beams), (std::vector<SweepRange>{{0, 10}, {10, 20}}));
}

TEST(sonarSweeps, WholeSweepsAreFullTurnsWhereverTheyBegin) {
  // From 100°: two full turns (each wraps through 0) and 50 beams cut by the end of the log.
  const auto beams = beamsAt(steps(100.0, 1.8, 450));
  EXPECT_EQ(wholeSweepFlags(beams, splitSweeps(beams)), (std::vector<bool>{true, true, false}));
  EXPECT_EQ(wholeSweeps(beams), (std::vector<SweepRange>{{0, 200}, {200, 400}}));
  const auto clockwise = beamsAt(steps(0.0, -3.6, 250));
  EXPECT_EQ(wholeSweeps(clockwise), (std::vector<SweepRange>{{0, 100}, {100, 200}}));
}

TEST(sonarSweeps, WholeSectorPassesRunFromTurnToTurn) {
  // Begun mid-sector (0° → 45°), then 45° → −45° and back to 45°, then cut at 0°: only the two
  // passes between turning points are whole.
  std::vector<double> bearings = steps(0.0, 0.9, 51);                    // 0 … 45
  for (double b : steps(45.0 - 0.9, -0.9, 100)) bearings.push_back(b);   // 44.1 … −45
  for (double b : steps(-45.0 + 0.9, 0.9, 100)) bearings.push_back(b);   // −44.1 … 45
  for (double b : steps(45.0 - 0.9, -0.9, 50)) bearings.push_back(b);    // 44.1 … 0
  const auto beams = beamsAt(bearings);
  const auto sweeps = splitSweeps(beams);
  ASSERT_EQ(sweeps.size(), 4u);
  EXPECT_EQ(wholeSweepFlags(beams, sweeps), (std::vector<bool>{false, true, true, false}));
}

TEST(sonarSweeps, ASweepCutByARangeChangeIsNotWhole) {
  auto beams = beamsAt(steps(0.0, 1.8, 300));
  for (std::size_t i = 100; i < beams.size(); ++i) beams[i].bin_length_m = 0.02;
  // 100 beams at 1 cm, then a full turn and 0 more at 2 cm.
  EXPECT_EQ(wholeSweeps(beams), (std::vector<SweepRange>{{100, 300}}));
}

TEST(sonarSweeps, RealCrasLogHas28FullSweepsAndAPartialOne) {
  const std::string path = std::string(SONARMAP_SHARED_DATA) + "/cras_micron_tank_static.mat";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no shared data at " << path;
  const SonarLog log = readCrasMat(path);
  const auto sweeps = splitSweeps(log.beams);
  ASSERT_EQ(sweeps.size(), 29u);
  for (std::size_t s = 0; s < 28; ++s) {
    EXPECT_EQ(sweeps[s].size(), 200u) << "sweep " << s;
    EXPECT_NEAR(log.beams[sweeps[s].first].bearing_rad, 0.0, 1e-6) << "sweep " << s;
  }
  EXPECT_EQ(sweeps[28].size(), 3u);  // 5,603 = 28 × 200 + 3
  EXPECT_EQ(sweeps.back().last_exclusive, log.beams.size());
  const auto whole = wholeSweepFlags(log.beams, sweeps);
  EXPECT_EQ(std::count(whole.begin(), whole.end(), true), 28);
  EXPECT_FALSE(whole.back());
}

}  // namespace
}  // namespace sonarmap
