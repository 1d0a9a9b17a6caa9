/// @file rectangle_fit.cpp
/// Rectangle fit by orientation search over wall histograms, then joint line refinement
/// (see rectangle_fit.hpp for the method and its contract).

#include "sonarmap/eval/rectangle_fit.hpp"

#include "sonarmap/core/errors.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

namespace sonarmap {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = std::numbers::pi / 2.0;
constexpr std::size_t kMinPoints = 8;
constexpr int kFineBinsPerWindow = 5;                  // the sliding window moves by histogram_bin_m / 5
constexpr std::size_t kMaxHistogramBins = 10'000'000;  // guards memory against far-away points

// Sides of the rectangle in its own frame (u along the width, v along the height).
enum Side : int { kULow = 0, kUHigh = 1, kVLow = 2, kVHigh = 3 };
constexpr int axisOf(int side) { return side < 2 ? 0 : 1; }

// A rectangle during the fit: orientation and the four side positions, as coordinates along u and
// v relative to the points' centroid. lo[a] / hi[a] are the low / high side on axis a (0 = u, 1 = v).
struct State {
  double theta = 0.0;
  std::array<double, 2> lo{0.0, 0.0};
  std::array<double, 2> hi{0.0, 0.0};
  std::array<bool, 4> seen{true, true, true, true};  // false: side placed from the other walls' extent

  double position(int side) const { return side % 2 == 0 ? lo[axisOf(side)] : hi[axisOf(side)]; }
  void setPosition(int side, double value) { (side % 2 == 0 ? lo : hi)[axisOf(side)] = value; }
};

// Nearest side of the outline [ulo, uhi] × [vlo, vhi] to the local point (pu, pv): the side, the
// distance to it and the position of the nearest outline point along the side, from its low end.
struct NearestSide {
  int side = 0;
  double distance_m = 0.0;
  double along_m = 0.0;
};

double clampedGap(double x, double low, double high) {
  if (x < low) return low - x;
  if (x > high) return x - high;
  return 0.0;
}

NearestSide nearestSide(double pu, double pv, double ulo, double uhi, double vlo, double vhi) {
  NearestSide best;
  best.distance_m = std::numeric_limits<double>::infinity();
  for (int side = 0; side < 4; ++side) {
    const bool u_side = axisOf(side) == 0;
    const double across = u_side ? pu : pv;                     // coordinate across the side
    const double along = u_side ? pv : pu;                      // coordinate along the side
    const double along_lo = u_side ? vlo : ulo;
    const double along_hi = u_side ? vhi : uhi;
    const double position = side == kULow ? ulo : side == kUHigh ? uhi : side == kVLow ? vlo : vhi;
    const double d = std::hypot(across - position, clampedGap(along, along_lo, along_hi));
    if (d < best.distance_m) {
      best.side = side;
      best.distance_m = d;
      best.along_m = std::clamp(along, along_lo, along_hi) - along_lo;
    }
  }
  return best;
}

void validate(const std::vector<Eigen::Vector2d>& points_m, const WallFitOptions& o) {
  if (points_m.size() < kMinPoints) {
    throw ValueError("rectangle fit: need at least " + std::to_string(kMinPoints) + " points, got " +
                     std::to_string(points_m.size()));
  }
  for (std::size_t i = 0; i < points_m.size(); ++i) {
    if (!points_m[i].allFinite()) {
      std::ostringstream msg;
      msg << "rectangle fit: point " << i << " is not finite (" << points_m[i].x() << ", " << points_m[i].y()
          << ")";
      throw ValueError(msg.str());
    }
  }
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto fail = [](const std::string& field, double value, const std::string& expected) {
    std::ostringstream msg;
    msg << "WallFitOptions." << field << " = " << value << ", expected " << expected;
    throw ValueError(msg.str());
  };
  if (!positive(o.wall_tolerance_m)) fail("wall_tolerance_m", o.wall_tolerance_m, "a finite value > 0");
  if (!positive(o.coverage_bin_m)) fail("coverage_bin_m", o.coverage_bin_m, "a finite value > 0");
  if (!positive(o.histogram_bin_m)) fail("histogram_bin_m", o.histogram_bin_m, "a finite value > 0");
  if (!positive(o.angle_step_rad) || o.angle_step_rad > kHalfPi) {
    fail("angle_step_rad", o.angle_step_rad, "a value in (0, pi/2]");
  }
  if (!positive(o.peak_fraction) || o.peak_fraction > 1.0) fail("peak_fraction", o.peak_fraction, "a value in (0, 1]");
  if (!std::isfinite(o.min_side_m) || o.min_side_m < 0.0) fail("min_side_m", o.min_side_m, "a finite value >= 0");
  if (o.refine_iterations < 0) fail("refine_iterations", o.refine_iterations, "a value >= 0");
}

// Sliding-window histogram of 1D coordinates over [-extent, extent]: window k covers the fine bins
// k … k + kFineBinsPerWindow − 1 and its centre is at centre(k).
class WindowHistogram {
 public:
  WindowHistogram(double extent_m, double window_m)
      : fine_m_(window_m / kFineBinsPerWindow), origin_m_(-extent_m - window_m) {
    const double bins = std::ceil(2.0 * (extent_m + window_m) / fine_m_) + 1.0;
    if (!(bins <= static_cast<double>(kMaxHistogramBins))) {
      std::ostringstream msg;
      msg << "rectangle fit: points span " << 2.0 * extent_m << " m, which needs " << bins
          << " histogram bins of " << fine_m_ << " m (limit " << kMaxHistogramBins
          << "); remove far-away points or raise WallFitOptions.histogram_bin_m";
      throw ValueError(msg.str());
    }
    fine_.assign(static_cast<std::size_t>(bins), 0);
    windows_.assign(fine_.size() - kFineBinsPerWindow + 1, 0);
  }

