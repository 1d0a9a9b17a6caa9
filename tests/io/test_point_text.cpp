// Plain-text point files (`x y z` per line, OctoMap's scan.dat style).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/point_text.hpp"

namespace sonarmap {
namespace {

PointCloud parse(const std::string& text) {
  std::istringstream in(text);
  return readPointText(in, "points.txt");
}

void expectFileError(const std::string& text, const std::string& message_part) {
  try {
    parse(text);
    ADD_FAILURE() << "no FileError; expected one mentioning '" << message_part << "'";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find(message_part), std::string::npos) << error.what();
  }
}

TEST(ioPointText, ReadsPointsSkippingBlankLinesAndComments) {
  const PointCloud points = parse(
      "# scan.dat\n"
      "1 2 3\n"
      "\n"
      "   \t \n"
      "-0.5\t1e-3  +2.25   # trailing comment\r\n"
      "  # indented comment\n"
      "4.0 -5 6.125");  // no final newline
  ASSERT_EQ(points.size(), 3U);
  EXPECT_EQ(points[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(points[1], Eigen::Vector3d(-0.5, 1e-3, 2.25));  // parsed exactly (from_chars)
  EXPECT_EQ(points[2], Eigen::Vector3d(4.0, -5.0, 6.125));
}

TEST(ioPointText, ReadsAFile) {
  const test::TempDir dir;
  std::ofstream(dir.file("scan.dat")) << "0.1 0.2 0.3\n0.4 0.5 0.6\n";
  const PointCloud points = readPointText(dir.file("scan.dat"));
  ASSERT_EQ(points.size(), 2U);
  EXPECT_EQ(points[1], Eigen::Vector3d(0.4, 0.5, 0.6));
  EXPECT_THROW(readPointText(dir.file("missing.dat")), FileError);
}

TEST(ioPointText, NonFinitePointsAreKeptForInsertionToSkip) {
  std::istringstream in("nan 0 0\n0 -inf 0\n0 0 1e999\n1 2 3\n");
  const PointCloud points = readPointText(in, "points.txt");
  ASSERT_EQ(points.size(), 4U);
  EXPECT_TRUE(std::isnan(points[0].x()));
  EXPECT_TRUE(std::isinf(points[1].y()));
  EXPECT_TRUE(std::isinf(points[2].z()));
  EXPECT_TRUE(points[3].allFinite());
}

TEST(ioPointText, BadLinesThrowFileErrorWithTheLineNumber) {
  expectFileError("1 2 3\n1 2\n", "points.txt: line 2: 2 value(s), expected 3");
  expectFileError("1 2 3 4\n", "line 1: more than 3 values");
  expectFileError("# c\n\n1 2 x\n", "line 3: 'x' is not a number");
  expectFileError("1 2 3\n1,2,3\n", "line 2: '1,2,3' is not a number");
  expectFileError("1 2 3abc\n", "'3abc' is not a number");
  expectFileError("", "points.txt: no points");
  expectFileError("# only a comment\n\n", "no points");
}

}  // namespace
}  // namespace sonarmap
