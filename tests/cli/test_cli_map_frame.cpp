// End-to-end tests of the map's frame and pictures: `--map-frame enu|ned` (the .bt in ENU or NED,
// its header naming the frame, OctoMap still reading it), `info` stating the default, a ROS bag's
// map overlaying its odom frame, PNGs drawn east right and north up with their axes so labelled,
// and a vehicle below the surface getting its obstacles drawn (the picture shows the occupied
// band, and the summary says which).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <tuple>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_fixture.hpp"
#include "figure_checks.hpp"
#include "octomap_leaves.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"
#include "sonarmap/formats/ros_bag_writer.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::test {
namespace {

const fs::path kPoolBag = fs::path(SONARMAP_SHARED_DATA) / "micron_pool_ros1.bag";

Eigen::Vector3d meanOf(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) sum += p;
  return points.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(points.size()));
}

/// The first `n` lines of `path`.
Names headLines(const fs::path& path, std::size_t n) {
  std::ifstream in(path, std::ios::binary);
  Names lines;
  std::string line;
  while (lines.size() < n && std::getline(in, line)) lines.push_back(line);
  return lines;
}

class cliMapFrame : public CliTest {
 protected:
  /// Simulates a static Micron at the origin (NED, heading north) among `scene_text` (NWU scene
  /// file) at `depth_m`; returns the folder.
  fs::path simulateScene(const std::string& scene_text, double depth_m = 0.0) {
    const fs::path scene = root_ / "scene.txt";
    std::ofstream(scene) << scene_text;
    const fs::path dir = root_ / "sim";
    const ProgramRun sim = run({"simulate", scene.string(), "-o", dir.string(), "--turns", "2", "--depth",
                                std::to_string(depth_m), "-q"});
    EXPECT_EQ(sim.exit_code, 0) << sim.err;
    return dir;
  }
};

// A pile 3 m north and 1 m east of the vehicle (a scene file without a frame line is NWU: x 3, y −1).
constexpr const char* kPileNorthEast = "cylinder 3 -1 0.2 -2 2 0.8\n";

TEST_F(cliMapFrame, EnuAndNedMapsPutTheEchoWhereTheFrameSaysAndNameIt) {
  const fs::path sim = simulateScene(kPileNorthEast);
  const fs::path enu = out_ / "enu.bt", ned = out_ / "ned.bt", plain = out_ / "default.bt";
  for (const auto& [path, frame] : {std::pair{enu, "enu"}, std::pair{ned, "ned"}}) {
    const ProgramRun map = run({"map", (sim / "beams.csv").string(), "--nav", (sim / "nav.csv").string(), "-o",
                                path.string(), "--map-frame", frame, "-q"});
    ASSERT_EQ(map.exit_code, 0) << map.err;
  }
  const ProgramRun map = run({"map", (sim / "beams.csv").string(), "--nav", (sim / "nav.csv").string(), "-o",
                              plain.string(), "-q"});
  ASSERT_EQ(map.exit_code, 0) << map.err;
  EXPECT_NE(map.out.find("-> " + plain.string() + " in ENU (x east, y north, z up)"), std::string::npos) << map.out;

  const std::vector<Eigen::Vector3d> in_enu = occupiedCentres(enu);
  const std::vector<Eigen::Vector3d> in_ned = occupiedCentres(ned);
  ASSERT_GE(in_enu.size(), 5u);
  ASSERT_EQ(in_ned.size(), in_enu.size());
  EXPECT_EQ(occupiedCentres(plain).size(), in_enu.size());
  // The pile's echoes lie on its near face, about (n, e) = (2.85, 0.95): ENU (e, n), NED (n, e).
  for (const Eigen::Vector3d& p : in_enu) EXPECT_LT(std::hypot(p.x() - 1.0, p.y() - 3.0), 0.45) << p.transpose();
  for (const Eigen::Vector3d& p : in_ned) EXPECT_LT(std::hypot(p.x() - 3.0, p.y() - 1.0), 0.45) << p.transpose();
  const Eigen::Vector3d e = meanOf(in_enu), n = meanOf(in_ned);
  EXPECT_NEAR(e.x(), n.y(), 1e-9);  // east
  EXPECT_NEAR(e.y(), n.x(), 1e-9);  // north
  EXPECT_NEAR(e.z(), -n.z(), 1e-9);  // up = −down
  EXPECT_EQ(headLines(enu, 3).back(), "# sonarmap map frame: ENU (x east, y north, z up)");
  EXPECT_EQ(headLines(ned, 3).back(), "# sonarmap map frame: NED (x north, y east, z down)");
  EXPECT_EQ(headLines(plain, 3).back(), "# sonarmap map frame: ENU (x east, y north, z up)");

  // eval reads the frame back: both files score the same against the scene.
  const ProgramRun eval_enu = run({"eval", enu.string(), "--truth", (sim / "scene.txt").string(), "-q"});
  const ProgramRun eval_ned = run({"eval", ned.string(), "--truth", (sim / "scene.txt").string(), "-q"});
  ASSERT_EQ(eval_enu.exit_code, 0) << eval_enu.err;
  ASSERT_EQ(eval_ned.exit_code, 0) << eval_ned.err;
  EXPECT_EQ(linesOf(eval_enu.out).front(), linesOf(eval_ned.out).front());
  double precision = 0.0;
  ASSERT_EQ(std::sscanf(eval_enu.out.c_str(), "precision %lf", &precision), 1) << eval_enu.out;
  EXPECT_GT(precision, 0.9);

  expectError(run({"map", (sim / "beams.csv").string(), "-o", (out_ / "x.bt").string(), "--map-frame", "nwu"}), 2);
}