  void fill(const std::vector<double>& coords_m) {
    std::fill(fine_.begin(), fine_.end(), 0);
    const auto last = static_cast<std::int64_t>(fine_.size()) - 1;
    for (double c : coords_m) {
      const auto bin = static_cast<std::int64_t>(std::floor((c - origin_m_) / fine_m_));
      ++fine_[static_cast<std::size_t>(std::clamp<std::int64_t>(bin, 0, last))];
    }
    std::int64_t sum = 0;
    for (int j = 0; j < kFineBinsPerWindow; ++j) sum += fine_[static_cast<std::size_t>(j)];
    windows_[0] = sum;
    for (std::size_t k = 1; k < windows_.size(); ++k) {
      sum += fine_[k + kFineBinsPerWindow - 1] - fine_[k - 1];
      windows_[k] = sum;
    }
  }

  /// Sharpness of the last fill: sum of squared window counts (shift-invariant up to a fine bin).
  double sharpness() const {
    double s = 0.0;
    for (std::int64_t w : windows_) s += static_cast<double>(w) * static_cast<double>(w);
    return s;
  }

  const std::vector<std::int64_t>& windows() const { return windows_; }
  double centre(std::size_t k) const { return origin_m_ + (static_cast<double>(k) + 0.5 * kFineBinsPerWindow) * fine_m_; }

