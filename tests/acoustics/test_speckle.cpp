// Gamma speckle (speckle.hpp): mean 1 and variance 1/L, the exponential for one look, quantiles
// that invert the distribution, the level's mean and variance against numerical integration of
// its density, and the quantised counts' probabilities against a Monte Carlo histogram.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>

#include "integrate.hpp"
#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/acoustics/receiver_model.hpp"
#include "sonarmap/acoustics/speckle.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const ReceiverScale kMicron{-33.0, 45.0};

/// ∫ g(x) f(x) dx over x > 0, integrated in t = ln x (the density of ln X is f(eᵗ) eᵗ), so that
/// the singularity of f at 0 for L < 1 does no harm.
template <typename Function>
double expectation(Function g, double looks) {
  return test::simpson(
      [&](double t) {
        const double x = std::exp(t);
        return g(x) * specklePdf(x, looks) * x;
      },
      -60.0, std::log(80.0 / looks), 40000);
}

TEST(acousticsSpeckle, HasMeanOneAndVarianceOneOverLooks) {
  for (const double looks : {0.6, 1.0, 2.0, 3.0, 5.0, 12.5}) {
    EXPECT_NEAR(expectation([](double) { return 1.0; }, looks), 1.0, 1e-9) << looks;
    EXPECT_NEAR(expectation([](double x) { return x; }, looks), 1.0, 1e-9) << looks;
    EXPECT_NEAR(expectation([](double x) { return (x - 1.0) * (x - 1.0); }, looks), 1.0 / looks, 1e-9) << looks;
  }
}

TEST(acousticsSpeckle, OneLookIsExponentialAndTwoLooksKnown) {
  for (const double x : {0.0, 1e-8, 0.3, 1.0, 4.0, 20.0, 300.0}) {
    EXPECT_NEAR(speckleSurvival(x, 1.0) / std::exp(-x), 1.0, 1e-12) << x;
    EXPECT_NEAR(speckleCdf(x, 1.0), -std::expm1(-x), 1e-15) << x;
    EXPECT_NEAR(specklePdf(x, 1.0) / std::exp(-x), 1.0, 1e-12) << x;
    // Two looks: Pr[X > x] = e^(−2x) (1 + 2x).
    EXPECT_NEAR(speckleSurvival(x, 2.0) / (std::exp(-2.0 * x) * (1.0 + 2.0 * x)), 1.0, 1e-12) << x;
    EXPECT_NEAR(speckleCdf(x, 3.0) + speckleSurvival(x, 3.0), 1.0, 1e-14) << x;
  }
  EXPECT_EQ(specklePdf(0.0, 0.5), kInf);
  EXPECT_EQ(specklePdf(0.0, 2.0), 0.0);
  EXPECT_EQ(speckleCdf(kInf, 2.0), 1.0);
  EXPECT_EQ(speckleSurvival(kInf, 2.0), 0.0);
}

TEST(acousticsSpeckle, QuantileInvertsTheDistribution) {
  for (const double probability : {0.3, 0.5, 0.99}) {
    EXPECT_NEAR(speckleQuantile(probability, 1.0), -std::log1p(-probability), 1e-13);
  }
  for (const double looks : {0.4, 1.0, 3.0, 10.0, 60.0}) {
    for (const double probability : {1e-12, 1e-4, 0.1, 0.5, 0.9, 1.0 - 1e-6}) {
      const double x = speckleQuantile(probability, looks);
      if (probability < 0.5) {
        EXPECT_NEAR(speckleCdf(x, looks) / probability, 1.0, 1e-11) << looks << " " << probability;
      } else {
        EXPECT_NEAR(speckleSurvival(x, looks) / (1.0 - probability), 1.0, 1e-11) << looks << " " << probability;
      }
    }
  }
  EXPECT_EQ(speckleQuantile(0.0, 2.0), 0.0);
  EXPECT_EQ(speckleQuantile(1.0, 2.0), kInf);
}

