// The local reverberation level (reverberation.hpp) and the echo span it asks of an obstacle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/detection/reverberation.hpp"
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {
namespace {

TEST(detectionReverberation, QuietWaterAsksOneBeamAndDenseSpeckleMore) {
  EXPECT_EQ(requiredEchoBeams(0.0, 20.0, 1e-6, 400), 1);
  EXPECT_EQ(requiredEchoBeams(1e-7, 20.0, 1e-6, 400), 1);
  // One chance run every 200 bins, 20 bins within reach: q ≈ 0.095, so n with 5e-3 · n · qⁿ⁻¹ ≤ 1e-6.
  const int n = requiredEchoBeams(5e-3, 20.0, 1e-6, 400);
  const double q = 1.0 - std::exp(-5e-3 * 20.0);
  EXPECT_LE(5e-3 * n * std::pow(q, n - 1), 1e-6);
  EXPECT_GT(5e-3 * (n - 1) * std::pow(q, n - 2), 1e-6) << "the fewest such beams";
  EXPECT_GT(n, 1);
  // Denser speckle asks more beams; never more than there are.
  EXPECT_GE(requiredEchoBeams(2e-2, 20.0, 1e-6, 400), n);
  EXPECT_EQ(requiredEchoBeams(0.5, 50.0, 1e-6, 7), 7);
}

TEST(detectionReverberation, BadArgumentsThrow) {
  EXPECT_THROW(requiredEchoBeams(-1.0, 1.0, 1e-6, 10), ValueError);
  EXPECT_THROW(requiredEchoBeams(NAN, 1.0, 1e-6, 10), ValueError);
  EXPECT_THROW(requiredEchoBeams(1e-3, -1.0, 1e-6, 10), ValueError);
  EXPECT_THROW(requiredEchoBeams(1e-3, 1.0, 0.0, 10), ValueError);
  EXPECT_THROW(requiredEchoBeams(1e-3, 1.0, 1e-6, 0), ValueError);
  ReverberationOptions options;
  options.range_looks = 0.0;
  EXPECT_THROW(options.validate(), ValueError);
}

/// A whole turn of `rows` beams × `cols` bins of speckle uniform in [lo, hi], a wall `wall_bins`
/// long at column `wall` in every beam at 220 counts.
PolarImage speckleTurn(int rows, int cols, int lo, int hi, int wall, int wall_bins) {
  std::mt19937 random(3);
  std::uniform_int_distribution<int> speckle(lo, hi);
  PolarImage polar;
  polar.intensities = cv::Mat(rows, cols, CV_8UC1);
  polar.bin_length_m = 0.01;
  for (int r = 0; r < rows; ++r) {
    polar.bearing_rad.push_back(2.0 * M_PI * r / rows);
    polar.time_s.push_back(0.05 * r);
    polar.valid_bins.push_back(cols);
    for (int c = 0; c < cols; ++c) {
      polar.intensities.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(c >= wall && c < wall + wall_bins ? 220 : speckle(random));
    }
  }
  return polar;
}

TEST(detectionReverberation, TheLevelIsTheSpeckleAroundAnEchoNotTheEcho) {
  const PolarImage polar = speckleTurn(200, 600, 20, 40, 300, 5);
  const LocalLevel level(polar, 10, 1.0, 2.0 * M_PI / 180.0, ReverberationOptions{});
  ASSERT_FALSE(level.empty());
  EXPECT_TRUE(level.circular());
  for (const int r : {0, 57, 199}) {
    EXPECT_NEAR(level.at(r, 302), 30.0, 3.0) << "the wall, 5 bins of a 25-bin half window, is not its own level";
    EXPECT_NEAR(level.at(r, 100), 30.0, 3.0);
    EXPECT_NEAR(level.at(r, 590), 30.0, 3.0);
  }
  EXPECT_EQ(level.at(0, 5), 0.0f) << "before the minimum range nothing is measured";
  // A beam of a sweep in progress takes the level of the nearest bearing.
  EXPECT_EQ(level.atBearing(2.0 * M_PI * 57 / 200 + 1e-4, 302), level.at(57, 302));
  const auto neighbours = level.bearingNeighbours(0);
  EXPECT_EQ(neighbours[0], 199) << "a whole turn closes the circle";
  EXPECT_EQ(neighbours[1], 1);
}

}  // namespace
}  // namespace sonarmap