 private:
  double fine_m_;
  double origin_m_;
  std::vector<std::int64_t> fine_;
  std::vector<std::int64_t> windows_;
};

void project(const std::vector<Eigen::Vector2d>& rel, double theta, std::vector<double>& u, std::vector<double>& v) {
  const double c = std::cos(theta), s = std::sin(theta);
  for (std::size_t i = 0; i < rel.size(); ++i) {
    u[i] = c * rel[i].x() + s * rel[i].y();
    v[i] = -s * rel[i].x() + c * rel[i].y();
  }
}

// Step 2 on one axis: the outermost windows holding ≥ fraction of the highest, each moved to the
// local maximum within two windows inwards. When they are closer than min_side_m only one wall is
// seen: `two` is false and lo = hi = the position of the axis's highest window between them.
struct AxisWalls {
  double lo = 0.0, hi = 0.0;
  bool two = true;
};

AxisWalls findWalls(const WindowHistogram& h, const WallFitOptions& o) {
  const auto& w = h.windows();
  const std::int64_t top = *std::max_element(w.begin(), w.end());
  const double threshold = o.peak_fraction * static_cast<double>(top);
  std::size_t first = 0, last = w.size() - 1;
  while (static_cast<double>(w[first]) < threshold) ++first;
  while (static_cast<double>(w[last]) < threshold) --last;
  const std::size_t reach = 2 * kFineBinsPerWindow;
  std::size_t klo = first;
  for (std::size_t k = first; k <= std::min(first + reach, w.size() - 1); ++k) {
    if (w[k] > w[klo]) klo = k;
  }
  std::size_t khi = last;
  for (std::size_t k = last + 1; k-- > (last >= reach ? last - reach : 0);) {
    if (w[k] > w[khi]) khi = k;
  }
  AxisWalls walls{h.centre(klo), h.centre(khi), true};
  if (walls.hi - walls.lo < o.min_side_m) {
    std::size_t kmax = first;
    for (std::size_t k = first; k <= last; ++k) {
      if (w[k] > w[kmax]) kmax = k;
    }
    walls = AxisWalls{h.centre(kmax), h.centre(kmax), false};
  }
  return walls;
}

// Extent along one axis of the points lying within `tol` of any of the given lines of the other
// axis (`across` coordinates). Falls back to the extent of all points when none is that close.
std::pair<double, double> extentNearLines(const std::vector<double>& along, const std::vector<double>& across,
                                          const std::vector<double>& lines, double tol) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < along.size(); ++i) {
    const bool near = std::any_of(lines.begin(), lines.end(), [&](double l) { return std::abs(across[i] - l) <= tol; });
    if (near) {
      lo = std::min(lo, along[i]);
      hi = std::max(hi, along[i]);
    }
  }
  if (lo > hi) {
    const auto [mn, mx] = std::minmax_element(along.begin(), along.end());
    return {*mn, *mx};
  }
  return {lo, hi};
}

// Places every unseen side at the far end of the points lying within tolerance of the seen sides
// of the other axis: the perpendicular walls end where the missing wall would be.
void placeUnseenSides(State& st, const std::vector<double>& u, const std::vector<double>& v, double tol) {
  for (int axis = 0; axis < 2; ++axis) {
    if (st.seen[2 * axis] && st.seen[2 * axis + 1]) continue;
    const int other = 1 - axis;
    std::vector<double> lines;
    if (st.seen[2 * other]) lines.push_back(st.lo[other]);
    if (st.seen[2 * other + 1]) lines.push_back(st.hi[other]);
    const auto [lo, hi] = extentNearLines(axis == 0 ? u : v, axis == 0 ? v : u, lines, tol);
    if (!st.seen[2 * axis] && !st.seen[2 * axis + 1]) {
      st.lo[axis] = lo;
      st.hi[axis] = hi;
    } else if (!st.seen[2 * axis]) {
      st.lo[axis] = std::min(lo, st.hi[axis]);
    } else {
      st.hi[axis] = std::max(hi, st.lo[axis]);
    }
  }
}

// For each axis where findWalls() saw one wall only, decides whether it is the low or the high side:
// the missing side is where the perpendicular walls extend farther from it. Then places it.
void initialiseSides(State& st, const std::array<AxisWalls, 2>& walls, const std::vector<double>& u,
                     const std::vector<double>& v, double tol) {
  for (int axis = 0; axis < 2; ++axis) {
    st.lo[axis] = walls[axis].lo;
    st.hi[axis] = walls[axis].hi;
    st.seen[2 * axis] = st.seen[2 * axis + 1] = true;
  }
  for (int axis = 0; axis < 2; ++axis) {
    if (walls[axis].two) continue;
    const AxisWalls& o = walls[1 - axis];
    const std::vector<double> lines = o.two ? std::vector<double>{o.lo, o.hi} : std::vector<double>{o.lo};
    const auto [lo, hi] = extentNearLines(axis == 0 ? u : v, axis == 0 ? v : u, lines, tol);
    const double wall = walls[axis].lo;
    const bool missing_high = hi - wall >= wall - lo;
    st.seen[2 * axis + (missing_high ? 1 : 0)] = false;
  }
  placeUnseenSides(st, u, v, tol);
}