TEST(acousticsSpeckle, LevelMeanAndVarianceMatchTheIntegralOfTheLevelDensity) {
  // One look: the classic −2.51 dB mean (−γ 10 / ln 10) and 5.57 dB standard deviation
  // (π / √6 · 10 / ln 10).
  EXPECT_NEAR(speckleLevelMean_db(1.0), -0.57721566490153286 * 10.0 / std::numbers::ln10, 1e-12);
  EXPECT_NEAR(std::sqrt(speckleLevelVariance_db2(1.0)), std::numbers::pi / std::sqrt(6.0) * 10.0 / std::numbers::ln10, 1e-12);
  for (const double looks : {0.5, 1.0, 3.0, 8.0}) {
    auto moment = [&](auto g) { return test::simpson([&](double y) { return g(y) * speckleLevelPdf(y, looks); }, -300.0, 25.0, 60000); };
    const double mass = moment([](double) { return 1.0; });
    const double mean_db = moment([](double y) { return y; });
    const double variance_db2 = moment([&](double y) { return (y - mean_db) * (y - mean_db); });
    EXPECT_NEAR(mass, 1.0, 1e-9) << looks;
    EXPECT_NEAR(mean_db, speckleLevelMean_db(looks), 1e-7) << looks;
    EXPECT_NEAR(variance_db2, speckleLevelVariance_db2(looks), 1e-6) << looks;
    // The level's distribution function is the integral of its density.
    for (const double level_db : {-10.0, -1.0, 2.0}) {
      const double integral = test::simpson([&](double y) { return speckleLevelPdf(y, looks); }, -300.0, level_db, 60000);
      EXPECT_NEAR(speckleLevelCdf(level_db, looks), integral, 1e-9) << looks << " " << level_db;
      EXPECT_NEAR(speckleLevelSurvival(level_db, looks), 1.0 - integral, 1e-9) << looks << " " << level_db;
    }
    EXPECT_NEAR(speckleLevelQuantile_db(0.25, looks), 10.0 * std::log10(speckleQuantile(0.25, looks)), 1e-12);
  }
  EXPECT_EQ(speckleLevelCdf(-kInf, 2.0), 0.0);
  EXPECT_EQ(speckleLevelCdf(kInf, 2.0), 1.0);
  EXPECT_EQ(speckleLevelPdf(kInf, 2.0), 0.0);
  EXPECT_EQ(speckleLevelQuantile_db(0.0, 2.0), -kInf);
}

TEST(acousticsSpeckle, TailMeanExcessIsTheIntegralOfTheLevelBeyondItsQuantile) {
  // E[Y − y_q | Y > y_q] by integrating the one-look level density beyond the quantile.
  for (const double exceedance : {0.5, 0.1, 0.01}) {
    const double q_db = speckleLevelQuantile_db(1.0 - exceedance, 1.0);
    const double mean_excess =
        test::simpson([&](double y) { return (y - q_db) * speckleLevelPdf(y, 1.0); }, q_db, 40.0, 60000) / exceedance;
    EXPECT_NEAR(speckleTailMeanExcess_db(exceedance), mean_excess, 1e-6) << exceedance;
  }
  EXPECT_NEAR(speckleTailMeanExcess_db(0.1), 1.4067, 1e-4);  // the evidence detector's least tail
  for (const double bad : {0.0, 1.0, -0.1, std::nan("")}) EXPECT_THROW(speckleTailMeanExcess_db(bad), ValueError) << bad;
}

