// The scene text format: exact round trip in every frame, the frame named by the header line (old
// files read as NWU), comments, and errors that name the file and the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/scene_file.hpp"
#include "sonarmap/sim/scene_frame.hpp"

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

constexpr MapFrame kFrames[] = {MapFrame::kEnu, MapFrame::kNed, MapFrame::kNwu};

TEST(simSceneFile, BuiltinScenesRoundTripExactlyInEveryFrame) {
  test::TempDir dir;
  for (const MapFrame frame : kFrames) {
    for (const std::string& name : builtinSceneNames()) {
      for (const double reach_m : {5.0, 20.0, 30.0, 50.0}) {  // as built for the presets' heads
        const Scene scene = builtinScene(name, reach_m, (reach_m == 5.0 ? 35.0 : 25.0) * std::numbers::pi / 180.0);
        const std::string path = dir.file(name + ".scene");
        writeScene(path, scene, frame);
        SCOPED_TRACE(std::string(mapFrameName(frame)) + " " + name);
        expectSameScene(readScene(path), scene);
      }
    }
  }
}

TEST(simSceneFile, AwkwardNumbersRoundTripExactly) {
  Scene scene;
  scene.primitives.push_back(Plane{{0.1, -1e-300, 1.0 / 3.0}, {0.0, 2.0 / 3.0, -7.0}, 0.123456789012345678});
  scene.primitives.push_back(Box{{1e5, -0.0, 3.5}, {0.3, 1e-6, 2.0}, -2.0 * std::numbers::pi / 7.0, 1.0});
  scene.primitives.push_back(Cylinder{-4.25, 1.0 / 7.0, 0.2, -1.3, 3.5, 0.0});
  scene.reverberation_db = -27.0 / 7.0;
  for (const MapFrame frame : kFrames) {
    std::stringstream text;
    writeScene(text, scene, frame);
    SCOPED_TRACE(mapFrameName(frame));
    expectSameScene(readScene(text, "memory"), scene);
  }
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
  EXPECT_THROW(writeScene(dir.file("empty.scene"), Scene{}, kDefaultMapFrame), ValueError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("empty.scene")));
}

TEST(simSceneFile, InvalidSceneIsNotWrittenAndTheOldFileStays) {
  test::TempDir dir;
  const std::string path = dir.file("truth.scene");
  writeScene(path, builtinScene("tank"), kDefaultMapFrame);
  Scene bad = builtinScene("tank");
  bad.primitives.push_back(Cylinder{0.0, 0.0, 0.0, 0.0, 1.0, 0.5});
  EXPECT_THROW(writeScene(path, bad, kDefaultMapFrame), ValueError);
  expectSameScene(readScene(path), builtinScene("tank"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator{}), 1);
}

