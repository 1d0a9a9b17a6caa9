// What a simulated head hears of each surface (echo_levels.hpp): a flat seabed's level over the
// receiver's floor follows the sonar equation's closed form (sonar_equation.hpp), each primitive's
// echo stays in its own bins, and bad options are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/echo_levels.hpp"
#include "sonarmap/sim/sonar_equation.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// The Micron preset with vertical rays dense enough (W / 60) for a seabed's footprints to overlap.
SonarPreset denseMicron() {
  SonarPreset preset = sonarPreset("micron");
  preset.echo.vertical.rays = std::max(preset.echo.vertical.rays, 78);
  return preset;
}

// A head tilted 25° down 1.5 m over a flat seabed of reflectivity 0.5, its beam looking the way it
// tilts: in every bin from where the seabed enters the flat of the pattern to the range's end, the
// level is the closed form's power over the larger of the mean noise and the A/D floor, within the
// 1.25 dB the simulated log itself keeps to the closed form (test_sonar_equation.cpp).
TEST(simEchoLevels, AFlatSeabedsLevelFollowsTheSonarEquation) {
  const SonarPreset preset = denseMicron();
  const double altitude_m = 1.5, tilt_rad = 25.0 * kDegree;
  const Scene seabed{{Plane{{0.0, 0.0, -altitude_m}, Eigen::Vector3d::UnitZ(), 0.5}}};
  const EchoLevels levels(seabed, preset.head, preset.echo);
  Eigen::Isometry3d tilted = Eigen::Isometry3d::Identity();
  tilted.linear() = Eigen::AngleAxisd(tilt_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();  // x towards −z
  std::vector<std::vector<double>> levels_db;
  levels.levels(tilted, 0.0, levels_db);
  ASSERT_EQ(levels_db.size(), 1U);
  ASSERT_EQ(levels_db[0].size(), static_cast<std::size_t>(preset.head.bins));
  const double bin_m = preset.head.binLength_m();
  const double converter_floor = std::pow(10.0, preset.echo.ad_low_db / 10.0);
  int checked = 0;
  // The seabed meets the aperture's −3 dB lower edge (42.5° down) at 2.2 m, the axis at 3.5 m.
  for (double range_m = 2.4; range_m < 0.95 * preset.head.range_m; range_m += 0.2) {
    const auto bin = static_cast<std::size_t>(range_m / bin_m);
    const double centre_m = (static_cast<double>(bin) + 0.5) * bin_m;
    const double expected_db =
        10.0 * std::log10(flatSeabedEchoPower(preset.head, preset.echo, altitude_m, 0.5, centre_m, tilt_rad) /
                          std::max(meanNoisePower(preset.echo, centre_m), converter_floor));
    EXPECT_NEAR(levels_db[0][bin], expected_db, 1.25) << "range " << centre_m << " m";
    ++checked;
  }
  EXPECT_GE(checked, 10);
  // Nearer than where the seabed enters the rays' extent, nothing is heard.
  EXPECT_EQ(levels_db[0][static_cast<std::size_t>(1.0 / bin_m)], -std::numeric_limits<double>::infinity());
  EXPECT_EQ(levels.floorPower().size(), levels_db[0].size());
}

// Each primitive's echo stays in the bins its own surface covers: a level head over a seabed 2 m
// down hears a loud quay face 3 m ahead from 3 m on, and no seabed before the seabed enters its
// rays' extent; the face's level stands tens of dB over the floor.
TEST(simEchoLevels, EachSurfaceKeepsToItsOwnBins) {
  const SonarPreset preset = denseMicron();
  const Scene scene{{Plane{{0.0, 0.0, -2.0}, Eigen::Vector3d::UnitZ(), 0.5},
                     Box{{3.5, 0.0, -1.0}, {1.0, 4.0, 4.0}, 0.0, 0.9}}};
  const EchoLevels levels(scene, preset.head, preset.echo);
  std::vector<std::vector<double>> levels_db;
  levels.levels(Eigen::Isometry3d::Identity(), 0.0, levels_db);
  ASSERT_EQ(levels_db.size(), 2U);
  const double bin_m = preset.head.binLength_m();
  const auto face_bin = static_cast<std::size_t>(3.0 / bin_m);
  for (std::size_t i = 0; i + 1 < face_bin; ++i) {
    EXPECT_EQ(levels_db[1][i], -std::numeric_limits<double>::infinity()) << "bin " << i;
  }
  EXPECT_GT(levels_db[1][face_bin + 1], 20.0);
  // The rays span ±0.75 W (26°) below the level: the seabed 2 m down enters them at 4.5 m.
  const double seabed_first_m = 2.0 / std::sin(0.5 * preset.echo.vertical.extent * preset.head.vertical_beam_width_rad);
  for (std::size_t i = 0; i < static_cast<std::size_t>(0.98 * seabed_first_m / bin_m); ++i) {
    EXPECT_EQ(levels_db[0][i], -std::numeric_limits<double>::infinity()) << "bin " << i;
  }
}

TEST(simEchoLevels, InvalidOptionsAreRefused) {
  const SonarPreset preset = sonarPreset("micron");
  const Scene seabed{{Plane{{0.0, 0.0, -2.0}, Eigen::Vector3d::UnitZ(), 0.5}}};
  MsisHeadOptions head = preset.head;
  head.range_m = 0.0;
  EXPECT_THROW(EchoLevels(seabed, head, preset.echo), ValueError);
  EchoModelOptions echo = preset.echo;
  echo.pulse_length_m = -1.0;
  EXPECT_THROW(EchoLevels(seabed, preset.head, echo), ValueError);
  const Scene broken{{Plane{{0.0, 0.0, -2.0}, Eigen::Vector3d::UnitZ(), 1.5}}};
  EXPECT_THROW(EchoLevels(broken, preset.head, preset.echo), ValueError);
}

}  // namespace
}  // namespace sonarmap
