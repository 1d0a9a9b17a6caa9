// The flat seabed's echo in closed form (sonar_equation.hpp): Lambert under a 20 log r TVG falls
// as h² / r³, it is the sonar equation's pulse-limited annulus (pattern × Lambert × area over the
// beam's equivalent solid angle), and it is 0 where the seabed is out of reach. Against the
// simulator: tests/sim/test_sonar_equation.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sonarmap/acoustics/backscatter.hpp"
#include "sonarmap/acoustics/beam_pattern.hpp"
#include "sonarmap/acoustics/ensonified_area.hpp"
#include "sonarmap/acoustics/receiver_model.hpp"
#include "sonarmap/acoustics/sonar_equation.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// A Micron-like head (sim/sonar_presets.hpp): a 35° flat-topped fan, 5 cm pulse, 5 m over 399
/// bins, with 78 cells across the fan.
FlatSeabedHead micronLike() { return FlatSeabedHead{{35.0 * kDegree, 8.0}, {78, 1.5}, 0.05, 5.0 / 399.0}; }

TEST(acousticsSonarEquation, FlatSeabedFollowsLambertAndTheGeometry) {
  const FlatSeabedHead head = micronLike();
  // Lambert under a 20 log r TVG: ∝ h² / r³ where the vertical pattern is flat (depressions of
  // 5.7–7.2°, where this pattern is within 0.01 dB of its axis).
  const double near = flatSeabedEchoPower(head, FlatSeabed{0.5, 0.5}, 4.0);
  const double far = flatSeabedEchoPower(head, FlatSeabed{0.5, 0.5}, 5.0);
  EXPECT_NEAR(10.0 * std::log10(near / far), 30.0 * std::log10(5.0 / 4.0), 0.05);
  const double higher = flatSeabedEchoPower(head, FlatSeabed{0.6, 0.5}, 5.0);
  EXPECT_NEAR(10.0 * std::log10(higher / far), 20.0 * std::log10(1.2), 0.05);
  // Proportional to the reflectivity; nothing nearer than the altitude or below the lowest cell.
  EXPECT_NEAR(flatSeabedEchoPower(head, FlatSeabed{0.5, 0.25}, 5.0), 0.5 * far, 1e-15);
  EXPECT_EQ(flatSeabedEchoPower(head, FlatSeabed{1.0, 0.5}, 0.9), 0.0);
  EXPECT_EQ(flatSeabedEchoPower(head, FlatSeabed{1.0, 0.5}, 1.01), 0.0);
  // A steeper law (k = 3) gives a weaker echo at low grazing: sin ψ = 0.1 lower.
  EXPECT_NEAR(flatSeabedEchoPower(head, FlatSeabed{0.5, 0.5, 3.0}, 5.0) / far, 0.1, 1e-12);
}

TEST(acousticsSonarEquation, FlatSeabedIsThePulseLimitedAnnulusOfTheSonarEquation) {
  const FlatSeabedHead head = micronLike();
  const FlatSeabed seabed{2.0, 0.5, 2.0};
  const BeamPattern horizontal{3.0 * kDegree, 2.0};
  const double width_rad = equivalentBeamWidth_rad(horizontal);  // Φ_h, cancels
  const double solid_angle_sr = width_rad * elevationPatternIntegral(head.vertical, head.vertical_sampling);
  const double pulse_m = pulseBins(head.pulse_length_m, head.bin_length_m) * head.bin_length_m;
  for (const double tilt_rad : {0.0, 25.0 * kDegree}) {
    int checked = 0;
    for (double range_m = 2.5; range_m < 10.0; range_m += 0.5) {
      const double grazing_rad = std::asin(seabed.altitude_m / range_m);
      const double elevation_rad = tilt_rad - grazing_rad;
      const double closed_form = flatSeabedEchoPower(head, seabed, range_m, tilt_rad);
      if (std::abs(elevation_rad) > 0.75 * head.vertical.width_rad) {
        EXPECT_EQ(closed_form, 0.0) << range_m;
        continue;
      }
      const double sonar_equation =
          surfaceEchoPower(twoWayPattern(head.vertical, elevation_rad),
                           lambertScatter(seabed.reflectivity, std::sin(grazing_rad), seabed.lambert_exponent),
                           pulseLimitedArea_m2(range_m, grazing_rad, pulse_m, width_rad, elevation_rad), range_m,
                           solid_angle_sr);
      EXPECT_NEAR(closed_form / sonar_equation, 1.0, 1e-12) << tilt_rad << " " << range_m;
      ++checked;
    }
    EXPECT_GE(checked, 5) << tilt_rad;
  }
}

TEST(acousticsSonarEquation, RejectsInvalidArguments) {
  const FlatSeabedHead head = micronLike();
  EXPECT_THROW(flatSeabedEchoPower(head, FlatSeabed{0.0, 0.5}, 5.0), ValueError);
  EXPECT_THROW(flatSeabedEchoPower(head, FlatSeabed{1.0, 1.5}, 5.0), ValueError);
  EXPECT_THROW(flatSeabedEchoPower(head, FlatSeabed{1.0, 0.5, 0.5}, 5.0), ValueError);
  EXPECT_THROW(flatSeabedEchoPower(head, FlatSeabed{1.0, 0.5}, 0.0), ValueError);
  EXPECT_THROW(flatSeabedEchoPower(head, FlatSeabed{1.0, 0.5}, 5.0, -0.1), ValueError);
  EXPECT_THROW(flatSeabedEchoPower(head, FlatSeabed{1.0, 0.5}, 5.0, 0.5 * std::numbers::pi), ValueError);
  FlatSeabedHead no_pulse = head;
  no_pulse.pulse_length_m = 0.0;
  EXPECT_THROW(flatSeabedEchoPower(no_pulse, FlatSeabed{1.0, 0.5}, 5.0), ValueError);
  EXPECT_THROW(surfaceEchoPower(1.5, 1.0, 1.0, 1.0, 1.0), ValueError);
  EXPECT_THROW(surfaceEchoPower(1.0, 1.0, 1.0, 1.0, 0.0), ValueError);
}

}  // namespace
}  // namespace sonarmap
