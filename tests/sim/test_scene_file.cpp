// The scene text format: exact round trip, comments, and errors that name the file and the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/scene_file.hpp"

namespace sonarmap {
namespace {

bool samePrimitive(const Primitive& a, const Primitive& b) {
  if (a.index() != b.index()) return false;
  if (const auto* p = std::get_if<Plane>(&a)) {
    const auto& q = std::get<Plane>(b);
    return p->point_m == q.point_m && p->normal == q.normal && p->reflectivity == q.reflectivity;
  }
  if (const auto* p = std::get_if<Box>(&a)) {
    const auto& q = std::get<Box>(b);
    return p->center_m == q.center_m && p->size_m == q.size_m && p->yaw_rad == q.yaw_rad &&
           p->reflectivity == q.reflectivity;
  }
  const auto& p = std::get<Cylinder>(a);
  const auto& q = std::get<Cylinder>(b);
  return p.center_x_m == q.center_x_m && p.center_y_m == q.center_y_m && p.radius_m == q.radius_m &&
         p.z_min_m == q.z_min_m && p.z_max_m == q.z_max_m && p.reflectivity == q.reflectivity;
}

void expectSameScene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.reverberation_db, b.reverberation_db);
  ASSERT_EQ(a.primitives.size(), b.primitives.size());
  for (std::size_t i = 0; i < a.primitives.size(); ++i)
    EXPECT_TRUE(samePrimitive(a.primitives[i], b.primitives[i])) << i;
}

/// The FileError message readScene gives for `text`, or "no error".
std::string errorOf(const std::string& text) {
  std::istringstream in(text);
  try {
    readScene(in, "broken.scene");
  } catch (const FileError& error) {
    return error.what();
  }
  return "no error";
}

TEST(simSceneFile, BuiltinScenesRoundTripExactly) {
  test::TempDir dir;
  for (const std::string& name : builtinSceneNames()) {
    for (const double reach_m : {5.0, 20.0, 30.0, 50.0}) {  // as built for the presets' heads
      const Scene scene = builtinScene(name, reach_m, (reach_m == 5.0 ? 35.0 : 25.0) * std::numbers::pi / 180.0);
      const std::string path = dir.file(name + ".scene");
      writeScene(path, scene);
      expectSameScene(readScene(path), scene);
    }
  }
}

TEST(simSceneFile, AwkwardNumbersRoundTripExactly) {
  Scene scene;
  scene.primitives.push_back(Plane{{0.1, -1e-300, 1.0 / 3.0}, {0.0, 2.0 / 3.0, -7.0}, 0.123456789012345678});
  scene.primitives.push_back(Box{{1e5, -0.0, 3.5}, {0.3, 1e-6, 2.0}, -2.0 * std::numbers::pi / 7.0, 1.0});
  scene.primitives.push_back(Cylinder{-4.25, 1.0 / 7.0, 0.2, -1.3, 3.5, 0.0});
  scene.reverberation_db = -27.0 / 7.0;
  std::stringstream text;
  writeScene(text, scene);
  expectSameScene(readScene(text, "memory"), scene);
}

TEST(simSceneFile, CommentsBlankLinesAndTabsAreAccepted) {
  std::istringstream in(
      "# a tank floor and a pile\n"
      "\n"
      "plane 0 0 -1.5  0 0 1  0.3   # the floor\n"
      "\tcylinder\t2 0 0.2 -1.5 0.5 0.8\r\n"
      "   # indented comment\n");
  const Scene scene = readScene(in, "memory");
  ASSERT_EQ(scene.primitives.size(), 2U);
  EXPECT_DOUBLE_EQ(std::get<Plane>(scene.primitives[0]).point_m.z(), -1.5);
  EXPECT_DOUBLE_EQ(std::get<Cylinder>(scene.primitives[1]).reflectivity, 0.8);
}

TEST(simSceneFile, BrokenLinesNameFileLineAndProblem) {
  const std::string good = "plane 0 0 -1.5 0 0 1 0.3\n";
  auto expectError = [&](const std::string& bad_line, const std::string& expected) {
    const std::string message = errorOf(good + "# comment\n" + bad_line + "\n");
    EXPECT_NE(message.find("broken.scene: line 3"), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  };
  expectError("sphere 0 0 0 1 0.5", "unknown primitive 'sphere'");
  expectError("box 0 0 0 1 1 1 0", "7 value(s), expected 8");
  expectError("cylinder 0 0 0.2 -1 1 0.5 9", "7 value(s), expected 6");
  expectError("plane 0 0 x 0 0 1 0.3", "'x' is not a number");
  expectError("plane 0 0 1e999 0 0 1 0.3", "not finite");
  expectError("plane 0 0 nan 0 0 1 0.3", "not finite");
  expectError("plane 0 0 0 0 0 0 0.3", "normal must be non-zero");
  expectError("box 0 0 0 1 0 1 0 0.5", "size_m.y must be > 0");
  expectError("cylinder 0 0 -0.2 -1 1 0.5", "radius_m must be > 0");
  expectError("cylinder 0 0 0.2 1 -1 0.5", "z_max_m");
  expectError("plane 0 0 0 0 0 1 1.5", "reflectivity must be in [0, 1]");
  expectError("reverberation -27 3", "2 value(s), expected 1: level_db");
  expectError("reverberation inf", "not finite");
  EXPECT_NE(errorOf(good + "reverberation -27\nreverberation -30\n").find("line 3: reverberation: given twice"),
            std::string::npos);
}

TEST(simSceneFile, ReverberationIsReadAndOnlyTheTankHasIt) {
  std::istringstream in("plane 0 0 -1.5 0 0 1 0.3\nreverberation -27.5  # a small concrete basin\n");
  EXPECT_EQ(readScene(in, "memory").reverberation_db, -27.5);
  EXPECT_TRUE(builtinScene("tank").reverberation_db.has_value());
  for (const char* name : {"harbour", "hull", "soft", "open-water", "quay3d"}) {
    EXPECT_FALSE(builtinScene(name).reverberation_db.has_value()) << name;  // open water: nothing bounces back
  }
}

TEST(simSceneFile, EmptyAndMissingFilesAreErrors) {
  EXPECT_NE(errorOf("# nothing but comments\n\n").find("no primitive"), std::string::npos);
  test::TempDir dir;
  const std::string missing = dir.file("missing.scene");
  try {
    readScene(missing);
    FAIL() << "expected FileError";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find(missing), std::string::npos);
  }
  EXPECT_THROW(writeScene(dir.file("empty.scene"), Scene{}), ValueError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("empty.scene")));
}

TEST(simSceneFile, InvalidSceneIsNotWrittenAndTheOldFileStays) {
  test::TempDir dir;
  const std::string path = dir.file("truth.scene");
  writeScene(path, builtinScene("tank"));
  Scene bad = builtinScene("tank");
  bad.primitives.push_back(Cylinder{0.0, 0.0, 0.0, 0.0, 1.0, 0.5});
  EXPECT_THROW(writeScene(path, bad), ValueError);
  expectSameScene(readScene(path), builtinScene("tank"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator{}), 1);
}

}  // namespace
}  // namespace sonarmap
