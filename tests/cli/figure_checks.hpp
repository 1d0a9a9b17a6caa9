#pragma once
// Checks the CLI tests share on the PNG figures the tool writes (render/figure.hpp): legible size,
// a title band and axis labels with ink, and pixels of a given colour.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sonarmap/render/figure.hpp"

namespace sonarmap::test {

/// Pixels of `colour` in `area` of the BGR `image` (the whole image by default).
inline int pixelsOf(const cv::Mat& image, const cv::Vec3b& colour, cv::Rect area = {}) {
  if (area.area() == 0) area = cv::Rect(0, 0, image.cols, image.rows);
  int n = 0;
  for (int row = area.y; row < area.y + area.height; ++row)
    for (int col = area.x; col < area.x + area.width; ++col) n += image.at<cv::Vec3b>(row, col) == colour ? 1 : 0;
  return n;
}

/// Non-white pixels of `area` of the BGR `image`.
inline int inkIn(const cv::Mat& image, const cv::Rect& area) {
  return area.area() - pixelsOf(image, cv::Vec3b(255, 255, 255), area);
}

/// Reads the figure at `png` and checks what every figure has: BGR, at least 800 pixels on its
/// long side, a title line on top (ink in the top 40 rows) and y tick labels on the left (ink in
/// the left 70 columns). Returns the image (empty when it does not decode).
inline cv::Mat readFigure(const std::filesystem::path& png) {
  SCOPED_TRACE(png.filename().string());
  const cv::Mat image = cv::imread(png.string(), cv::IMREAD_UNCHANGED);
  EXPECT_FALSE(image.empty()) << "does not decode";
  if (image.empty()) return image;
  EXPECT_EQ(image.channels(), 3);
  if (image.channels() != 3) return cv::Mat();
  EXPECT_GE(std::max(image.rows, image.cols), kMinFigureLongSide_px);
  EXPECT_GT(inkIn(image, cv::Rect(0, 0, image.cols, 40)), 300) << "no title line";
  EXPECT_GT(inkIn(image, cv::Rect(0, 60, 70, image.rows - 120)), 200) << "no y axis labels";
  return image;
}

}  // namespace sonarmap::test