// Step 3: one refinement round (inliers → demotion of empty sides → shared direction by total least
// squares → side positions).
void refine(State& st, const std::vector<Eigen::Vector2d>& rel, std::vector<double>& u, std::vector<double>& v,
            double tol, double peak_fraction) {
  project(rel, st.theta, u, v);
  std::array<std::vector<std::size_t>, 4> inliers;
  for (std::size_t i = 0; i < rel.size(); ++i) {
    const NearestSide n = nearestSide(u[i], v[i], st.lo[0], st.hi[0], st.lo[1], st.hi[1]);
    if (n.distance_m <= tol) inliers[static_cast<std::size_t>(n.side)].push_back(i);
  }
  // A seen side holding fewer than peak_fraction of the best side's points was no wall (e.g. the
  // ends of a flat histogram when only two opposite walls exist): from now on it is placed at the
  // end of the perpendicular walls.
  std::size_t most = 0;
  for (int side = 0; side < 4; ++side) {
    if (st.seen[static_cast<std::size_t>(side)]) most = std::max(most, inliers[static_cast<std::size_t>(side)].size());
  }
  for (int side = 0; side < 4; ++side) {
    const double held = static_cast<double>(inliers[static_cast<std::size_t>(side)].size());
    if (held < peak_fraction * static_cast<double>(most)) st.seen[static_cast<std::size_t>(side)] = false;
  }
  // Shared direction: sides along u (kVLow, kVHigh) as they are, sides along v turned by −90° so
  // that they run along u too; the principal axis of the pooled scatter is the new u.
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (int side = 0; side < 4; ++side) {
    const auto& idx = inliers[static_cast<std::size_t>(side)];
    if (idx.size() < 2) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (std::size_t i : idx) mean += rel[i];
    mean /= static_cast<double>(idx.size());
    for (std::size_t i : idx) {
      Eigen::Vector2d d = rel[i] - mean;
      if (axisOf(side) == 0) d = Eigen::Vector2d(d.y(), -d.x());
      scatter += d * d.transpose();
    }
  }
  const double sxy = scatter(0, 1), diff = scatter(0, 0) - scatter(1, 1);
  if (std::abs(sxy) > 0.0 || std::abs(diff) > 0.0) {
    double phi = 0.5 * std::atan2(2.0 * sxy, diff);  // direction, defined modulo π
    phi += kPi * std::round((st.theta - phi) / kPi);
    st.theta = phi;
  }
  project(rel, st.theta, u, v);
  for (int side = 0; side < 4; ++side) {
    const auto& idx = inliers[static_cast<std::size_t>(side)];
    if (!st.seen[static_cast<std::size_t>(side)] || idx.empty()) continue;
    const std::vector<double>& across = axisOf(side) == 0 ? u : v;
    double sum = 0.0;
    for (std::size_t i : idx) sum += across[i];
    st.setPosition(side, sum / static_cast<double>(idx.size()));
  }
  placeUnseenSides(st, u, v, tol);
}

}  // namespace

std::vector<Eigen::Vector2d> RectangleFit::corners() const {
  const Eigen::Vector2d u(std::cos(angle_rad), std::sin(angle_rad));
  const Eigen::Vector2d v(-u.y(), u.x());
  const Eigen::Vector2d a = 0.5 * width_m * u, b = 0.5 * height_m * v;
  return {center_m - a - b, center_m + a - b, center_m + a + b, center_m - a + b};
}