TEST_F(cliMapFrame, InfoStatesTheMapFrame) {
  const fs::path sim = simulateScene(kPileNorthEast);
  const ProgramRun info = run({"info", (sim / "beams.csv").string()});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("map frame   ENU (x east, y north, z up) by default (map --map-frame enu|ned)"),
            std::string::npos)
      << info.out;
  const ProgramRun json = run({"info", (sim / "beams.csv").string(), "--json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(nlohmann::json::parse(json.out)["map_frame"]["default"], "ENU");
}

/// How well the text `text`, drawn as figure.cpp draws axis labels (Hershey simplex, scale 0.55),
/// matches its best place in `area` of `figure`, turned by `rotate` (cv::RotateFlags, or −1: not
/// turned): the normalised correlation of the ink (1 for the same pixels).
double labelMatch(const cv::Mat& figure, const std::string& text, cv::Rect area, int rotate) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 0.55, 1, &baseline);
  cv::Mat label(size.height + baseline + 4, size.width + 4, CV_8UC3, cv::Scalar::all(255));
  cv::putText(label, text, cv::Point(2, size.height + 2), cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar::all(0), 1,
              cv::LINE_AA);
  if (rotate >= 0) cv::rotate(label, label, rotate);
  cv::Mat ink, label_ink;
  cv::cvtColor(figure(area), ink, cv::COLOR_BGR2GRAY);
  cv::cvtColor(label, label_ink, cv::COLOR_BGR2GRAY);
  ink = 255 - ink;
  label_ink = 255 - label_ink;
  cv::Mat found;
  cv::matchTemplate(ink, label_ink, found, cv::TM_CCOEFF_NORMED);
  double best = 0.0;
  cv::minMaxLoc(found, nullptr, &best);
  return best;
}

/// labelMatch of a y axis label, turned either way.
double yLabelMatch(const cv::Mat& figure, const std::string& text) {
  const cv::Rect left(0, 0, 40, figure.rows);
  return std::max(labelMatch(figure, text, left, cv::ROTATE_90_COUNTERCLOCKWISE),
                  labelMatch(figure, text, left, cv::ROTATE_90_CLOCKWISE));
}

