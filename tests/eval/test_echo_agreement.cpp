// echoAgreement: exact shares on a hand-made log of a straight wall and hand-made maps; what is
// not a strong echo (a ring at one range in every bearing, a weak rise); placed beams; errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/echo_agreement.hpp"

namespace sonarmap {
namespace {

constexpr double kBin = 0.02;        // metres
constexpr std::size_t kBins = 250;   // 5 m
constexpr double kWallX = 2.0;       // the wall x = 2 m
constexpr int kBeams = 61;           // bearings −30°…+30°, 1° apart
constexpr std::uint8_t kWater = 20;  // counts
constexpr std::uint8_t kEcho = 200;  // counts: (200 − 20) / 255 · 45 dB = 31.8 dB above the water

double bearingOf(int i) { return (i - kBeams / 2) * std::numbers::pi / 180.0; }

/// Beams of a sonar at the origin facing the wall x = 2 m; each beam's echo is the bin of its range
/// 2 / cos(bearing) (different in each beam, so the median of every range stays the water's), and
/// every beam has a ring at bin 10 (0.2 m) as strong as the echo.
SonarLog wallLog() {
  SonarLog log;
  for (int i = 0; i < kBeams; ++i) {
    Beam beam;
    beam.time_s = 0.1 * i;
    beam.bearing_rad = std::fmod(bearingOf(i) + 2.0 * std::numbers::pi, 2.0 * std::numbers::pi);
    beam.bin_length_m = kBin;
    beam.intensities.assign(kBins, kWater);
    beam.intensities[10] = kEcho;
    beam.intensities[static_cast<std::size_t>(kWallX / std::cos(bearingOf(i)) / kBin)] = kEcho;
    log.beams.push_back(beam);
  }
  return log;
}

/// Where beam i's echo lies (its bin's centre on the beam's axis).
Eigen::Vector3d echoPoint(int i) {
  const double range_m = (std::floor(kWallX / std::cos(bearingOf(i)) / kBin) + 0.5) * kBin;
  return {range_m * std::cos(bearingOf(i)), range_m * std::sin(bearingOf(i)), 0.0};
}

void setOccupied(OcTree16& map, const Eigen::Vector3d& point_m) { map.updateNode(map.coder().keyOfChecked(point_m), 4.0F); }

TEST(evalEchoAgreement, AMapOfTheWallAgreesWithItsEchoesAndNotWithTheRing) {
  const SonarLog log = wallLog();
  OcTree16 map(0.05);
  for (int i = 0; i < kBeams; ++i) setOccupied(map, echoPoint(i));
  const EchoAgreement a = echoAgreement(map, log);
  EXPECT_EQ(a.echo_points, static_cast<std::size_t>(kBeams));  // the ring is every beam's median: no echo
  EXPECT_EQ(a.beams_with_echo, static_cast<std::size_t>(kBeams));
  EXPECT_GT(a.occupied, 0U);
  EXPECT_DOUBLE_EQ(a.precision, 1.0);
  EXPECT_DOUBLE_EQ(a.recall, 1.0);
  EXPECT_DOUBLE_EQ(a.first_echo_recall, 1.0);
}

TEST(evalEchoAgreement, VoxelsAwayFromEchoesLowerPrecisionAndMissingWallLowersRecall) {
  const SonarLog log = wallLog();
  OcTree16 map(0.05);
  // Only the beams of negative bearing (30 of 61) are mapped, plus 10 voxels 1 m in front of the wall.
  for (int i = 0; i < kBeams / 2; ++i) setOccupied(map, echoPoint(i));
  for (int k = 0; k < 10; ++k) setOccupied(map, {1.0, -0.5 + 0.1 * k, 0.0});
  const EchoAgreement a = echoAgreement(map, log);
  const double on_wall = static_cast<double>(a.occupied - 10) / static_cast<double>(a.occupied);
  EXPECT_DOUBLE_EQ(a.precision, on_wall);
  // Recalled: the mapped 30 and the few just past the middle still within 0.3 m of a mapped voxel.
  EXPECT_GT(a.recall, 30.0 / kBeams);
  EXPECT_LT(a.recall, 40.0 / kBeams);
  EXPECT_DOUBLE_EQ(a.first_echo_recall, a.recall);  // one echo per beam: the same points
}

TEST(evalEchoAgreement, AWeakRiseIsNoStrongEchoAndTheToleranceDecides) {
  SonarLog log = wallLog();
  for (Beam& beam : log.beams) {
    for (std::uint8_t& v : beam.intensities) v = v == kEcho ? static_cast<std::uint8_t>(kWater + 100) : v;  // 17.6 dB
  }
  OcTree16 map(0.05);
  setOccupied(map, echoPoint(0));
  EXPECT_EQ(echoAgreement(map, log).echo_points, 0U);
  EchoAgreementOptions weaker;
  weaker.strong_db = 15.0;
  EXPECT_EQ(echoAgreement(map, log, {}, weaker).echo_points, static_cast<std::size_t>(kBeams));
  // The map's one voxel, 0.35 m off along the wall from beam 0's echo: beyond 0.3 m, within 0.5 m.
  OcTree16 shifted(0.05);
  setOccupied(shifted, echoPoint(0) + Eigen::Vector3d(0.0, -0.35, 0.0));
  EXPECT_DOUBLE_EQ(echoAgreement(shifted, log, {}, weaker).precision, 0.0);
  weaker.tolerance_m = 0.5;
  EXPECT_DOUBLE_EQ(echoAgreement(shifted, log, {}, weaker).precision, 1.0);
}

TEST(evalEchoAgreement, PosesPlaceTheEchoesAndUnplacedBeamsAreLeftOut) {
  const SonarLog log = wallLog();
  const Eigen::Isometry3d shift(Eigen::Translation3d(10.0, 5.0, 0.0));
  std::vector<std::optional<Eigen::Isometry3d>> poses(log.beams.size(), shift);
  poses[0] = std::nullopt;
  OcTree16 map(0.05);
  for (int i = 0; i < kBeams; ++i) setOccupied(map, shift * echoPoint(i));
  const EchoAgreement a = echoAgreement(map, log, poses);
  EXPECT_EQ(a.echo_points, static_cast<std::size_t>(kBeams - 1));
  EXPECT_DOUBLE_EQ(a.recall, 1.0);
  EXPECT_DOUBLE_EQ(a.precision, 1.0);  // beam 0's voxel lies 4 cm from beam 1's echo
  EXPECT_DOUBLE_EQ(echoAgreement(map, log).precision, 0.0);  // without the poses: 10 m away from them
}

TEST(evalEchoAgreement, RejectsBadOptionsAndPoseCounts) {
  const SonarLog log = wallLog();
  const OcTree16 map(0.05);
  EchoAgreementOptions bad;
  bad.tolerance_m = 0.0;
  EXPECT_THROW(echoAgreement(map, log, {}, bad), ValueError);
  bad = {};
  bad.strong_db = std::nan("");
  EXPECT_THROW(echoAgreement(map, log, {}, bad), ValueError);
  EXPECT_THROW(echoAgreement(map, log, {Eigen::Isometry3d::Identity()}), ValueError);
  const EchoAgreement empty = echoAgreement(map, log);
  EXPECT_EQ(empty.occupied, 0U);
  EXPECT_DOUBLE_EQ(empty.precision, 0.0);
  EXPECT_DOUBLE_EQ(empty.recall, 0.0);
}

}  // namespace
}  // namespace sonarmap
