/// Physical units on polar images: metres to bins, angles to rows, dB to counts (polar_units.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The same length is the same physical extent whatever the log's bin length: the Micron's 1.25 cm
// bins, a Ping360's 4.17 cm samples, a SeaKing's 10 cm bins.
TEST(sonarPolarUnits, LengthsBecomeBinsOfEachLog) {
  EXPECT_EQ(binsForLength(0.05, 0.0125, 1, 1000), 4);
  EXPECT_EQ(binsForLength(0.05, 0.0417, 1, 1000), 1);
  EXPECT_EQ(binsForLength(0.05, 0.10, 1, 1000), 1);  // never below the minimum: at least one bin
  EXPECT_EQ(binsForLength(0.5, 0.0125, 1, 1000), 40);
  EXPECT_EQ(binsForLength(0.5, 0.10, 1, 1000), 5);
  for (const double bin_m : {0.0125, 0.0417, 0.0625, 0.1}) {
    const int bins = binsForLength(1.0, bin_m, 0, 100000);
    EXPECT_NEAR(bins * bin_m, 1.0, 0.5 * bin_m) << bin_m;
  }
  EXPECT_EQ(binsForLength(0.0, 0.01, 0, 10), 0);
}

// A metres-to-bins conversion never overflows: a huge length saturates (the CLI's
// --self-reflection 1e9 once wrapped to a negative bin count and removed nothing).
TEST(sonarPolarUnits, HugeLengthsSaturateInsteadOfOverflowing) {
  EXPECT_EQ(binsForLength(1e9, 0.0125, 1, 399), 399);
  EXPECT_EQ(binsForLength(1e300, 1e-300, 0, 7), 7);
  EXPECT_EQ(binsForLength(std::numeric_limits<double>::infinity(), 0.01, 0, 5), 5);
  EXPECT_EQ(firstBinAtOrBeyond(1e9, 0.0125, 399), 399);
  EXPECT_EQ(firstBinAtOrBeyond(0.0, 0.0125, 399), 0);
  EXPECT_EQ(firstBinAtOrBeyond(0.3, 0.1, 399), 3);   // centres 0.05, 0.15, 0.25 < 0.3; 0.35 is not
  EXPECT_EQ(firstBinAtOrBeyond(0.35, 0.1, 399), 3);  // the centre of bin 3 is at the range
}

TEST(sonarPolarUnits, AnglesBecomeRowsOfTheBeamSpacing) {
  PolarImage polar;
  for (int r = 0; r < 10; ++r) polar.bearing_rad.push_back(r * 1.8 * kDegree);
  EXPECT_NEAR(beamSpacing_rad(polar), 1.8 * kDegree, 1e-12);
  EXPECT_EQ(rowsForAngle(4.1 * kDegree, beamSpacing_rad(polar), 1, 100), 2);
  // A sector scan reversing at its limit, and a wrap through 0: the spacing is still the step.
  polar.bearing_rad = {350.0 * kDegree, 353.6 * kDegree, 357.2 * kDegree, 0.8 * kDegree, 4.4 * kDegree, 4.4 * kDegree,
                       0.8 * kDegree};
  EXPECT_NEAR(beamSpacing_rad(polar), 3.6 * kDegree, 1e-9);
  EXPECT_EQ(rowsForAngle(1.0, 0.0, 1, 9), 1);  // no spacing (one bearing): the minimum
  EXPECT_EQ(beamSpacing_rad(PolarImage{}), 0.0);
}

TEST(sonarPolarUnits, DecibelsBecomeCountsOfTheIntensitySpan) {
  EXPECT_DOUBLE_EQ(countsForDb(45.0, 45.0), 255.0);
  EXPECT_NEAR(countsForDb(15.6, 45.0), 88.4, 0.1);
  EXPECT_NEAR(countsForDb(15.6, 46.7), 85.2, 0.1);  // the SeaNet log's ADspan 149 of 80 dB
  PolarImage polar;
  EXPECT_EQ(intensitySpan_db(polar), kDefaultIntensitySpan_db);
  polar.intensity_span_db = 46.7;
  EXPECT_EQ(intensitySpan_db(polar), 46.7);
}

TEST(sonarPolarUnits, InvalidValuesThrow) {
  EXPECT_THROW(binsForLength(-0.1, 0.01, 0, 10), ValueError);
  EXPECT_THROW(binsForLength(std::nan(""), 0.01, 0, 10), ValueError);
  EXPECT_THROW(binsForLength(0.1, 0.0, 0, 10), ValueError);
  EXPECT_THROW(binsForLength(0.1, 0.01, 5, 4), ValueError);
  EXPECT_THROW(firstBinAtOrBeyond(-1.0, 0.01, 10), ValueError);
  EXPECT_THROW(rowsForAngle(-1.0, 0.1, 0, 10), ValueError);
  EXPECT_THROW(countsForDb(-1.0, 45.0), ValueError);
  EXPECT_THROW(countsForDb(1.0, 0.0), ValueError);
}

}  // namespace
}  // namespace sonarmap
