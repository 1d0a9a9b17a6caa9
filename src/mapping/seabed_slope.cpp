/// @file seabed_slope.cpp
/// The seabed's local slope from extended returns' onsets (see seabed_slope.hpp).

#include "sonarmap/mapping/seabed_slope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Dense>

namespace sonarmap {
namespace {

/// The F test's critical value at 1 % for two more parameters, large samples: χ²₂(0.99) / 2.
constexpr double kCriticalF = 4.61;
/// Triples drawn by the least-median-of-squares search.
constexpr int kTriples = 300;
/// The largest mean resultant length of the inliers' look directions (seabed_slope.hpp).
constexpr double kMaxMeanLook = 0.5;
/// The steepest ground taken for a seabed met at grazing incidence.
const double kMaxSlopeTan = std::tan(30.0 * std::numbers::pi / 180.0);

/// z − (a + gx x + gy y) for the plane (a, gx, gy).
double residual(const Eigen::Vector3d& plane, const Eigen::Vector3d& p) {
  return p.z() - plane(0) - plane(1) * p.x() - plane(2) * p.y();
}

/// Least-squares z = a + gx x + gy y over `points`; its residuals' sum of squares in `rss`. False
/// when the points do not span a plane.
bool fitPlane(const std::vector<Eigen::Vector3d>& points, Eigen::Vector3d& coefficients, double& rss) {
  Eigen::MatrixX3d design(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::VectorXd heights(static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    design.row(row) << 1.0, points[i].x(), points[i].y();
    heights(row) = points[i].z();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixX3d> qr(design);
  if (qr.rank() < 3) return false;
  coefficients = qr.solve(heights);
  rss = (design * coefficients - heights).squaredNorm();
  return true;
}

/// Least median of squares (Rousseeuw 1984): the plane through three of `points` whose median
/// squared residual is least, over kTriples triples drawn with a fixed seed (the same map every
/// run); its median squared residual in `median_sq`. False when every triple was degenerate.
bool leastMedianPlane(const std::vector<Eigen::Vector3d>& points, Eigen::Vector3d& best, double& median_sq) {
  std::mt19937 random(12345);
  std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
  std::vector<double> squared(points.size());
  median_sq = std::numeric_limits<double>::infinity();
  const auto middle = static_cast<std::ptrdiff_t>(points.size() / 2);
  for (int t = 0; t < kTriples; ++t) {
    const Eigen::Vector3d& a = points[pick(random)];
    const Eigen::Vector3d n = (points[pick(random)] - a).cross(points[pick(random)] - a);
    if (!(std::abs(n.z()) > 1e-6 * n.norm())) continue;  // degenerate, or a vertical plane
    const Eigen::Vector3d plane(a.z() + (n.x() * a.x() + n.y() * a.y()) / n.z(), -n.x() / n.z(), -n.y() / n.z());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double r = residual(plane, points[i]);
      squared[i] = r * r;
    }
    std::nth_element(squared.begin(), squared.begin() + middle, squared.end());
    if (squared[static_cast<std::size_t>(middle)] < median_sq) {
      median_sq = squared[static_cast<std::size_t>(middle)];
      best = plane;
    }
  }
  return std::isfinite(median_sq);
}

}  // namespace

void SeabedSlope::add(const Eigen::Vector3d& onset_m, const Eigen::Vector2d& look) {
  const double length = look.norm();
  if (!onset_m.allFinite() || !(length > 1e-9) || !std::isfinite(length)) return;
  const Onset onset{onset_m, look / length};
  if (onsets_.size() < kCapacity) {
    onsets_.push_back(onset);
    return;
  }
  onsets_[next_] = onset;
  next_ = (next_ + 1) % kCapacity;
}

double SeabedSlope::Fit::heightAbove(const Eigen::Vector3d& point_m) const { return residual(plane, point_m - at_m); }

std::optional<SeabedSlope::Fit> SeabedSlope::robustFit(const Eigen::Vector3d& at_m, double radius_m,
                                                       std::vector<Eigen::Vector3d>& near,
                                                       std::vector<Eigen::Vector2d>& looks) const {
  near.clear();
  looks.clear();
  if (!(radius_m > 0.0) || !at_m.allFinite()) return std::nullopt;
  for (const Onset& onset : onsets_) {
    const Eigen::Vector3d d = onset.point_m - at_m;
    if (d.head<2>().squaredNorm() > radius_m * radius_m) continue;
    near.push_back(d);
    looks.push_back(onset.look);
  }
  // Onsets of returns that are no seabed (a weak echo of a wall or a pile heard by a beam without
  // an obstacle) do not pull the least-median plane while they are fewer than half.
  Fit fit{at_m, Eigen::Vector3d::Zero(), 0.0, false};
  double median_sq = 0.0;
  if (near.size() < kMinOnsets || !leastMedianPlane(near, fit.plane, median_sq)) return std::nullopt;
  fit.deviation_m = 1.4826 * (1.0 + 5.0 / (static_cast<double>(near.size()) - 3.0)) * std::sqrt(median_sq);
  Eigen::Vector2d mean_look = Eigen::Vector2d::Zero();
  std::size_t inliers = 0;
  for (std::size_t i = 0; i < near.size(); ++i) {
    if (std::abs(residual(fit.plane, near[i])) > kInlierDeviations * fit.deviation_m) continue;
    mean_look += looks[i];
    ++inliers;
  }
  fit.seen_around = inliers > 0 && mean_look.norm() <= kMaxMeanLook * static_cast<double>(inliers);
  return fit;
}

std::optional<SeabedSlope::Fit> SeabedSlope::fitAround(const Eigen::Vector3d& at_m, double radius_m) const {
  std::vector<Eigen::Vector3d> near;
  std::vector<Eigen::Vector2d> looks;
  return robustFit(at_m, radius_m, near, looks);
}

Eigen::Vector3d SeabedSlope::normalAt(const Eigen::Vector3d& at_m, double radius_m) const {
  const Eigen::Vector3d level = Eigen::Vector3d::UnitZ();
  std::vector<Eigen::Vector3d> near;  // relative to at_m
  std::vector<Eigen::Vector2d> looks;
  const std::optional<Fit> robust_fit = robustFit(at_m, radius_m, near, looks);
  if (!robust_fit) return level;
  const Eigen::Vector3d& robust = robust_fit->plane;
  const double scale_m = robust_fit->deviation_m;
  // Least squares over its inliers, against the level through the same points: does the slope
  // explain enough (the F test)?
  std::vector<Eigen::Vector3d> kept;
  Eigen::Vector2d mean_look = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < near.size(); ++i) {
    if (std::abs(residual(robust, near[i])) > kInlierDeviations * scale_m) continue;
    kept.push_back(near[i]);
    mean_look += looks[i];
  }
  // Seen from one way only, the onsets' errors do not cancel (see seabed_slope.hpp).
  if (kept.empty() || mean_look.norm() > kMaxMeanLook * static_cast<double>(kept.size())) return level;
  Eigen::Vector3d plane;
  double rss = 0.0;
  if (kept.size() < kMinOnsets || !fitPlane(kept, plane, rss)) return level;
  double mean_z = 0.0;
  for (const Eigen::Vector3d& p : kept) mean_z += p.z();
  mean_z /= static_cast<double>(kept.size());
  double rss_level = 0.0;
  for (const Eigen::Vector3d& p : kept) rss_level += (p.z() - mean_z) * (p.z() - mean_z);
  const double dof = static_cast<double>(kept.size()) - 3.0;
  if ((rss_level - rss) / 2.0 <= kCriticalF * rss / dof) return level;  // no slope to speak of
  if (std::hypot(plane(1), plane(2)) > kMaxSlopeTan) return level;
  return Eigen::Vector3d(-plane(1), -plane(2), 1.0).normalized();
}

}  // namespace sonarmap
