// Spreading, absorption and the TVG (propagation.hpp), and the ensonified areas
// (ensonified_area.hpp): the TVG restores 20 log r + 2αr, so an extended surface's echo after it
// does not depend on range; Urick's pulse-limited area for a level head.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "sonarmap/acoustics/ensonified_area.hpp"
#include "sonarmap/acoustics/propagation.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(acousticsPropagation, TransmissionLossIsSphericalSpreadingPlusAbsorption) {
  EXPECT_NEAR(oneWayTransmissionLoss_db(1.0, 0.15), 0.15, 1e-15);
  EXPECT_NEAR(oneWayTransmissionLoss_db(10.0, 0.0), 20.0, 1e-13);
  EXPECT_NEAR(oneWayTransmissionLoss_db(100.0, 0.1), 40.0 + 10.0, 1e-12);
  for (const double range_m : {0.3, 4.0, 50.0}) {
    EXPECT_NEAR(-10.0 * std::log10(twoWayTransmissionFactor(range_m, 0.15)), 2.0 * oneWayTransmissionLoss_db(range_m, 0.15),
                1e-11)
        << range_m;
  }
}

TEST(acousticsPropagation, TvgRestoresTwentyLogRPlusTwoAlphaR) {
  for (const double range_m : {0.5, 3.0, 30.0}) {
    for (const double absorption_db_per_m : {0.0, 0.06, 0.2}) {
      EXPECT_NEAR(10.0 * std::log10(tvgGain(range_m, absorption_db_per_m)),
                  20.0 * std::log10(range_m) + 2.0 * absorption_db_per_m * range_m, 1e-11);
      // An extended surface: the loss per solid angle of the beam (r⁻⁴ · r²) after the gain is 1
      // at every range when the TVG compensates the water's absorption.
      EXPECT_NEAR(tvgGain(range_m, absorption_db_per_m) * twoWayLossPerSolidAngle(2.0 * range_m, absorption_db_per_m, 0.01),
                  1.0, 1e-12);
    }
  }
  EXPECT_EQ(tvgGain(0.0, 0.1), 0.0);
}

TEST(acousticsPropagation, LossPerSolidAngleIsTheTwoWayLossOverTheFootprint) {
  for (const double range_m : {0.2, 2.0, 20.0}) {
    EXPECT_NEAR(twoWayLossPerSolidAngle(2.0 * range_m, 0.15, 0.01) / (twoWayTransmissionFactor(range_m, 0.15) * range_m * range_m),
                1.0, 1e-12);
  }
  // A longer (bounced) path heard at half its length; never nearer than min_range_m.
  EXPECT_NEAR(twoWayLossPerSolidAngle(6.0, 0.1, 0.01), std::pow(10.0, -0.06) / 9.0, 1e-15);
  EXPECT_NEAR(twoWayLossPerSolidAngle(0.0, 0.1, 0.5), 4.0, 1e-15);
}

TEST(acousticsPropagation, RejectsInvalidArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(oneWayTransmissionLoss_db(0.0, 0.1), ValueError);
  EXPECT_THROW(oneWayTransmissionLoss_db(1.0, -0.1), ValueError);
  EXPECT_THROW(twoWayTransmissionFactor(nan, 0.1), ValueError);
  EXPECT_THROW(twoWayLossPerSolidAngle(-1.0, 0.1, 0.01), ValueError);
  EXPECT_THROW(twoWayLossPerSolidAngle(1.0, 0.1, 0.0), ValueError);
  EXPECT_THROW(tvgGain(-1.0, 0.1), ValueError);
  EXPECT_THROW(tvgGain(1.0, nan), ValueError);
}

TEST(acousticsEnsonifiedArea, PulseLimitedAreaIsUricksAnnulusForALevelHead) {
  const double width_rad = 0.05, pulse_m = 0.05;
  for (const double grazing_rad : {2.0 * kDegree, 10.0 * kDegree, 40.0 * kDegree}) {
    // Level head, the seabed seen at depression ψ: A = Φ r L, whatever the grazing angle.
    EXPECT_NEAR(pulseLimitedArea_m2(4.0, grazing_rad, pulse_m, width_rad, -grazing_rad), width_rad * 4.0 * pulse_m, 1e-15);
  }
  // A vertical wall seen in the beam's plane at normal incidence: ψ = 90° − 0 is not allowed (the
  // pulse-limited strip would be infinite); at grazing ψ along the beam's plane the strip is L / cos ψ.
  EXPECT_NEAR(pulseLimitedArea_m2(4.0, 60.0 * kDegree, pulse_m, width_rad, 0.0), 4.0 * width_rad * pulse_m / 0.5, 1e-14);
  EXPECT_THROW(pulseLimitedArea_m2(4.0, 0.5 * std::numbers::pi, pulse_m, width_rad, 0.0), ValueError);
  EXPECT_THROW(pulseLimitedArea_m2(0.0, 0.1, pulse_m, width_rad, 0.0), ValueError);
  EXPECT_THROW(pulseLimitedArea_m2(4.0, 0.1, pulse_m, width_rad, 0.5 * std::numbers::pi), ValueError);
}

TEST(acousticsEnsonifiedArea, FootprintGrowsAsRangeSquaredOverCosine) {
  EXPECT_NEAR(footprintArea_m2(2.0, 0.01, 1.0), 0.04, 1e-16);
  EXPECT_NEAR(footprintArea_m2(2.0, 0.01, 0.5), 0.08, 1e-16);
  EXPECT_THROW(footprintArea_m2(2.0, 0.01, 0.0), ValueError);
  EXPECT_THROW(footprintArea_m2(2.0, 0.0, 1.0), ValueError);
}

}  // namespace
}  // namespace sonarmap
