/// Tests of makePolarImage, makeCartesianImage and writePng.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "common/temp_dir.hpp"

namespace sonarmap {
namespace {

constexpr double kPi = std::numbers::pi;

Beam beam(double bearing_rad, std::vector<std::uint8_t> bins, double bin_length_m = 0.1, double time_s = 0.0) {
  return Beam{time_s, bearing_rad, bin_length_m, std::move(bins)};
}

TEST(sonarPolarImage, RowsAreBeamsPaddedToTheWidest) {
  const std::vector<Beam> beams = {beam(0.0, {1, 2, 3}), beam(0.1, {4, 5, 6, 7, 8}, 0.1, 1.0),
                                   beam(0.2, {9}, 0.1, 2.0), beam(0.3, {1, 1})};
  const PolarImage polar = makePolarImage(beams, 1, 3);  // beams 1 and 2
  ASSERT_EQ(polar.rows(), 2);
  ASSERT_EQ(polar.cols(), 5);
  EXPECT_EQ(polar.intensities.type(), CV_8UC1);
  EXPECT_EQ(polar.valid_bins, (std::vector<int>{5, 1}));
  EXPECT_EQ(polar.bearing_rad, (std::vector<double>{0.1, 0.2}));
  EXPECT_EQ(polar.time_s, (std::vector<double>{1.0, 2.0}));
  EXPECT_DOUBLE_EQ(polar.bin_length_m, 0.1);
  EXPECT_EQ(polar.intensities.at<std::uint8_t>(0, 4), 8);
  EXPECT_EQ(polar.intensities.at<std::uint8_t>(1, 0), 9);
  for (int c = 1; c < 5; ++c) EXPECT_EQ(polar.intensities.at<std::uint8_t>(1, c), 0) << "padding at " << c;
}

TEST(sonarPolarImage, KeepsTheShortestPulseOfItsBeams) {
  std::vector<Beam> beams = {beam(0.0, {1}), beam(0.1, {2}), beam(0.2, {3}), beam(0.3, {4})};
  EXPECT_FALSE(makePolarImage(beams, 0, 4).pulse_length_m.has_value());  // no beam says
  beams[1].pulse_length_m = 0.02;
  beams[2].pulse_length_m = 0.008;
  EXPECT_EQ(makePolarImage(beams, 0, 4).pulse_length_m, 0.008);
  EXPECT_EQ(makePolarImage(beams, 0, 2).pulse_length_m, 0.02);
  EXPECT_FALSE(makePolarImage(beams, 3, 4).pulse_length_m.has_value());
}

TEST(sonarPolarImage, RejectsEmptyRangeAndMixedBinLengths) {
  const std::vector<Beam> beams = {beam(0.0, {1, 2}), beam(0.1, {1, 2}, 0.2)};
  EXPECT_THROW(makePolarImage(beams, 1, 1), ValueError);
  EXPECT_THROW(makePolarImage(beams, 0, 3), ValueError);
  EXPECT_THROW(makePolarImage(beams, 0, 2), ValueError);
  EXPECT_NO_THROW(makePolarImage(beams, 1, 2));
}

TEST(sonarCartesianImage, BeamAtBearingZeroLightsAheadUp) {
  const std::vector<Beam> beams = {beam(0.0, std::vector<std::uint8_t>(10, 200))};  // 1 m of bins
  const PolarImage polar = makePolarImage(beams, 0, 1);
  const cv::Mat image = makeCartesianImage(polar, 0.05, 10.0 * kPi / 180.0);
  ASSERT_EQ(image.type(), CV_8UC1);
  ASSERT_EQ(image.rows, 41);  // 2 · ceil(1.0 / 0.05) + 1
  ASSERT_EQ(image.cols, 41);
  const int c = 20;
  // Seen from above, ahead (+x) up. (The last pixel lies at exactly 1.0 m, the far end of the last
  // bin, and stays 0.)
  for (int v = 1; v < c; ++v) EXPECT_EQ(image.at<std::uint8_t>(v, c), 200) << "+x (ahead) pixel " << v;
  for (int v = c + 1; v < image.rows; ++v) EXPECT_EQ(image.at<std::uint8_t>(v, c), 0) << "−x pixel " << v;
  for (int u = c + 1; u < image.cols; ++u) EXPECT_EQ(image.at<std::uint8_t>(c, u), 0) << "+y pixel " << u;
  EXPECT_EQ(cv::countNonZero(image.rowRange(c + 1, image.rows)), 0);  // nothing on the lower half
  // The wedge is ±5°: at 0.9 m a pixel 0.05 m off-axis (3.2°) is lit, 0.15 m off (9.5°) is not.
  EXPECT_EQ(image.at<std::uint8_t>(c - 18, c + 1), 200);
  EXPECT_EQ(image.at<std::uint8_t>(c - 18, c + 3), 0);
}

TEST(sonarCartesianImage, StarboardIsRightAndAnglesInterpolate) {
  // Beams at 80° and 100°, 20° apart, width 30°: the gap is filled, blending the two values.
  const std::vector<Beam> beams = {beam(80.0 * kPi / 180.0, std::vector<std::uint8_t>(10, 100)),
                                   beam(100.0 * kPi / 180.0, std::vector<std::uint8_t>(10, 200))};
  const cv::Mat image = makeCartesianImage(makePolarImage(beams, 0, 2), 0.05, 30.0 * kPi / 180.0);
  const int c = 20;
  EXPECT_NEAR(image.at<std::uint8_t>(c, c + 15), 150, 1);  // right (90°, starboard): halfway
  EXPECT_EQ(image.at<std::uint8_t>(c, c - 15), 0);          // left (port): no beam
  // Above the horizontal (bearing < 90°, towards ahead) is nearer the 100-valued beam.
  EXPECT_LT(image.at<std::uint8_t>(c - 2, c + 15), 150);
  EXPECT_GT(image.at<std::uint8_t>(c + 2, c + 15), 150);
}

TEST(sonarCartesianImage, DistantBeamsOnlyFillTheirOwnWidth) {
  const std::vector<Beam> beams = {beam(0.0, std::vector<std::uint8_t>(10, 100)),
                                   beam(kPi / 2.0, std::vector<std::uint8_t>(10, 100))};
  const cv::Mat image = makeCartesianImage(makePolarImage(beams, 0, 2), 0.05, 4.0 * kPi / 180.0);
  const int c = 20;
  const double r_px = 15.0;  // 0.75 m
  const auto at = [&](double deg) {
    return image.at<std::uint8_t>(static_cast<int>(std::lround(c - r_px * std::cos(deg * kPi / 180.0))),
                                  static_cast<int>(std::lround(c + r_px * std::sin(deg * kPi / 180.0))));
  };
  EXPECT_EQ(at(0.0), 100);
  EXPECT_EQ(at(90.0), 100);
  EXPECT_EQ(at(45.0), 0);  // between them, 45° from both: no beam reaches it
}

TEST(sonarCartesianImage, RejectsBadArguments) {
  const PolarImage polar = makePolarImage({beam(0.0, {1, 2})}, 0, 1);
  EXPECT_THROW(makeCartesianImage(polar, 0.0, 0.1), ValueError);
  EXPECT_THROW(makeCartesianImage(polar, 0.01, 0.0), ValueError);
  EXPECT_THROW(makeCartesianImage(polar, 1e-9, 0.1), ValueError);  // too many pixels
  EXPECT_THROW(makeCartesianImage(PolarImage{}, 0.01, 0.1), ValueError);
}

TEST(sonarPng, WritesAtomicallyAndReadsBack) {
  test::TempDir dir;
  cv::Mat image(7, 5, CV_8UC1);
  cv::randu(image, 0, 255);
  const std::string path = dir.file("image.png");
  writePng(path, image);
  const cv::Mat back = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(back.empty());
  EXPECT_EQ(cv::countNonZero(back != image), 0);
  writePng(path, cv::Mat::zeros(3, 3, CV_8UC1));  // replaces the existing file
  EXPECT_EQ(cv::imread(path, cv::IMREAD_UNCHANGED).rows, 3);
  // Only the target is left: no temporary files.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator{}), 1);
}

TEST(sonarPng, FailuresThrowAndLeaveNothing) {
  test::TempDir dir;
  EXPECT_THROW(writePng(dir.file("no/such/folder/x.png"), cv::Mat::zeros(2, 2, CV_8UC1)), FileError);
  EXPECT_THROW(writePng(dir.file("empty.png"), cv::Mat()), FileError);
  EXPECT_THROW(writePng(dir.file("float.png"), cv::Mat::zeros(2, 2, CV_32FC1)), FileError);
  std::filesystem::create_directory(dir.file("folder.png"));  // rename onto a folder fails
  EXPECT_THROW(writePng(dir.file("folder.png"), cv::Mat::zeros(2, 2, CV_8UC1)), FileError);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator{}), 1);
}

}  // namespace
}  // namespace sonarmap
