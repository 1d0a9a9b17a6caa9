// Tests of fitRectangle() / evaluateWalls() on synthetic tank maps: clean outlines, outlines with a
// floater and multipath, a ring of false obstacles, partial outlines and bad input.

#include "sonarmap/eval/rectangle_fit.hpp"

#include "sonarmap/core/errors.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace sonarmap {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kTankWidth = 4.4;   // metres, along the rectangle's angle
constexpr double kTankHeight = 4.6;  // metres

using Points = std::vector<Eigen::Vector2d>;

Eigen::Vector2d toWorld(const RectangleFit& r, double pu, double pv) {
  const Eigen::Vector2d u(std::cos(r.angle_rad), std::sin(r.angle_rad));
  const Eigen::Vector2d v(-u.y(), u.x());
  return r.center_m + pu * u + pv * v;
}

// A point on the outline at arc length t ∈ [0, perimeter) and the outward normal there, both in the
// rectangle's frame. Sides in order: bottom (v = −h/2), right, top, left. `sides` masks them.
struct OutlinePoint {
  double pu, pv, nu, nv;
};
OutlinePoint outlineAt(const RectangleFit& r, double t) {
  const double w = r.width_m, h = r.height_m;
  if (t < w) return {t - w / 2, -h / 2, 0, -1};
  t -= w;
  if (t < h) return {w / 2, t - h / 2, 1, 0};
  t -= h;
  if (t < w) return {w / 2 - t, h / 2, 0, 1};
  t -= w;
  return {-w / 2, h / 2 - t, -1, 0};
}

int sideAt(const RectangleFit& r, double t) {
  if (t < r.width_m) return 0;
  if (t < r.width_m + r.height_m) return 1;
  if (t < 2 * r.width_m + r.height_m) return 2;
  return 3;
}

// n points spread uniformly along the chosen sides of the outline, with isotropic Gaussian noise.
Points outline(const RectangleFit& r, int n, double sigma_m, std::mt19937& rng, std::array<bool, 4> sides = {true, true, true, true}) {
  const double perimeter = 2 * (r.width_m + r.height_m);
  std::uniform_real_distribution<double> arc(0.0, perimeter);
  std::normal_distribution<double> noise(0.0, sigma_m);
  Points pts;
  while (static_cast<int>(pts.size()) < n) {
    const double t = arc(rng);
    if (!sides[static_cast<std::size_t>(sideAt(r, t))]) continue;
    const OutlinePoint o = outlineAt(r, t);
    pts.push_back(toWorld(r, o.pu, o.pv) + Eigen::Vector2d(noise(rng), noise(rng)));
  }
  return pts;
}

// A floater: a Gaussian blob of n points, σ 0.15 m, inside the tank at (0.8, −0.5) in its frame.
void addFloater(Points& pts, const RectangleFit& r, int n, std::mt19937& rng) {
  std::normal_distribution<double> blob(0.0, 0.15);
  for (int i = 0; i < n; ++i) pts.push_back(toWorld(r, 0.8 + blob(rng), -0.5 + blob(rng)));
}

// Multipath: n points 0.3–0.6 m behind randomly chosen walls.
void addMultipath(Points& pts, const RectangleFit& r, int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> arc(0.0, 2 * (r.width_m + r.height_m));
  std::uniform_real_distribution<double> behind(0.3, 0.6);
  for (int i = 0; i < n; ++i) {
    const OutlinePoint o = outlineAt(r, arc(rng));
    const double d = behind(rng);
    pts.push_back(toWorld(r, o.pu + d * o.nu, o.pv + d * o.nv));
  }
}

// A ring of false obstacles of radius radius_m around centre_m.
Points ring(const Eigen::Vector2d& centre_m, double radius_m, int n, double sigma_m, std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(0.0, 2 * kPi);
  std::normal_distribution<double> noise(0.0, sigma_m);
  Points pts;
  for (int i = 0; i < n; ++i) {
    const double a = angle(rng);
    pts.push_back(centre_m + radius_m * Eigen::Vector2d(std::cos(a), std::sin(a)) + Eigen::Vector2d(noise(rng), noise(rng)));
  }
  return pts;
}