RectangleFit fitRectangle(const std::vector<Eigen::Vector2d>& points_m, const WallFitOptions& options) {
  validate(points_m, options);
  const std::size_t n = points_m.size();

  // Work relative to the centroid so the histograms stay small wherever the points are.
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : points_m) centroid += p;
  centroid /= static_cast<double>(n);
  std::vector<Eigen::Vector2d> rel(n);
  double extent_m = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    rel[i] = points_m[i] - centroid;
    extent_m = std::max(extent_m, rel[i].norm());
  }

  // 1. Orientation search.
  WindowHistogram hu(extent_m, options.histogram_bin_m), hv(extent_m, options.histogram_bin_m);
  std::vector<double> u(n), v(n);
  const auto angles = static_cast<int>(std::ceil(kHalfPi / options.angle_step_rad - 1e-9));
  double best_theta = 0.0, best_score = -1.0;
  for (int a = 0; a < angles; ++a) {
    const double theta = a * options.angle_step_rad;
    project(rel, theta, u, v);
    hu.fill(u);
    hv.fill(v);
    const double score = hu.sharpness() + hv.sharpness();
    if (score > best_score) {
      best_score = score;
      best_theta = theta;
    }
  }

  // 2. Walls on each axis at the best orientation.
  State st;
  st.theta = best_theta;
  project(rel, st.theta, u, v);
  hu.fill(u);
  hv.fill(v);
  initialiseSides(st, {findWalls(hu, options), findWalls(hv, options)}, u, v, options.wall_tolerance_m);

  // 3. Refinement.
  for (int it = 0; it < options.refine_iterations; ++it) refine(st, rel, u, v, options.wall_tolerance_m, options.peak_fraction);

  // Canonical form: angle in [0, π/2), width along it.
  double theta = st.theta;
  double width = std::abs(st.hi[0] - st.lo[0]);
  double height = std::abs(st.hi[1] - st.lo[1]);
  const Eigen::Vector2d u_axis(std::cos(theta), std::sin(theta));
  const Eigen::Vector2d v_axis(-u_axis.y(), u_axis.x());
  RectangleFit fit;
  fit.center_m = centroid + 0.5 * (st.lo[0] + st.hi[0]) * u_axis + 0.5 * (st.lo[1] + st.hi[1]) * v_axis;
  const double quarter_turns = std::floor(theta / kHalfPi);
  theta -= quarter_turns * kHalfPi;
  if (theta >= kHalfPi) theta -= kHalfPi, std::swap(width, height);  // rounding at the boundary
  if (static_cast<std::int64_t>(quarter_turns) % 2 != 0) std::swap(width, height);
  fit.angle_rad = theta;
  fit.width_m = width;
  fit.height_m = height;
  return fit;
}

WallFitReport evaluateWalls(const std::vector<Eigen::Vector2d>& points_m, const WallFitOptions& options) {
  WallFitReport report;
  report.rect = fitRectangle(points_m, options);  // validates
  report.points = points_m.size();

  const RectangleFit& r = report.rect;
  const double c = std::cos(r.angle_rad), s = std::sin(r.angle_rad);
  const double hw = 0.5 * r.width_m, hh = 0.5 * r.height_m;
  // Bins per side: sides along v (kULow, kUHigh) have the height's length, sides along u the width's.
  std::array<std::size_t, 4> bins{};
  std::array<double, 4> length{};
  for (int side = 0; side < 4; ++side) {
    length[static_cast<std::size_t>(side)] = axisOf(side) == 0 ? r.height_m : r.width_m;
    bins[static_cast<std::size_t>(side)] = static_cast<std::size_t>(
        std::max(1.0, std::round(length[static_cast<std::size_t>(side)] / options.coverage_bin_m)));
  }
  std::array<std::vector<bool>, 4> covered;
  for (int side = 0; side < 4; ++side) covered[static_cast<std::size_t>(side)].assign(bins[static_cast<std::size_t>(side)], false);

  std::size_t on_wall = 0;
  double sum_sq = 0.0;
  for (const auto& p : points_m) {
    const Eigen::Vector2d d = p - r.center_m;
    const double pu = c * d.x() + s * d.y(), pv = -s * d.x() + c * d.y();
    const NearestSide ns = nearestSide(pu, pv, -hw, hw, -hh, hh);
    if (ns.distance_m > options.wall_tolerance_m) continue;
    ++on_wall;
    sum_sq += ns.distance_m * ns.distance_m;
    const auto side = static_cast<std::size_t>(ns.side);
    const double len = length[side];
    std::size_t bin = len > 0.0 ? static_cast<std::size_t>(ns.along_m / len * static_cast<double>(bins[side])) : 0;
    covered[side][std::min(bin, bins[side] - 1)] = true;
  }
  std::size_t total_bins = 0, covered_bins = 0;
  for (std::size_t side = 0; side < 4; ++side) {
    total_bins += bins[side];
    covered_bins += static_cast<std::size_t>(std::count(covered[side].begin(), covered[side].end(), true));
  }
  report.share_on_walls = static_cast<double>(on_wall) / static_cast<double>(points_m.size());
  report.wall_coverage = static_cast<double>(covered_bins) / static_cast<double>(total_bins);
  report.rms_wall_distance_m = on_wall > 0 ? std::sqrt(sum_sq / static_cast<double>(on_wall)) : 0.0;
  return report;
}

}  // namespace sonarmap