TEST(acousticsSpeckle, QuantisedCountsAddUpToOneAndMatchAMonteCarloHistogram) {
  const int looks = 3;
  const double mean_power = powerOfLevel(-15.0);  // about 102 counts
  const std::array<double, 256> model = quantisedSpeckleDistribution(mean_power, looks, kMicron);
  double total = 0.0;
  for (int counts = 0; counts < 256; ++counts) {
    total += model[static_cast<std::size_t>(counts)];
    EXPECT_NEAR(quantisedSpeckleProbability(counts, mean_power, looks, kMicron), model[static_cast<std::size_t>(counts)],
                1e-15)
        << counts;
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  // The mean of three exponential draws, through the A/D.
  std::mt19937_64 engine(7);
  auto exponential = [&] { return -std::log((static_cast<double>(engine() >> 11) + 1.0) * 0x1.0p-53); };
  constexpr int kSamples = 100000;
  std::array<int, 256> histogram{};
  for (int i = 0; i < kSamples; ++i) {
    const double speckle = (exponential() + exponential() + exponential()) / looks;
    ++histogram[countsOfPower(kMicron, mean_power * speckle)];
  }
  for (std::size_t counts = 0; counts < 256; ++counts) {
    const double p = model[counts];
    const double observed = static_cast<double>(histogram[counts]) / kSamples;
    EXPECT_NEAR(observed, p, 5.0 * std::sqrt(p * (1.0 - p) / kSamples) + 2e-5) << counts;
  }
}

TEST(acousticsSpeckle, ClippedEndsTakeTheirTails) {
  // A mean far below the A/D's lowest level: nearly everything at 0; far above: at 255.
  const std::array<double, 256> quiet = quantisedSpeckleDistribution(powerOfLevel(-60.0), 2.0, kMicron);
  EXPECT_NEAR(quiet[0], speckleLevelCdf(-33.0 + 0.5 / 255.0 * 45.0 + 60.0, 2.0), 1e-14);
  EXPECT_GT(quiet[0], 0.999);
  const std::array<double, 256> loud = quantisedSpeckleDistribution(powerOfLevel(30.0), 2.0, kMicron);
  EXPECT_NEAR(loud[255], speckleLevelSurvival(-33.0 + 254.5 / 255.0 * 45.0 - 30.0, 2.0), 1e-14);
  EXPECT_GT(loud[255], 0.999);
  // No power at all: counts 0 surely.
  EXPECT_EQ(quantisedSpeckleProbability(0, 0.0, 2.0, kMicron), 1.0);
  EXPECT_EQ(quantisedSpeckleProbability(1, 0.0, 2.0, kMicron), 0.0);
}

TEST(acousticsSpeckle, RejectsInvalidArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(specklePdf(1.0, 0.0), ValueError);
  EXPECT_THROW(speckleCdf(-1.0, 2.0), ValueError);
  EXPECT_THROW(speckleSurvival(nan, 2.0), ValueError);
  EXPECT_THROW(speckleQuantile(1.5, 2.0), ValueError);
  EXPECT_THROW(speckleLevelPdf(nan, 2.0), ValueError);
  EXPECT_THROW(speckleLevelMean_db(kInf), ValueError);
  EXPECT_THROW(speckleLevelVariance_db2(-1.0), ValueError);
  EXPECT_THROW(quantisedSpeckleProbability(256, 1.0, 2.0, kMicron), ValueError);
  EXPECT_THROW(quantisedSpeckleProbability(3, -1.0, 2.0, kMicron), ValueError);
  EXPECT_THROW(quantisedSpeckleDistribution(1.0, 2.0, ReceiverScale{-33.0, -1.0}), ValueError);
}

}  // namespace
}  // namespace sonarmap

namespace sonarmap {
namespace {

TEST(acousticsSpeckle, SurvivalQuantileKeepsTinyExceedancesExact) {
  // One look: the exponential's −ln(p), where 1 − p would round p away.
  for (const double p : {0.3, 1e-6, 1e-12, 1e-100}) {
    EXPECT_NEAR(speckleSurvivalQuantile(p, 1.0), -std::log(p), 1e-10 * -std::log(p)) << "p = " << p;
  }
  for (const double looks : {2.0, 5.0, 30.0}) {
    for (const double p : {0.7, 1e-3, 1e-9}) {
      EXPECT_NEAR(speckleSurvival(speckleSurvivalQuantile(p, looks), looks) / p, 1.0, 1e-9) << looks << " looks, p " << p;
    }
  }
  EXPECT_EQ(speckleSurvivalQuantile(1.0, 3.0), 0.0);
  EXPECT_TRUE(std::isinf(speckleSurvivalQuantile(0.0, 3.0)));
  EXPECT_THROW(speckleSurvivalQuantile(1.5, 3.0), ValueError);
  EXPECT_THROW(speckleSurvivalQuantile(0.1, 0.0), ValueError);
}

}  // namespace
}  // namespace sonarmap