RectangleFit tank(double angle_deg, Eigen::Vector2d centre_m) {
  return RectangleFit{centre_m, angle_deg * kDeg, kTankWidth, kTankHeight};
}

// Compares a fit with the truth up to the rectangle's symmetry (quarter turns swap the sides).
void expectSameRectangle(const RectangleFit& fit, const RectangleFit& truth, double size_tol_m, double angle_tol_deg,
                         double centre_tol_m) {
  double delta = fit.angle_rad - truth.angle_rad;
  const double quarter = std::round(delta / (kPi / 2));
  delta -= quarter * (kPi / 2);
  const bool swapped = static_cast<long>(std::abs(quarter)) % 2 == 1;
  const double width = swapped ? fit.height_m : fit.width_m;
  const double height = swapped ? fit.width_m : fit.height_m;
  EXPECT_LE(std::abs(delta), angle_tol_deg * kDeg) << "angle " << fit.angle_rad / kDeg << "°";
  EXPECT_NEAR(width, truth.width_m, size_tol_m);
  EXPECT_NEAR(height, truth.height_m, size_tol_m);
  EXPECT_LE((fit.center_m - truth.center_m).norm(), centre_tol_m) << fit.center_m.transpose();
  EXPECT_GE(fit.angle_rad, 0.0);
  EXPECT_LT(fit.angle_rad, kPi / 2);
}

struct Pose {
  double angle_deg;
  double cx, cy;
};

class RectangleFitPose : public ::testing::TestWithParam<Pose> {};

TEST_P(RectangleFitPose, CleanOutlineIsRecovered) {
  const Pose pose = GetParam();
  const RectangleFit truth = tank(pose.angle_deg, {pose.cx, pose.cy});
  std::mt19937 rng(42);
  const Points pts = outline(truth, 1500, 0.02, rng);

  const WallFitReport report = evaluateWalls(pts, {});
  expectSameRectangle(report.rect, truth, 0.05, 1.0, 0.05);
  EXPECT_EQ(report.points, pts.size());
  EXPECT_GT(report.share_on_walls, 0.99);
  EXPECT_GT(report.wall_coverage, 0.97);
  EXPECT_NEAR(report.rms_wall_distance_m, 0.02, 0.01);  // σ of the noise across the wall
}

TEST_P(RectangleFitPose, FloaterAndMultipathAreIgnored) {
  const Pose pose = GetParam();
  const RectangleFit truth = tank(pose.angle_deg, {pose.cx, pose.cy});
  std::mt19937 rng(7);
  const int walls = 1300, floater = 500, multipath = 200;  // 65 %, 25 %, 10 %
  Points pts = outline(truth, walls, 0.02, rng);
  addFloater(pts, truth, floater, rng);
  addMultipath(pts, truth, multipath, rng);

  const WallFitReport report = evaluateWalls(pts, {});
  expectSameRectangle(report.rect, truth, 0.08, 1.0, 0.08);
  EXPECT_NEAR(report.share_on_walls, static_cast<double>(walls) / static_cast<double>(pts.size()), 0.02);
  EXPECT_GT(report.wall_coverage, 0.95);
  EXPECT_LT(report.rms_wall_distance_m, 0.035);
}

INSTANTIATE_TEST_SUITE_P(Poses, RectangleFitPose,
                         ::testing::Values(Pose{0.0, 0.3, -0.4}, Pose{17.0, 0.3, -0.4}, Pose{44.0, -0.6, 0.2},
                                           Pose{62.7, 1.2, 0.8}, Pose{-3.3, 0.0, 0.0}, Pose{100.0, 0.5, 0.5}));

