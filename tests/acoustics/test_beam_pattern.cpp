// The beam pattern (beam_pattern.hpp): 1 on the axis and −3 dB at half the width in both planes,
// the two-way pattern its square, the equivalent width against numerical integration, and the
// aperture's cells and the elevation integral over them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "integrate.hpp"
#include "sonarmap/acoustics/beam_pattern.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(acousticsBeamPattern, IsOneOnTheAxisAndHalfAtHalfTheWidth) {
  for (const double width_rad : {1.8 * kDegree, 3.0 * kDegree, 35.0 * kDegree}) {
    for (const double exponent : {1.0, 2.0, 8.0}) {
      const BeamPattern pattern{width_rad, exponent};
      EXPECT_EQ(oneWayPattern(pattern, 0.0), 1.0);
      EXPECT_NEAR(oneWayPattern(pattern, 0.5 * width_rad), 0.5, 1e-15);
      EXPECT_NEAR(oneWayPattern(pattern, -0.5 * width_rad), 0.5, 1e-15);
      EXPECT_NEAR(twoWayPattern(pattern, 0.5 * width_rad), 0.25, 1e-15);
      // Falls off the axis, symmetrically; beyond the half width faster for a larger exponent.
      EXPECT_GT(oneWayPattern(pattern, 0.3 * width_rad), oneWayPattern(pattern, 0.4 * width_rad));
      EXPECT_EQ(oneWayPattern(pattern, 0.7 * width_rad), oneWayPattern(pattern, -0.7 * width_rad));
    }
  }
  // n = 2 is a Gaussian: p(θ) = exp(−4 ln 2 θ² / W²).
  const BeamPattern gaussian{3.0 * kDegree, 2.0};
  const double angle_rad = 2.2 * kDegree;
  EXPECT_NEAR(oneWayPattern(gaussian, angle_rad),
              std::exp(-4.0 * std::numbers::ln2 * angle_rad * angle_rad / (gaussian.width_rad * gaussian.width_rad)),
              1e-15);
  // A flatter top for a larger exponent: within the half width it stays nearer 1.
  EXPECT_GT(oneWayPattern(BeamPattern{gaussian.width_rad, 8.0}, 0.3 * gaussian.width_rad),
            oneWayPattern(gaussian, 0.3 * gaussian.width_rad));
}

TEST(acousticsBeamPattern, BothPlanesMultiply) {
  const TransducerPattern head{{3.0 * kDegree, 2.0}, {35.0 * kDegree, 8.0}};
  EXPECT_EQ(oneWayPattern(head, 0.0, 0.0), 1.0);
  EXPECT_NEAR(oneWayPattern(head, 1.5 * kDegree, 0.0), 0.5, 1e-15);
  EXPECT_NEAR(oneWayPattern(head, 0.0, -17.5 * kDegree), 0.5, 1e-15);
  EXPECT_NEAR(oneWayPattern(head, 1.5 * kDegree, 17.5 * kDegree), 0.25, 1e-15);
  EXPECT_NEAR(twoWayPattern(head, 1.5 * kDegree, 17.5 * kDegree), 0.0625, 1e-15);
  EXPECT_NEAR(twoWayPattern(head, 1.0 * kDegree, 5.0 * kDegree),
              twoWayPattern(head.horizontal, 1.0 * kDegree) * twoWayPattern(head.vertical, 5.0 * kDegree), 1e-15);
}

TEST(acousticsBeamPattern, EquivalentWidthIsTheIntegralOfTheTwoWayPattern) {
  for (const double exponent : {1.0, 2.0, 8.0}) {
    const BeamPattern pattern{10.0 * kDegree, exponent};
    const double integral = test::simpson([&](double angle_rad) { return twoWayPattern(pattern, angle_rad); },
                                          -20.0 * pattern.width_rad, 20.0 * pattern.width_rad, 40000);
    EXPECT_NEAR(equivalentBeamWidth_rad(pattern) / integral, 1.0, 1e-6) << exponent;
  }
  // Gaussian: W √(π / (8 ln 2)) = 0.7527 W.
  EXPECT_NEAR(equivalentBeamWidth_rad(BeamPattern{1.0, 2.0}), std::sqrt(std::numbers::pi / (8.0 * std::numbers::ln2)),
              1e-15);
}

