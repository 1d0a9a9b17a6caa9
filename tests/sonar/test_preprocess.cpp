/// Tests of removeSelfReflection, smooth and the smoothing names.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <opencv2/core.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/preprocess.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

PolarImage imageOf(const cv::Mat& intensities, double bin_length_m = 0.01) {
  PolarImage polar;
  polar.intensities = intensities.clone();
  polar.valid_bins.assign(static_cast<std::size_t>(intensities.rows), intensities.cols);
  for (int r = 0; r < intensities.rows; ++r) polar.bearing_rad.push_back(r * kDegree);  // 1° apart
  polar.time_s.assign(static_cast<std::size_t>(intensities.rows), 0.0);
  polar.bin_length_m = bin_length_m;
  return polar;
}

/// A flat grey image of 100 with Gaussian noise (σ 20), fixed seed.
cv::Mat noisyFlat() {
  cv::Mat noise(60, 80, CV_32FC1);
  cv::RNG rng(12345);
  rng.fill(noise, cv::RNG::NORMAL, 100.0, 20.0);
  cv::Mat out;
  noise.convertTo(out, CV_8UC1);
  return out;
}

double stddevOf(const cv::Mat& m) {
  cv::Scalar mean, stddev;
  cv::meanStdDev(m, mean, stddev);
  return stddev[0];
}

TEST(sonarPreprocess, SelfReflectionZeroesBinsNearerThanTheRange) {
  PolarImage polar = imageOf(cv::Mat(3, 10, CV_8UC1, cv::Scalar(50)), 0.1);
  removeSelfReflection(polar, 0.3);  // bin centres 0.05, 0.15, 0.25 < 0.3; 0.35 is not
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(polar.intensities.at<std::uint8_t>(r, c), 0);
    for (int c = 3; c < 10; ++c) EXPECT_EQ(polar.intensities.at<std::uint8_t>(r, c), 50);
  }
  removeSelfReflection(polar, 0.0);
  EXPECT_EQ(polar.intensities.at<std::uint8_t>(0, 3), 50);
  removeSelfReflection(polar, 100.0);  // beyond the image: everything
  EXPECT_EQ(cv::countNonZero(polar.intensities), 0);
  EXPECT_THROW(removeSelfReflection(polar, -0.1), ValueError);
}

TEST(sonarPreprocess, NoneLeavesTheImage) {
  const cv::Mat noisy = noisyFlat();
  PolarImage polar = imageOf(noisy);
  smooth(polar, {Smoothing::kNone, 0.05, 5.0 * kDegree});
  EXPECT_EQ(cv::countNonZero(polar.intensities != noisy), 0);
}

TEST(sonarPreprocess, EachFilterReducesNoiseAndKeepsTheLevel) {
  const cv::Mat noisy = noisyFlat();
  const double before = stddevOf(noisy);
  for (Smoothing kind : {Smoothing::kMean, Smoothing::kMedian, Smoothing::kGaussian}) {
    PolarImage polar = imageOf(noisy);
    smooth(polar, {kind, kind == Smoothing::kGaussian ? 0.015 : 0.05, (kind == Smoothing::kGaussian ? 1.5 : 5.0) * kDegree});
    EXPECT_LT(stddevOf(polar.intensities), 0.5 * before) << smoothingName(kind);
    EXPECT_NEAR(cv::mean(polar.intensities)[0], 100.0, 3.0) << smoothingName(kind);
    EXPECT_EQ(polar.intensities.size(), noisy.size());
  }
}