TEST(RectangleFit, ReturnsTheCanonicalForm) {
  // The 4.4 m side points at 100°, so the 4.6 m side points at 10° (mod 180°): canonically the
  // angle is 10° and the width is 4.6 m.
  const RectangleFit truth{{0.5, 0.5}, 100.0 * kDeg, kTankWidth, kTankHeight};
  std::mt19937 rng(3);
  const RectangleFit fit = fitRectangle(outline(truth, 1000, 0.01, rng));
  EXPECT_NEAR(fit.angle_rad / kDeg, 10.0, 0.5);
  EXPECT_NEAR(fit.width_m, kTankHeight, 0.03);
  EXPECT_NEAR(fit.height_m, kTankWidth, 0.03);
}

TEST(RectangleFit, CornersAreCounterClockwise) {
  const RectangleFit r{{1.0, 2.0}, kPi / 2 - 1e-12, 2.0, 4.0};
  const auto c = r.corners();
  ASSERT_EQ(c.size(), 4u);
  EXPECT_NEAR(c[0].x(), 3.0, 1e-9);
  EXPECT_NEAR(c[0].y(), 1.0, 1e-9);
  EXPECT_NEAR(c[2].x(), -1.0, 1e-9);
  EXPECT_NEAR(c[2].y(), 3.0, 1e-9);
}

TEST(RectangleFit, RingIsDistinguishableFromTank) {
  // The failure mode: a ring of false obstacles at 1.56 m around the sonar instead of the walls.
  std::mt19937 rng(11);
  const Points ring_pts = ring({0.0, 0.0}, 1.56, 1500, 0.02, rng);
  const WallFitReport ring_report = evaluateWalls(ring_pts, {});

  const RectangleFit truth = tank(17.0, {0.3, -0.4});
  const WallFitReport tank_report = evaluateWalls(outline(truth, 1500, 0.02, rng), {});

  // A ring gives a square a little smaller than its diameter (about 3.0 m, far from 4.4 × 4.6 m),
  // which it touches only around the sides' middles: poor coverage, many points off the outline and
  // a wall distance several times the noise.
  EXPECT_LT(std::max(ring_report.rect.width_m, ring_report.rect.height_m), 3.4);
  EXPECT_LT(ring_report.wall_coverage, 0.7);
  EXPECT_LT(ring_report.share_on_walls, 0.8);
  EXPECT_GT(ring_report.rms_wall_distance_m, 0.05);
  EXPECT_GT(std::min(tank_report.rect.width_m, tank_report.rect.height_m), 4.3);
  EXPECT_GT(tank_report.wall_coverage, 0.95);
  EXPECT_GT(tank_report.share_on_walls, 0.99);
  EXPECT_LT(tank_report.rms_wall_distance_m, 0.03);
  EXPECT_GT(tank_report.wall_coverage - ring_report.wall_coverage, 0.3);
}

TEST(RectangleFit, RingInsideTankDoesNotShrinkTheFit) {
  const RectangleFit truth = tank(17.0, {0.3, -0.4});
  std::mt19937 rng(12);
  Points pts = outline(truth, 1500, 0.02, rng);
  const Points r = ring({0.0, 0.0}, 1.56, 500, 0.02, rng);
  pts.insert(pts.end(), r.begin(), r.end());

  const WallFitReport report = evaluateWalls(pts, {});
  expectSameRectangle(report.rect, truth, 0.08, 1.0, 0.08);
  EXPECT_NEAR(report.share_on_walls, 0.75, 0.03);  // the ring's quarter of the points is off the walls
}

TEST(RectangleFit, TwoAdjacentWallsCoverHalfTheOutline) {
  const RectangleFit truth = tank(17.0, {0.3, -0.4});
  std::mt19937 rng(5);
  const Points pts = outline(truth, 1000, 0.02, rng, {true, false, false, true});  // bottom and left

  const WallFitReport report = evaluateWalls(pts, {});
  expectSameRectangle(report.rect, truth, 0.10, 1.0, 0.10);
  EXPECT_NEAR(report.wall_coverage, 0.5, 0.06);
  EXPECT_GT(report.share_on_walls, 0.99);
}

