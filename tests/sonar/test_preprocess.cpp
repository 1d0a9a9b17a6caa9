/// Tests of removeSelfReflection, smooth and the smoothing names.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/preprocess.hpp"

namespace sonarmap {
namespace {

PolarImage imageOf(const cv::Mat& intensities, double bin_length_m = 0.01) {
  PolarImage polar;
  polar.intensities = intensities.clone();
  polar.valid_bins.assign(static_cast<std::size_t>(intensities.rows), intensities.cols);
  polar.bearing_rad.assign(static_cast<std::size_t>(intensities.rows), 0.0);
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
  smooth(polar, {Smoothing::kNone, 5, 1.0});
  EXPECT_EQ(cv::countNonZero(polar.intensities != noisy), 0);
}

TEST(sonarPreprocess, EachFilterReducesNoiseAndKeepsTheLevel) {
  const cv::Mat noisy = noisyFlat();
  const double before = stddevOf(noisy);
  for (Smoothing kind : {Smoothing::kMean, Smoothing::kMedian, Smoothing::kGaussian}) {
    PolarImage polar = imageOf(noisy);
    smooth(polar, {kind, 5, 1.5});
    EXPECT_LT(stddevOf(polar.intensities), 0.5 * before) << smoothingName(kind);
    EXPECT_NEAR(cv::mean(polar.intensities)[0], 100.0, 3.0) << smoothingName(kind);
    EXPECT_EQ(polar.intensities.size(), noisy.size());
  }
}

TEST(sonarPreprocess, MedianRemovesAnImpulseMeanAndGaussianSpreadIt) {
  cv::Mat impulse = cv::Mat::zeros(21, 21, CV_8UC1);
  impulse.at<std::uint8_t>(10, 10) = 255;
  PolarImage median = imageOf(impulse), mean = imageOf(impulse), gauss = imageOf(impulse);
  smooth(median, {Smoothing::kMedian, 3, 0.0});
  smooth(mean, {Smoothing::kMean, 3, 0.0});
  smooth(gauss, {Smoothing::kGaussian, 5, 1.0});
  EXPECT_EQ(cv::countNonZero(median.intensities), 0);
  EXPECT_EQ(cv::countNonZero(mean.intensities), 9);          // 3 × 3 box of 255 / 9
  EXPECT_NEAR(mean.intensities.at<std::uint8_t>(9, 11), 28, 1);
  EXPECT_GT(cv::countNonZero(gauss.intensities), 9);
  EXPECT_GT(gauss.intensities.at<std::uint8_t>(10, 10), gauss.intensities.at<std::uint8_t>(10, 11));
}

TEST(sonarPreprocess, InvalidOptionsThrow) {
  PolarImage polar = imageOf(noisyFlat());
  EXPECT_THROW(smooth(polar, {Smoothing::kGaussian, 4, 1.0}), ValueError);
  EXPECT_THROW(smooth(polar, {Smoothing::kMean, 0, 1.0}), ValueError);
  EXPECT_THROW(smooth(polar, {Smoothing::kMedian, 257, 1.0}), ValueError);
  EXPECT_THROW(smooth(polar, {Smoothing::kGaussian, 5, -1.0}), ValueError);
  PolarImage wrong = imageOf(cv::Mat::zeros(3, 3, CV_8UC1));
  wrong.intensities = cv::Mat::zeros(3, 3, CV_16UC1);
  EXPECT_THROW(smooth(wrong, {}), ValueError);
}

TEST(sonarPreprocess, SmoothingNamesRoundTrip) {
  for (Smoothing kind : {Smoothing::kNone, Smoothing::kMean, Smoothing::kMedian, Smoothing::kGaussian}) {
    EXPECT_EQ(parseSmoothing(smoothingName(kind)), kind);
  }
  EXPECT_EQ(smoothingName(Smoothing::kGaussian), "gaussian");
  EXPECT_THROW(parseSmoothing("bilateral"), ValueError);
  EXPECT_EQ(SmoothingOptions{}.kind, Smoothing::kGaussian);  // the paper's choice (§8.1, §9)
  EXPECT_EQ(SmoothingOptions{}.kernel_size, 11);
}

}  // namespace
}  // namespace sonarmap