TEST_F(cliMapFrame, PictureHasNorthUpEastRightAndSaysSo) {
  const fs::path sim = simulateScene("cylinder 3 0 0.2 -2 2 0.8\n");  // a pile 3 m north
  const fs::path png = out_ / "map.png";
  const ProgramRun map = run({"map", (sim / "beams.csv").string(), "--nav", (sim / "nav.csv").string(), "-o",
                              (out_ / "m.bt").string(), "--png", png.string(), "-q"});
  ASSERT_EQ(map.exit_code, 0) << map.err;
  const cv::Mat figure = readFigure(png);
  ASSERT_FALSE(figure.empty());
  // The sonar (a red dot) and the pile (occupied pixels): the pile straight above the dot.
  cv::Mat red, occupied;
  cv::inRange(figure, cv::Scalar(kTrackBgr[0], kTrackBgr[1], kTrackBgr[2]),
              cv::Scalar(kTrackBgr[0], kTrackBgr[1], kTrackBgr[2]), red);
  cv::inRange(figure, cv::Scalar(kOccupiedBgr[0], kOccupiedBgr[1], kOccupiedBgr[2]),
              cv::Scalar(kOccupiedBgr[0], kOccupiedBgr[1], kOccupiedBgr[2]), occupied);
  // Only the plot: the legend's swatches (right of the plot) hold the same colours.
  const int plot_right = figure.cols - 220;
  red(cv::Rect(plot_right, 0, figure.cols - plot_right, figure.rows)) = 0;
  occupied(cv::Rect(plot_right, 0, figure.cols - plot_right, figure.rows)) = 0;
  const cv::Moments sonar = cv::moments(red, true), pile = cv::moments(occupied, true);
  ASSERT_GT(sonar.m00, 3.0);
  ASSERT_GT(pile.m00, 3.0);
  const double sonar_col = sonar.m10 / sonar.m00, sonar_row = sonar.m01 / sonar.m00;
  const double pile_col = pile.m10 / pile.m00, pile_row = pile.m01 / pile.m00;
  EXPECT_LT(pile_row, sonar_row - 100.0) << "the pile north of the sonar is not drawn above it";
  EXPECT_NEAR(pile_col, sonar_col, 20.0) << "the pile north of the sonar is drawn beside it";
  // The axes say east and north: the labels' text as figure.cpp draws it.
  const cv::Rect bottom(0, figure.rows - 40, figure.cols, 40);
  const double east = labelMatch(figure, "east (m)", bottom, -1), x = labelMatch(figure, "x (m)", bottom, -1);
  const double north = yLabelMatch(figure, "north (m)"), y = yLabelMatch(figure, "y (m)");
  std::printf("axis labels: 'east (m)' %.3f, 'x (m)' %.3f, 'north (m)' %.3f, 'y (m)' %.3f\n", east, x, north, y);
  EXPECT_GT(east, 0.95);
  EXPECT_LT(x, 0.9);
  EXPECT_GT(north, 0.95);
  EXPECT_LT(y, 0.9);
}

TEST_F(cliMapFrame, VehicleThreeMetresDownGetsItsObstaclesDrawnAndTheBandSaid) {
  const fs::path sim = simulateScene("cylinder 3 0 0.2 -6 2 0.8\ncylinder -2 2 0.2 -6 2 0.8\n", 3.0);
  const fs::path png = out_ / "map.png";
  const ProgramRun map = run({"map", (sim / "beams.csv").string(), "--nav", (sim / "nav.csv").string(), "-o",
                              (out_ / "m.bt").string(), "--png", png.string(), "--tank-report", "-q"});
  ASSERT_EQ(map.exit_code, 0) << map.err;
  const cv::Mat figure = readFigure(png);
  ASSERT_FALSE(figure.empty());
  const int plot_right = figure.cols - 220;
  EXPECT_GT(pixelsOf(figure, kOccupiedBgr, cv::Rect(0, 50, plot_right, figure.rows - 110)), 50)
      << "no obstacle drawn";
  // The summary says what the picture shows: the occupied band around z = −3 m.
  const std::size_t at = map.out.find("picture: ");
  ASSERT_NE(at, std::string::npos) << map.out;
  double lo = 0.0, hi = 0.0;
  const std::string said = map.out.substr(at);
  ASSERT_TRUE(std::sscanf(said.c_str(), "picture: occupied band z %lf .. %lf m up", &lo, &hi) == 2 ||
              (std::sscanf(said.c_str(), "picture: slice z = %lf m up", &lo) == 1 && (hi = lo, true)))
      << said;
  EXPECT_LE(lo, -2.9);
  EXPECT_GE(hi, -3.1);
  EXPECT_GT(lo, -4.5);
  EXPECT_LT(hi, -1.5);
  // The tank report slices at the vehicle's depth, not at z = 0.
  const std::size_t tank = map.out.find("tank: slice z = ");
  ASSERT_NE(tank, std::string::npos) << map.out;
  double slice_z_m = 0.0;
  ASSERT_EQ(std::sscanf(map.out.c_str() + tank, "tank: slice z = %lf m up", &slice_z_m), 1) << map.out;
  EXPECT_NEAR(slice_z_m, -3.0, 0.1) << map.out;
}