TEST(RectangleFit, TwoOppositeWallsCoverHalfTheOutline) {
  const RectangleFit truth = tank(44.0, {-0.2, 0.1});
  std::mt19937 rng(6);
  const Points pts = outline(truth, 1000, 0.02, rng, {true, false, true, false});  // bottom and top

  const WallFitReport report = evaluateWalls(pts, {});
  expectSameRectangle(report.rect, truth, 0.10, 1.0, 0.10);
  EXPECT_NEAR(report.wall_coverage, 0.5, 0.06);
}

TEST(RectangleFit, IsDeterministic) {
  const RectangleFit truth = tank(31.0, {0.1, 0.2});
  std::mt19937 rng(9);
  Points pts = outline(truth, 800, 0.02, rng);
  addFloater(pts, truth, 300, rng);
  const RectangleFit a = fitRectangle(pts), b = fitRectangle(pts);
  EXPECT_EQ(a.center_m, b.center_m);
  EXPECT_EQ(a.angle_rad, b.angle_rad);
  EXPECT_EQ(a.width_m, b.width_m);
  EXPECT_EQ(a.height_m, b.height_m);
}

TEST(RectangleFit, RejectsTooFewPoints) {
  const Points pts(7, Eigen::Vector2d(1.0, 2.0));
  EXPECT_THROW(fitRectangle(pts), ValueError);
  EXPECT_THROW(evaluateWalls(pts), ValueError);
  EXPECT_THROW(fitRectangle({}), ValueError);
}

TEST(RectangleFit, RejectsNonFinitePoints) {
  const RectangleFit truth = tank(0.0, {0.0, 0.0});
  std::mt19937 rng(1);
  Points pts = outline(truth, 100, 0.02, rng);
  pts[17].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(fitRectangle(pts), ValueError);
  pts[17].y() = 0.0;
  pts[3].x() = std::numeric_limits<double>::infinity();
  try {
    evaluateWalls(pts);
    FAIL() << "expected ValueError";
  } catch (const ValueError& e) {
    EXPECT_NE(std::string(e.what()).find("point 3"), std::string::npos) << e.what();
  }
}

TEST(RectangleFit, RejectsBadOptions) {
  const RectangleFit truth = tank(0.0, {0.0, 0.0});
  std::mt19937 rng(2);
  const Points pts = outline(truth, 100, 0.02, rng);
  auto with = [](auto change) {
    WallFitOptions o;
    change(o);
    return o;
  };
  EXPECT_THROW(fitRectangle(pts, with([](WallFitOptions& o) { o.wall_tolerance_m = 0.0; })), ValueError);
  EXPECT_THROW(fitRectangle(pts, with([](WallFitOptions& o) { o.coverage_bin_m = -1.0; })), ValueError);
  EXPECT_THROW(fitRectangle(pts, with([](WallFitOptions& o) { o.histogram_bin_m = std::nan(""); })), ValueError);
  EXPECT_THROW(fitRectangle(pts, with([](WallFitOptions& o) { o.angle_step_rad = 0.0; })), ValueError);
  EXPECT_THROW(fitRectangle(pts, with([](WallFitOptions& o) { o.angle_step_rad = 2.0; })), ValueError);
  EXPECT_THROW(fitRectangle(pts, with([](WallFitOptions& o) { o.peak_fraction = 1.5; })), ValueError);
  EXPECT_THROW(fitRectangle(pts, with([](WallFitOptions& o) { o.min_side_m = -0.1; })), ValueError);
  EXPECT_THROW(fitRectangle(pts, with([](WallFitOptions& o) { o.refine_iterations = -1; })), ValueError);
}

TEST(RectangleFit, RejectsPointsTooFarApart) {
  Points pts(10, Eigen::Vector2d(0.0, 0.0));
  pts[0] = Eigen::Vector2d(1e6, 0.0);  // 2 km of 1 cm bins is beyond the histogram limit
  EXPECT_THROW(fitRectangle(pts), ValueError);
}

}  // namespace
}  // namespace sonarmap