TEST(acousticsBeamPattern, ApertureCellsSpanTheExtentSymmetrically) {
  const ApertureSampling sampling{15, 1.5};
  const double width_rad = 35.0 * kDegree;
  const double step_rad = apertureStep_rad(sampling, width_rad);
  EXPECT_NEAR(step_rad, 1.5 * width_rad / 15.0, 1e-16);
  EXPECT_NEAR(apertureAngle_rad(sampling, width_rad, 0), -0.75 * width_rad + 0.5 * step_rad, 1e-15);
  EXPECT_NEAR(apertureAngle_rad(sampling, width_rad, 7), 0.0, 1e-15);  // the middle of 15 cells
  for (int j = 0; j < sampling.rays; ++j) {
    EXPECT_NEAR(apertureAngle_rad(sampling, width_rad, j), -apertureAngle_rad(sampling, width_rad, sampling.rays - 1 - j),
                1e-15);
  }
  EXPECT_THROW(apertureAngle_rad(sampling, width_rad, 15), ValueError);
  EXPECT_THROW(apertureAngle_rad(sampling, width_rad, -1), ValueError);
}

TEST(acousticsBeamPattern, ElevationIntegralIsTheMidpointRuleOfTheTwoWayPatternTimesCosine) {
  const BeamPattern vertical{35.0 * kDegree, 8.0};
  // One cell: the pattern on the axis (1) times the cell's width.
  EXPECT_NEAR(elevationPatternIntegral(vertical, ApertureSampling{1, 1.5}), 1.5 * vertical.width_rad, 1e-15);
  // Many cells: the integral over ± 1.5 half widths.
  const double half_span_rad = 0.75 * vertical.width_rad;
  const double integral = test::simpson(
      [&](double v) { return twoWayPattern(vertical, v) * std::cos(v); }, -half_span_rad, half_span_rad, 20000);
  EXPECT_NEAR(elevationPatternIntegral(vertical, ApertureSampling{2000, 1.5}) / integral, 1.0, 1e-6);
  // A flat-topped pattern over ± 1.5 half widths holds nearly all of it: close to Φ of the whole line.
  EXPECT_NEAR(integral / equivalentBeamWidth_rad(vertical), 1.0, 0.05);
}

TEST(acousticsBeamPattern, RejectsInvalidPatternsAndAngles) {
  EXPECT_THROW(oneWayPattern(BeamPattern{0.0, 2.0}, 0.0), ValueError);
  EXPECT_THROW(oneWayPattern(BeamPattern{std::numbers::pi, 2.0}, 0.0), ValueError);
  EXPECT_THROW(oneWayPattern(BeamPattern{0.1, 0.0}, 0.0), ValueError);
  EXPECT_THROW(oneWayPattern(BeamPattern{0.1, 2.0}, std::numeric_limits<double>::quiet_NaN()), ValueError);
  EXPECT_THROW(equivalentBeamWidth_rad(BeamPattern{0.1, -1.0}), ValueError);
  EXPECT_THROW(TransducerPattern({{0.1, 2.0}, {0.0, 2.0}}).validate(), ValueError);
  EXPECT_THROW(apertureStep_rad(ApertureSampling{0, 1.5}, 0.1), ValueError);
  EXPECT_THROW(apertureStep_rad(ApertureSampling{3, 0.0}, 0.1), ValueError);
  EXPECT_THROW(elevationPatternIntegral(BeamPattern{0.1, 2.0}, ApertureSampling{3, -1.0}), ValueError);
  EXPECT_EQ(oneWayPattern(BeamPattern{0.1, 2.0}, std::numeric_limits<double>::infinity()), 0.0);
}

}  // namespace
}  // namespace sonarmap