TEST(sonarPreprocess, MedianRemovesAnImpulseMeanAndGaussianSpreadIt) {
  cv::Mat impulse = cv::Mat::zeros(21, 21, CV_8UC1);
  impulse.at<std::uint8_t>(10, 10) = 255;
  PolarImage median = imageOf(impulse), mean = imageOf(impulse), gauss = imageOf(impulse);
  smooth(median, {Smoothing::kMedian, 0.03, 0.0});        // 3 × 3 pixels (square)
  smooth(mean, {Smoothing::kMean, 0.03, 3.0 * kDegree});  // 3 bins × 3 beams
  smooth(gauss, {Smoothing::kGaussian, 0.01, 1.0 * kDegree});  // σ 1 pixel both ways
  EXPECT_EQ(cv::countNonZero(median.intensities), 0);
  EXPECT_EQ(cv::countNonZero(mean.intensities), 9);          // 3 × 3 box of 255 / 9
  EXPECT_NEAR(mean.intensities.at<std::uint8_t>(9, 11), 28, 1);
  EXPECT_GT(cv::countNonZero(gauss.intensities), 9);
  EXPECT_GT(gauss.intensities.at<std::uint8_t>(10, 10), gauss.intensities.at<std::uint8_t>(10, 11));
}

TEST(sonarPreprocess, InvalidOptionsThrow) {
  PolarImage polar = imageOf(noisyFlat());
  EXPECT_THROW(smooth(polar, {Smoothing::kGaussian, -0.01, 1.0 * kDegree}), ValueError);
  EXPECT_THROW(smooth(polar, {Smoothing::kMean, 0.01, -kDegree}), ValueError);
  EXPECT_THROW(smooth(polar, {Smoothing::kMedian, std::nan(""), 0.0}), ValueError);
  EXPECT_THROW(smooth(polar, {Smoothing::kGaussian, std::numeric_limits<double>::infinity(), 0.0}), ValueError);
  PolarImage wrong = imageOf(cv::Mat::zeros(3, 3, CV_8UC1));
  wrong.intensities = cv::Mat::zeros(3, 3, CV_16UC1);
  EXPECT_THROW(smooth(wrong, {}), ValueError);
  PolarImage no_bins = imageOf(noisyFlat(), 0.0);
  EXPECT_THROW(smooth(no_bins, {Smoothing::kGaussian}), ValueError);
}

// The extents are lengths and angles: the same σ in metres blurs the same distance along the beam
// whatever the bin length, and a huge extent is capped at OpenCV's largest kernel, not overflowed.
TEST(sonarPreprocess, ExtentsAreMetresAndDegreesWhateverTheBinLength) {
  auto spread_m = [](double bin_m) {
    const int bins = static_cast<int>(std::lround(2.0 / bin_m));
    cv::Mat impulse = cv::Mat::zeros(1, bins, CV_8UC1);
    impulse.at<std::uint8_t>(0, bins / 2) = 255;
    PolarImage polar = imageOf(impulse, bin_m);
    smooth(polar, {Smoothing::kGaussian, 0.1, 0.0});  // σ 10 cm along the beam
    return cv::countNonZero(polar.intensities) * bin_m;
  };
  EXPECT_NEAR(spread_m(0.01), spread_m(0.05), 0.15);  // ±3σ either way: about 0.6 m of bins
  EXPECT_GT(spread_m(0.01), 0.4);
  PolarImage huge = imageOf(noisyFlat());
  EXPECT_NO_THROW(smooth(huge, {Smoothing::kMean, 1e9, 1e9}));
}

TEST(sonarPreprocess, SmoothingNamesRoundTrip) {
  for (Smoothing kind : {Smoothing::kNone, Smoothing::kMean, Smoothing::kMedian, Smoothing::kGaussian}) {
    EXPECT_EQ(parseSmoothing(smoothingName(kind)), kind);
  }
  EXPECT_EQ(smoothingName(Smoothing::kGaussian), "gaussian");
  EXPECT_THROW(parseSmoothing("bilateral"), ValueError);
  // No smoothing by default (it moves the leading edge nearer); when chosen, the paper's Gaussian
  // (§9: σ 2.3 pixels of 1.25 cm and 1.8°) in physical units.
  EXPECT_EQ(SmoothingOptions{}.kind, Smoothing::kNone);
  EXPECT_NEAR(SmoothingOptions{}.range_m, 2.3 * 0.0125, 0.001);
  EXPECT_NEAR(SmoothingOptions{}.bearing_rad, 2.3 * 1.8 * kDegree, 0.1 * kDegree);
}

}  // namespace
}  // namespace sonarmap