// The frames' axes written out by hand (REP 103 and the NED convention), not taken from the code:
// a point n north, e east, u up is NWU (n, −e, u), ENU (e, n, u), NED (n, e, −u).
TEST(simSceneFile, HandWrittenFramesMeanTheSamePlace) {
  // A wall 5 m east facing west, a pile 3 m north and 2 m east from 1 m to 2.5 m deep, a block
  // 4 m long from north to south (on a heading of 0) whose centre is 6 m north, 1 m down.
  const std::string enu =
      "# sonarmap scene: map frame ENU (x east, y north, z up), metres, radians; reflectivity in [0, 1]\n"
      "plane 5 0 0  -1 0 0  0.9\n"
      "cylinder 2 3  0.25  -2.5 -1  0.8\n"
      "box 0 6 -1  1 4 0.5  0  0.7\n";
  const std::string ned =
      "# sonarmap scene: map frame NED (x north, y east, z down), metres, radians; reflectivity in [0, 1]\n"
      "plane 0 5 0  0 -1 0  0.9\n"
      "cylinder 3 2  0.25  1 2.5  0.8\n"
      "box 6 0 1  4 1 0.5  0  0.7\n";
  const std::string nwu_old =
      "# sonarmap scene: map frame (x north, y west, z up), metres, radians; reflectivity in [0, 1]\n"
      "plane 0 -5 0  0 1 0  0.9\n"
      "cylinder 3 -2  0.25  -2.5 -1  0.8\n"
      "box 6 0 -1  4 1 0.5  0  0.7\n";
  const std::string nwu_unnamed = nwu_old.substr(nwu_old.find('\n') + 1);  // a hand-written file: no header
  std::istringstream enu_in(enu), ned_in(ned), old_in(nwu_old), unnamed_in(nwu_unnamed);
  const Scene from_enu = readScene(enu_in, "enu.scene");
  const Scene from_ned = readScene(ned_in, "ned.scene");
  const Scene from_old = readScene(old_in, "old.scene");
  const Scene from_unnamed = readScene(unnamed_in, "unnamed.scene");
  // Internally NWU: the old file's numbers, as read before frames were named.
  const auto& wall = std::get<Plane>(from_old.primitives[0]);
  EXPECT_EQ(wall.point_m, Eigen::Vector3d(0, -5, 0));
  EXPECT_EQ(wall.normal, Eigen::Vector3d(0, 1, 0));
  const auto& pile = std::get<Cylinder>(from_old.primitives[1]);
  EXPECT_EQ(pile.center_x_m, 3.0);
  EXPECT_EQ(pile.center_y_m, -2.0);
  EXPECT_EQ(pile.z_min_m, -2.5);
  EXPECT_EQ(pile.z_max_m, -1.0);
  const auto& block = std::get<Box>(from_old.primitives[2]);
  EXPECT_EQ(block.center_m, Eigen::Vector3d(6, 0, -1));
  EXPECT_EQ(block.size_m, Eigen::Vector3d(4, 1, 0.5));
  EXPECT_EQ(block.yaw_rad, 0.0);
  // The same solids from every file: each point of space is as far from each surface, and the
  // ENU block (sizes 1 along east, 4 along north) is the NWU block (4 along north, 1 along west).
  for (const Scene* scene : {&from_enu, &from_ned, &from_unnamed}) {
    ASSERT_EQ(scene->primitives.size(), 3U);
    for (const Eigen::Vector3d& point_nwu :
         {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(5.5, -1.5, -0.7), Eigen::Vector3d(6.2, 0.3, -1.1),
          Eigen::Vector3d(3.1, -2.4, -3.0), Eigen::Vector3d(-2, 7, 4)}) {
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(distanceToSurface(scene->primitives[i], point_nwu), distanceToSurface(from_old.primitives[i], point_nwu),
                    1e-12)
            << i << " at " << point_nwu.transpose();
      }
    }
  }
}

TEST(simSceneFile, BoxYawTurnsWithTheFrame) {
  // A block 3 m by 1 m whose long side points 30° east of north (a heading of 30°), centred 4 m
  // north, 2 m east, 1 m down. NED: yaw from north towards east, +30°. ENU: from east towards
  // north, 60°. NWU: from north towards west, −30°.
  const double deg = std::numbers::pi / 180.0;
  const Box ned{{4, 2, 1}, {3, 1, 0.5}, 30 * deg, 0.7};
  const Box enu{{2, 4, -1}, {3, 1, 0.5}, 60 * deg, 0.7};
  const Box nwu{{4, -2, -1}, {3, 1, 0.5}, -30 * deg, 0.7};
  const Primitive from_ned = primitiveFromFrame(ned, MapFrame::kNed);
  const Primitive from_enu = primitiveFromFrame(enu, MapFrame::kEnu);
  // Points around and inside the block, NWU: each as far from all three descriptions.
  for (double north = 1.0; north <= 7.0; north += 0.75) {
    for (double west = -5.0; west <= 1.0; west += 0.75) {
      for (const double up : {-1.6, -1.0, -0.2}) {
        const Eigen::Vector3d point(north, west, up);
        EXPECT_NEAR(distanceToSurface(from_ned, point), distanceToSurface(nwu, point), 1e-12) << point.transpose();
        EXPECT_NEAR(distanceToSurface(from_enu, point), distanceToSurface(nwu, point), 1e-12) << point.transpose();
      }
    }
  }
}