/// `log` with a static vehicle at `fix` (NED; its time ignored) over the log's span, as a ROS bag
/// whose navigation is nav_msgs/Odometry in the ENU frame `odom`.
void writeBagWithPose(const fs::path& path, const SonarLog& log, NavSample fix) {
  NavTrack nav;
  fix.time_s = log.beams.front().time_s - 1.0;
  nav.push_back(fix);
  fix.time_s = log.beams.back().time_s + 1.0;
  nav.push_back(fix);
  writeRosBag(path.string(), log, nav);
}

TEST_F(cliMapFrame, RosBagMapOverlaysItsOdomFrame) {
  if (!fs::exists(kPoolBag)) GTEST_SKIP() << kPoolBag << " not found";
  SonarLog log = readRosBag(kPoolBag.string());
  log.beams.resize(std::min<std::size_t>(log.beams.size(), 1200));  // six turns are enough
  // Bag A: base_link at the odom origin with odom's axes (ENU/FLU identity: NED yaw 90°, facing
  // east). Its ENU map's voxels are then the echoes' positions in the odom frame and in base_link.
  // Bag B: base_link at odom (x, y, z) = (1.5, −2.0, −1.0) turned 90° counter-clockwise (facing
  // north: NED yaw 0). Its voxels must be the same echoes moved by that odom pose.
  NavSample a, b;
  a.yaw_rad = std::numbers::pi / 2;
  b.position_ned_m = Eigen::Vector3d(-2.0, 1.5, 1.0);  // odom y = north, x = east, z = −down
  writeBagWithPose(root_ / "a.bag", log, a);
  writeBagWithPose(root_ / "b.bag", log, b);
  for (const char* name : {"a", "b"}) {
    const ProgramRun map = run({"map", (root_ / (std::string(name) + ".bag")).string(), "-o",
                                (out_ / (std::string(name) + ".bt")).string(), "--resolution", "0.1", "-q"});
    ASSERT_EQ(map.exit_code, 0) << map.err;
  }
  const std::vector<Eigen::Vector3d> in_a = occupiedCentres(out_ / "a.bt");
  const std::vector<Eigen::Vector3d> in_b = occupiedCentres(out_ / "b.bt");
  ASSERT_GT(in_a.size(), 100u);
  std::set<std::tuple<long, long, long>> b_keys;
  const auto key = [](const Eigen::Vector3d& p) {
    return std::tuple<long, long, long>{std::lround(p.x() * 10 - 0.5), std::lround(p.y() * 10 - 0.5),
                                        std::lround(p.z() * 10 - 0.5)};
  };
  for (const Eigen::Vector3d& p : in_b) b_keys.insert(key(p));
  // odom pose of B: rotation 90° about z, translation (1.5, −2, −1): exact on 0.1 m voxels.
  std::size_t found = 0;
  for (const Eigen::Vector3d& p : in_a) {
    const Eigen::Vector3d moved(1.5 - p.y(), -2.0 + p.x(), -1.0 + p.z());
    found += b_keys.count(key(moved));
  }
  EXPECT_GE(static_cast<double>(found), 0.95 * static_cast<double>(in_a.size()))
      << found << " of " << in_a.size() << " voxels of the map at the odom origin found moved by B's odom pose";
  EXPECT_NEAR(static_cast<double>(in_b.size()), static_cast<double>(in_a.size()), 0.05 * static_cast<double>(in_a.size()));
}

}  // namespace
}  // namespace sonarmap::test
