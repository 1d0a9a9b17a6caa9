// Lambert's law (backscatter.hpp): the strength at normal incidence is 10 log10(ρ / π), it falls
// as sin^k ψ, and the simulator's per-area and per-solid-angle forms agree with it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "sonarmap/acoustics/backscatter.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

TEST(acousticsBackscatter, LambertAtNormalIncidence) {
  EXPECT_NEAR(lambertCoefficient(1.0), 1.0 / std::numbers::pi, 1e-16);
  EXPECT_NEAR(lambertStrength_db(1.0, kHalfPi), -4.9715, 1e-4);  // a perfect diffuse scatterer
  // Mackenzie's deep-sea floor, μ = −27 dB: ρ = π 10^(−2.7).
  EXPECT_NEAR(lambertStrength_db(std::numbers::pi * std::pow(10.0, -2.7), kHalfPi), -27.0, 1e-12);
  for (const double exponent : {1.0, 2.0, 3.5}) {
    EXPECT_EQ(lambertScatter(0.5, 1.0, exponent), 0.5);
    EXPECT_EQ(lambertScatterPerSolidAngle(0.5, 1.0, exponent), 0.5);
  }
}

TEST(acousticsBackscatter, StrengthFallsAsSineToTheK) {
  const double grazing_rad = std::numbers::pi / 6.0;  // sin ψ = 1/2
  EXPECT_NEAR(lambertStrength_db(0.5, grazing_rad) - lambertStrength_db(0.5, kHalfPi), 20.0 * std::log10(0.5), 1e-12);
  EXPECT_NEAR(lambertStrength_db(0.5, grazing_rad, 3.0) - lambertStrength_db(0.5, kHalfPi, 3.0), 30.0 * std::log10(0.5),
              1e-12);
  EXPECT_EQ(lambertStrength_db(0.5, 0.0), -std::numeric_limits<double>::infinity());
  // The simulator's units: π · 10^(S_b/10) = ρ sin^k ψ; over the footprint (1 / cos θ), ρ sin^(k−1) ψ.
  for (const double grazing : {0.1, 0.5, 1.2}) {
    const double sine = std::sin(grazing);
    EXPECT_NEAR(lambertScatter(0.7, sine, 2.0), std::numbers::pi * std::pow(10.0, lambertStrength_db(0.7, grazing) / 10.0),
                1e-14);
    EXPECT_NEAR(lambertScatterPerSolidAngle(0.7, sine, 2.5), lambertScatter(0.7, sine, 2.5) / sine, 1e-15);
  }
}

TEST(acousticsBackscatter, RejectsInvalidArguments) {
  EXPECT_THROW(lambertCoefficient(1.5), ValueError);
  EXPECT_THROW(lambertCoefficient(std::numeric_limits<double>::quiet_NaN()), ValueError);
  EXPECT_THROW(lambertStrength_db(0.5, -0.1), ValueError);
  EXPECT_THROW(lambertStrength_db(0.5, 0.1, 0.5), ValueError);
  EXPECT_THROW(lambertScatter(0.5, -0.1, 2.0), ValueError);
  EXPECT_THROW(lambertScatterPerSolidAngle(-0.1, 0.5, 2.0), ValueError);
  EXPECT_THROW(lambertScatterPerSolidAngle(0.5, 0.5, std::numeric_limits<double>::infinity()), ValueError);
}

}  // namespace
}  // namespace sonarmap
