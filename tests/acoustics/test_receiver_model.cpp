// The receiver (receiver_model.hpp, decibels.hpp): levels and powers, the A/D mapping and its
// inverse, rounding and clipping, the noise after the TVG and the floor, the pulse sum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/acoustics/receiver_model.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
const ReceiverScale kMicron{-33.0, 45.0};

TEST(acousticsDecibels, LevelsAndPowersAreInverse) {
  EXPECT_EQ(powerOfLevel(0.0), 1.0);
  EXPECT_NEAR(powerOfLevel(-30.0), 1e-3, 1e-18);
  EXPECT_NEAR(levelOfPower(100.0), 20.0, 1e-14);
  EXPECT_NEAR(levelOfPower(powerOfLevel(-41.5)), -41.5, 1e-13);
  EXPECT_EQ(levelOfPower(0.0), -kInf);
  EXPECT_EQ(powerOfLevel(-kInf), 0.0);
  EXPECT_THROW(levelOfPower(-1.0), ValueError);
  EXPECT_THROW(levelOfPower(kNan), ValueError);
  EXPECT_THROW(powerOfLevel(kNan), ValueError);
}

TEST(acousticsReceiverModel, AdMappingIsLinearInLevelAndInvertible) {
  EXPECT_EQ(intensityOfLevel(kMicron, -33.0), 0.0);
  EXPECT_EQ(intensityOfLevel(kMicron, 12.0), 255.0);
  EXPECT_NEAR(intensityOfLevel(kMicron, -10.5), 127.5, 1e-12);
  for (const double intensity : {0.0, 27.0, 100.0, 254.0}) {
    EXPECT_NEAR(intensityOfLevel(kMicron, levelOfIntensity(kMicron, intensity)), intensity, 1e-12);
  }
  EXPECT_NEAR(levelOfIntensity(kMicron, 100.0), -33.0 + 100.0 / 255.0 * 45.0, 1e-14);
}

TEST(acousticsReceiverModel, CountsAreRoundedAndClipped) {
  EXPECT_EQ(countsOfLevel(kMicron, -60.0), 0);
  EXPECT_EQ(countsOfLevel(kMicron, 40.0), 255);
  EXPECT_EQ(countsOfLevel(kMicron, kInf), 255);
  EXPECT_EQ(countsOfLevel(kMicron, -kInf), 0);
  EXPECT_EQ(countsOfLevel(kMicron, levelOfIntensity(kMicron, 127.4)), 127);
  EXPECT_EQ(countsOfLevel(kMicron, levelOfIntensity(kMicron, 127.6)), 128);
  EXPECT_EQ(countsOfLevel(kMicron, levelOfIntensity(kMicron, 0.49)), 0);
  EXPECT_EQ(countsOfLevel(kMicron, levelOfIntensity(kMicron, 254.6)), 255);
  EXPECT_EQ(countsOfPower(kMicron, powerOfLevel(levelOfIntensity(kMicron, 99.8))), 100);
  EXPECT_EQ(countsOfPower(kMicron, 0.0), 0);
  EXPECT_EQ(countsOfPower(kMicron, -1.0), 0);
  EXPECT_EQ(countsOfPower(kMicron, kNan), 0);
  EXPECT_EQ(countsOfPower(kMicron, kInf), 255);
  EXPECT_THROW(countsOfLevel(kMicron, kNan), ValueError);
  EXPECT_THROW(countsOfPower(ReceiverScale{-33.0, 0.0}, 1.0), ValueError);
  EXPECT_THROW(intensityOfLevel(ReceiverScale{kNan, 45.0}, 1.0), ValueError);
  EXPECT_THROW(levelOfIntensity(kMicron, kInf), ValueError);
}

TEST(acousticsReceiverModel, NoiseGrowsWithTheGainAndTheFloorHoldsTheConverter) {
  const ReceiverNoise noise{-41.5, 0.15};
  EXPECT_NEAR(levelOfPower(meanNoisePower(ReceiverNoise{-41.5, 0.0}, 1.0)), -41.5, 1e-12);
  for (const double range_m : {0.5, 2.0, 5.0}) {
    EXPECT_NEAR(levelOfPower(meanNoisePower(noise, range_m)), -41.5 + 20.0 * std::log10(range_m) + 0.3 * range_m, 1e-12);
  }
  // Near the head the converter's lowest level is the floor, far out the noise.
  EXPECT_EQ(receiverFloorPower(noise, kMicron, 0.5), powerOfLevel(-33.0));
  EXPECT_EQ(receiverFloorPower(noise, kMicron, 5.0), meanNoisePower(noise, 5.0));
  EXPECT_THROW(meanNoisePower(noise, 0.0), ValueError);
  EXPECT_THROW(meanNoisePower(ReceiverNoise{kNan, 0.1}, 1.0), ValueError);
  EXPECT_THROW(receiverFloorPower(ReceiverNoise{-41.5, -0.1}, kMicron, 1.0), ValueError);
}

TEST(acousticsReceiverModel, PulseSumsTheBinsOfOnePulseLength) {
  EXPECT_EQ(pulseBins(0.05, 5.0 / 399.0), 4);
  EXPECT_EQ(pulseBins(0.001, 0.0125), 1);  // at least one bin
  EXPECT_THROW(pulseBins(0.0, 0.01), ValueError);
  EXPECT_THROW(pulseBins(0.05, kInf), ValueError);
  const std::vector<double> energy{1.0, 0.0, 2.0, 0.5, 0.0, 0.0, 3.0, 1e-17};
  std::vector<double> pulse;
  for (const int bins : {1, 3, 10}) {
    pulseSum(energy, bins, pulse);
    ASSERT_EQ(pulse.size(), energy.size());
    for (std::size_t i = 0; i < energy.size(); ++i) {
      double expected = 0.0;
      for (std::size_t j = i + 1 - std::min<std::size_t>(i + 1, static_cast<std::size_t>(bins)); j <= i; ++j) expected += energy[j];
      EXPECT_NEAR(pulse[i], expected, 1e-15) << bins << " " << i;
      EXPECT_GE(pulse[i], 0.0);
    }
  }
  EXPECT_THROW(pulseSum(energy, 0, pulse), ValueError);
}

}  // namespace
}  // namespace sonarmap