TEST(simSceneFile, EveryFrameKeepsEachSolidAndRoundTripsExactly) {
  // Each primitive, turned into a frame, is the same solid seen in that frame's coordinates:
  // its distance from R·p equals the NWU primitive's from p, for R = the frame's rotation.
  Scene scene = builtinScene("quay3d");  // a sloped plane, yawed boxes
  scene.primitives.push_back(Box{{1.5, -2.5, -0.5}, {0.7, 2.9, 1.3}, 1.1, 0.5});
  scene.primitives.push_back(Cylinder{-1.25, 2.5, 0.4, -3.0, 0.75, 0.9});
  for (const MapFrame frame : kFrames) {
    const Eigen::Matrix3d rotation = nwuToMapFrame(frame);
    const Scene framed = sceneInFrame(scene, frame);
    const Scene back = sceneFromFrame(framed, frame);
    SCOPED_TRACE(mapFrameName(frame));
    expectSameScene(back, scene);
    for (std::size_t i = 0; i < scene.primitives.size(); ++i) {
      for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.3, 2.9, -3.5), Eigen::Vector3d(-1.2, -0.8, -4.5),
                                       Eigen::Vector3d(3.0, 0.0, -5.0), Eigen::Vector3d(1.9, -2.4, -2.2),
                                       Eigen::Vector3d(1.4, -2.0, -0.4)}) {
        EXPECT_NEAR(distanceToSurface(framed.primitives[i], rotation * p), distanceToSurface(scene.primitives[i], p),
                    1e-12)
            << i;
      }
    }
  }
}

TEST(simSceneFile, HeaderNamesTheFrameWrittenIn) {
  const Scene scene = builtinScene("tank");
  const std::pair<MapFrame, const char*> expected[] = {
      {MapFrame::kEnu, "# sonarmap scene: map frame ENU (x east, y north, z up), metres, radians; reflectivity in [0, 1]"},
      {MapFrame::kNed, "# sonarmap scene: map frame NED (x north, y east, z down), metres, radians; reflectivity in [0, 1]"},
      {MapFrame::kNwu, "# sonarmap scene: map frame NWU (x north, y west, z up), metres, radians; reflectivity in [0, 1]"}};
  for (const auto& [frame, header] : expected) {
    std::stringstream text;
    writeScene(text, scene, frame);
    std::string first;
    std::getline(text, first);
    EXPECT_EQ(first, header);
    EXPECT_EQ(text.str().find("-0 "), std::string::npos) << "no negative zero written:\n" << text.str();
  }
}

TEST(simSceneFile, UnknownFrameAndMisplacedHeadersAreErrors) {
  const std::string header = "# sonarmap scene: map frame ";
  const std::string body = "plane 0 0 -1.5 0 0 1 0.3\n";
  std::string message = errorOf("# a basin\n" + header + "ECEF (x, y, z), metres\n" + body);
  EXPECT_NE(message.find("broken.scene: line 2: scene frame 'ECEF' unknown, expected ENU, NED or NWU"),
            std::string::npos)
      << message;
  EXPECT_NE(errorOf(header + "enu (x east, y north, z up)\n" + body).find("line 1: scene frame 'enu' unknown"),
            std::string::npos);  // written by the tool in capitals, as map headers are
  EXPECT_NE(errorOf(header + "\n" + body).find("line 1: scene frame '' unknown"), std::string::npos);
  message = errorOf(header + "ENU (x east, y north, z up)\n" + header + "NED (x north, y east, z down)\n" + body);
  EXPECT_NE(message.find("line 2: scene frame named again (first on line 1)"), std::string::npos) << message;
  message = errorOf(body + header + "NED (x north, y east, z down)\n" + body);
  EXPECT_NE(message.find("line 2: scene frame named after the first primitive"), std::string::npos) << message;
  // A CRLF file's header is read as well.
  std::istringstream crlf(header + "NED\r\n" + "cylinder 0 0 0.2 1 2 0.5\r\n");
  EXPECT_EQ(std::get<Cylinder>(readScene(crlf, "crlf.scene").primitives[0]).z_max_m, -1.0);
}

}  // namespace
}  // namespace sonarmap
