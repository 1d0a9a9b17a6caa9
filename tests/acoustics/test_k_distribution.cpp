// The K distribution (k_distribution.hpp): a density of mass 1, mean 1 and second moment
// 2 (1 + 1/α), a survival function that is its integral and that of single-look speckle
// modulated by a Gamma texture of shape α (Abraham & Lyons 2002's compound form), tending to
// speckle for a large shape and with a heavier tail than it for a small one.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "integrate.hpp"
#include "sonarmap/acoustics/k_distribution.hpp"
#include "sonarmap/acoustics/speckle.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// ∫ g(x) f(x) dx over x in [e^lower_t, e^upper_t], integrated in t = ln x.
template <typename Function>
double integral(Function g, double shape, double lower_t, double upper_t) {
  return test::simpson(
      [&](double t) {
        const double x = std::exp(t);
        return g(x) * kDistributionPdf(x, shape) * x;
      },
      lower_t, upper_t, 40000);
}

TEST(acousticsKDistribution, HasMassOneMeanOneAndTheKnownSecondMoment) {
  for (const double shape : {0.5, 1.0, 3.0, 10.0}) {
    const double upper_t = std::log(4000.0);  // the tail of a small shape is long
    EXPECT_NEAR(integral([](double) { return 1.0; }, shape, -40.0, upper_t), 1.0, 1e-8) << shape;
    EXPECT_NEAR(integral([](double x) { return x; }, shape, -40.0, upper_t), 1.0, 1e-7) << shape;
    EXPECT_NEAR(integral([](double x) { return x * x; }, shape, -40.0, upper_t), 2.0 * (1.0 + 1.0 / shape), 1e-5) << shape;
  }
}

TEST(acousticsKDistribution, SurvivalIsTheIntegralOfTheDensity) {
  for (const double shape : {0.5, 1.0, 4.0}) {
    for (const double x : {0.01, 0.5, 2.0, 8.0}) {
      EXPECT_NEAR(kDistributionSurvival(x, shape), integral([](double) { return 1.0; }, shape, std::log(x), std::log(400.0)),
                  1e-8)
          << shape << " " << x;
    }
  }
  EXPECT_EQ(kDistributionSurvival(0.0, 2.0), 1.0);
  EXPECT_NEAR(kDistributionPdf(1e-12, 3.0), 1.5, 1e-4);  // α / (α − 1) at 0
}

TEST(acousticsKDistribution, IsSpeckleModulatedByAGammaTexture) {
  // X = G · E, E exponential (one look), G Gamma of shape α and mean 1 (speckle.hpp's density):
  // Pr[X > x] = E[exp(−x / G)], integrated over G in t = ln g.
  for (const double shape : {0.7, 2.0, 5.0}) {
    for (const double x : {0.1, 1.0, 5.0}) {
      const double compound = test::simpson(
          [&](double t) {
            const double g = std::exp(t);
            return std::exp(-x / g) * specklePdf(g, shape) * g;
          },
          -40.0, std::log(200.0), 40000);
      EXPECT_NEAR(kDistributionSurvival(x, shape), compound, 1e-9) << shape << " " << x;
    }
  }
}

TEST(acousticsKDistribution, TendsToSpeckleForALargeShapeAndHasAHeavierTailForASmallOne) {
  // A texture of variance 1/α: Pr[X > x] ≈ e^−x (1 + (x²/2 − x) / α) to first order in 1/α (the
  // tolerance, O(1/α²), is a fraction of that correction: exp(−x) alone would fail).
  const double shape = 100.0;
  for (const double x : {0.1, 1.0, 3.0, 5.0}) {
    EXPECT_NEAR(kDistributionSurvival(x, shape) / std::exp(-x), 1.0 + (0.5 * x * x - x) / shape,
                (1.0 + std::pow(x, 4)) / (2.0 * shape * shape))
        << x;
  }
  // α = 1: a bin 10 times the mean is over 100 times likelier than under speckle (2√10 K₁(2√10)
  // = 6.0e-3 against e^−10 = 4.5e-5).
  EXPECT_GT(kDistributionSurvival(10.0, 1.0), 100.0 * std::exp(-10.0));
  EXPECT_GT(kDistributionSurvival(10.0, 1.0), kDistributionSurvival(10.0, 10.0));
}

TEST(acousticsKDistribution, RejectsInvalidArguments) {
  EXPECT_THROW(kDistributionPdf(1.0, 0.0), ValueError);
  EXPECT_THROW(kDistributionPdf(1.0, 101.0), ValueError);
  EXPECT_THROW(kDistributionSurvival(-1.0, 2.0), ValueError);
  EXPECT_THROW(kDistributionSurvival(std::numeric_limits<double>::quiet_NaN(), 2.0), ValueError);
}

}  // namespace
}  // namespace sonarmap
