/// @file scan_matcher.cpp
/// matchScans (scan_matcher.hpp): probabilistic point-to-line / point-to-point ICP with a
/// correlative search before it when asked or when it fails.

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include <Eigen/Eigenvalues>
#include <nanoflann.hpp>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/slam/scan_matcher.hpp"

namespace sonarmap {
namespace {

/// The target's points for a nanoflann k-d tree (its dataset adaptor interface).
struct TargetCloud {
  const std::vector<ScanPoint>* points = nullptr;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t index, std::size_t dim) const { return (*points)[index].xy_m[static_cast<Eigen::Index>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box& /*box*/) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, TargetCloud>, TargetCloud, 2>;

/// A target point's local shape: the normal of the line its neighbours form, when they form one,
/// and how far its neighbours reach along the surface either side of it.
struct LocalShape {
  bool line = false;
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  /// Along the surface: the line's direction, else across the point's view; zero for a point
  /// without neighbours or without a known view (no boundary then).
  Eigen::Vector2d tangent = Eigen::Vector2d::Zero();
  double ahead_m = 0.0;   ///< the farthest neighbour's offset along +tangent, ≥ 0
  double behind_m = 0.0;  ///< ... along −tangent, ≥ 0
};

/// Lines where a target point and its nearest neighbours (within a few of its own σ) lie along one
/// direction: the smaller eigenvalue of their scatter below a tenth of the larger (PCA). And every
/// point's reach along the surface: where its neighbours end, the surface as its sonar saw it ends
/// (the side of a pile turning away, a shadow, the edge of the beams that heard it).
std::vector<LocalShape> localShapes(const std::vector<ScanPoint>& target, const KdTree& tree) {
  constexpr std::size_t kNeighbours = 7;
  std::vector<LocalShape> shapes(target.size());
  std::array<unsigned int, kNeighbours> index{};  // nanoflann's default index type
  std::array<double, kNeighbours> distance_sq{};
  for (std::size_t i = 0; i < target.size(); ++i) {
    const std::size_t found = tree.knnSearch(target[i].xy_m.data(), kNeighbours, index.data(), distance_sq.data());
    const double radius_sq = 64.0 * target[i].covariance_m2.trace();  // within about 11 σ
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    std::size_t used = 0;
    for (std::size_t k = 0; k < found; ++k) {
      if (distance_sq[k] > radius_sq) continue;
      mean += target[index[k]].xy_m;
      ++used;
    }
    if (used < 2) continue;  // alone: no line, no boundary
    mean /= static_cast<double>(used);
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    for (std::size_t k = 0; k < found; ++k) {
      if (distance_sq[k] > radius_sq) continue;
      const Eigen::Vector2d d = target[index[k]].xy_m - mean;
      scatter += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(scatter);
    if (used >= 4 && eigen.eigenvalues()(0) < 0.1 * eigen.eigenvalues()(1)) {
      shapes[i].line = true;
      shapes[i].normal = eigen.eigenvectors().col(0);
    }
    const Eigen::Vector2d& view = target[i].toward_sonar;
    shapes[i].tangent = shapes[i].line ? Eigen::Vector2d(eigen.eigenvectors().col(1))
                        : view.squaredNorm() > 0.5 ? Eigen::Vector2d(-view.y(), view.x()).normalized()
                                                   : Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < found; ++k) {
      if (distance_sq[k] > radius_sq) continue;
      const double along = shapes[i].tangent.dot(target[index[k]].xy_m - target[i].xy_m);
      shapes[i].ahead_m = std::max(shapes[i].ahead_m, along);
      shapes[i].behind_m = std::max(shapes[i].behind_m, -along);
    }
  }
  return shapes;
}

/// One ICP solve from `start`: pairs by nearest neighbour under the Mahalanobis gate, Gauss–Newton
/// on (x, y, yaw) until the step is below 0.1 mm and 0.001°. A source point that lies beyond the
/// last of its target's neighbours along the surface has no counterpart in the target (its sonar
/// did not see that part: a pile's other side, a shadowed stretch of wall) and is not paired: paired
/// with the target's end it pulls the match towards where the two views' ends meet, which is
/// towards less motion (Rusinkiewicz & Levoy 2001, "Efficient variants of the ICP algorithm",
/// rejecting pairs on boundaries; Turk & Levoy 1994; measured in docs/localization.md).
/// The prior (`prior`, its information `prior_information`) joins the pairs in each step (a MAP
/// estimate, as MSISpIC's EKF update): a direction the pairs leave free (along a wall, along a row
/// of equal piles) stays where the prior puts it instead of sliding to the next pile. The reported
/// information is the pairs' alone, so a graph that also holds the prior's edge counts it once.
ScanMatch icp(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source, const KdTree& tree,
              const std::vector<LocalShape>& shapes, const Pose2& start, const Pose2& prior,
              const Eigen::Matrix3d& prior_information, const ScanMatchOptions& options) {
  ScanMatch match;
  match.pose = start;
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  double chi2_sum = 0.0;
  double dof = 0.0;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    const Eigen::Matrix2d rotation = match.pose.rotation();
    Eigen::Matrix2d d_rotation;  // ∂R/∂yaw
    d_rotation << -rotation(1, 0), -rotation(0, 0), rotation(0, 0), -rotation(1, 0);
    hessian.setZero();
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
    chi2_sum = 0.0;
    dof = 0.0;
    match.pairs = 0;
    for (const ScanPoint& point : source) {
      const Eigen::Vector2d moved = match.pose * point.xy_m;
      unsigned int nearest = 0;
      double distance_sq = 0.0;
      if (tree.knnSearch(moved.data(), 1, &nearest, &distance_sq) == 0) continue;
      const ScanPoint& pair = target[nearest];
      const Eigen::Matrix2d covariance =
          pair.covariance_m2 + rotation * point.covariance_m2 * rotation.transpose();
      const Eigen::Vector2d difference = moved - pair.xy_m;
      const Eigen::Matrix2d weight = covariance.inverse();
      if (difference.dot(weight * difference) > options.gate_chi2) continue;
      const double along = shapes[nearest].tangent.dot(difference);
      if (along > shapes[nearest].ahead_m || -along > shapes[nearest].behind_m) continue;  // beyond its end
      Eigen::Matrix<double, 2, 3> jacobian;
      jacobian << Eigen::Matrix2d::Identity(), d_rotation * point.xy_m;
      ++match.pairs;
      // Point to line: only the offset across the wall counts. An isolated point (a pile) is a patch
      // facing the sonar that saw it (ScanPoint::toward_sonar): only the offset along that view counts.
      const bool facing = !shapes[nearest].line && pair.toward_sonar.squaredNorm() > 0.5;
      if (shapes[nearest].line || facing) {
        const Eigen::Vector2d& n = shapes[nearest].line ? shapes[nearest].normal : pair.toward_sonar;
        const double residual = n.dot(difference);
        const double w = 1.0 / n.dot(covariance * n);
        const Eigen::RowVector3d j = n.transpose() * jacobian;
        hessian += j.transpose() * w * j;
        gradient += j.transpose() * w * residual;
        chi2_sum += residual * residual * w;
        dof += 1.0;
      } else {
        hessian += jacobian.transpose() * weight * jacobian;
        gradient += jacobian.transpose() * weight * difference;
        chi2_sum += difference.dot(weight * difference);
        dof += 2.0;
      }
    }
    if (match.pairs < 3) break;
    const Eigen::Vector3d from_prior(match.pose.x_m - prior.x_m, match.pose.y_m - prior.y_m,
                                     wrapAngle_rad(match.pose.yaw_rad - prior.yaw_rad));
    const Eigen::Matrix3d posterior = hessian + prior_information;
    const Eigen::Vector3d step = -posterior.ldlt().solve(gradient + prior_information * from_prior);
    if (!step.allFinite()) break;
    match.pose = {match.pose.x_m + step.x(), match.pose.y_m + step.y(), wrapAngle_rad(match.pose.yaw_rad + step.z())};
    if (step.head<2>().norm() < 1e-4 && std::abs(step.z()) < 1e-5) break;
  }
  match.overlap = source.empty() ? 0.0 : static_cast<double>(match.pairs) / static_cast<double>(source.size());
  match.mean_chi2 = dof > 0.0 ? chi2_sum / dof : 0.0;
  // Residuals larger than the points' covariances say: the match is less certain than the pairs'.
  match.information = hessian / std::max(1.0, match.mean_chi2);
  return match;
}

/// The information no greater, in any direction, than either `pairs` (the ICP's Hessian: the
/// curvature at its solution) or `surface` (the search's score surface over the whole window): in
/// the basis that whitens `pairs` and diagonalises `surface` (the generalised eigenproblem
/// surface v = μ pairs v), each μ above 1 is cut to 1. A direction the surface leaves flat keeps
/// the surface's (about none) however sharp the pairs' local fit; elsewhere the pairs' finer value.
Eigen::Matrix3d withinSurface(const Eigen::Matrix3d& pairs, const Eigen::Matrix3d& surface) {
  const Eigen::Matrix3d regular = pairs + 1e-9 * Eigen::Matrix3d::Identity();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> eigen(surface, regular);
  if (eigen.info() != Eigen::Success) return pairs;
  // Vᵀ regular V = I, so regular = V⁻ᵀ V⁻¹ and surface = V⁻ᵀ diag(μ) V⁻¹.
  const Eigen::Matrix3d back = eigen.eigenvectors().inverse();
  const Eigen::Matrix3d bounded = back.transpose() * eigen.eigenvalues().cwiseMin(1.0).asDiagonal() * back;
  return 0.5 * (bounded + bounded.transpose());
}

/// Accepts or refuses `match`, saying why.
void judge(ScanMatch& match, std::size_t source_points, const ScanMatchOptions& options) {
  if (match.pairs < options.min_pairs || match.overlap < options.min_overlap) {
    match.reason = "too few pairs: " + std::to_string(match.pairs) + " of " + std::to_string(source_points) + " points";
    return;
  }
  if (!match.information.allFinite()) {
    match.reason = "no solution";
    return;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> translation(match.information.topLeftCorner<2, 2>());
  const double weakest = translation.eigenvalues()(0), strongest = translation.eigenvalues()(1);
  match.along_m = translation.eigenvectors().col(0);
  if (!(weakest > 0.0) || strongest > options.max_information_ratio * weakest) {
    match.reason = "ambiguous: constrained along one direction only (a long straight wall)";
    return;
  }
  if (match.searched && match.peak_ratio < options.min_peak_ratio) {
    match.reason = "ambiguous: several poses fit about as well (repetitive or few features)";
    return;
  }
  match.accepted = true;
}

/// What every ICP on one target needs: its k-d tree and its points' local shapes.
struct PreparedTarget {
  explicit PreparedTarget(const std::vector<ScanPoint>& points)
      : cloud{&points}, tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree.buildIndex();
    shapes = localShapes(points, tree);
  }
  TargetCloud cloud;
  KdTree tree;
  std::vector<LocalShape> shapes;
};

/// A refused match at `initial` when either side has fewer points than a match needs pairs.
std::optional<ScanMatch> tooFewPoints(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source,
                                      const Pose2& initial, const ScanMatchOptions& options) {
  if (target.size() >= options.min_pairs && source.size() >= options.min_pairs) return std::nullopt;
  ScanMatch match;
  match.pose = initial;
  match.reason = "too few points: " + std::to_string(source.size()) + " against " + std::to_string(target.size());
  return match;
}

}  // namespace

void ScanMatchOptions::validate() const {
  if (max_iterations < 1) throw ValueError("scan matching: max_iterations must be ≥ 1");
  if (!(std::isfinite(gate_chi2) && gate_chi2 > 0.0)) throw ValueError("scan matching: gate_chi2 must be > 0");
  if (min_pairs < 3) throw ValueError("scan matching: min_pairs must be ≥ 3");
  if (!(min_overlap > 0.0 && min_overlap <= 1.0)) throw ValueError("scan matching: min_overlap must be in (0, 1]");
  if (!(std::isfinite(max_information_ratio) && max_information_ratio >= 1.0)) {
    throw ValueError("scan matching: max_information_ratio must be ≥ 1");
  }
  if (!(std::isfinite(min_peak_ratio) && min_peak_ratio >= 1.0)) throw ValueError("scan matching: min_peak_ratio must be ≥ 1");
  if (max_search_steps < 3) throw ValueError("scan matching: max_search_steps must be ≥ 3");
}

ScanMatch matchScans(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source,
                     const Pose2& initial, const Eigen::Matrix3d& prior_covariance, bool search,
                     const ScanMatchOptions& options, SearchField field, const std::vector<CoverageDisc>& coverage,
                     bool bound_by_surface) {
  options.validate();
  if (!prior_covariance.allFinite()) throw ValueError("scan matching: the prior covariance must be finite");
  if (std::optional<ScanMatch> refused = tooFewPoints(target, source, initial, options)) return *refused;
  const PreparedTarget prepared(target);
  const KdTree& tree = prepared.tree;
  const std::vector<LocalShape>& shapes = prepared.shapes;
  ScanMatch match;

  const Eigen::Matrix3d prior_information =
      (prior_covariance + 1e-12 * Eigen::Matrix3d::Identity()).ldlt().solve(Eigen::Matrix3d::Identity());
  auto searchFirst = [&] {
    const double sigma_m = typicalPointSigma(source);
    // Each wall drawn between its samples, as far as its neighbours reach either side of each.
    std::vector<SurfaceSegment> surfaces;
    for (std::size_t i = 0; i < target.size() && field == SearchField::kSurfaces; ++i) {
      if (!shapes[i].line) continue;
      surfaces.push_back({target[i].xy_m - shapes[i].behind_m * shapes[i].tangent, target[i].xy_m + shapes[i].ahead_m * shapes[i].tangent});
    }
    const CorrelativeResult found =
        correlativeSearch(target, source, initial, prior_covariance, sigma_m, options.max_search_steps, surfaces, coverage);
    ScanMatch refined = icp(target, source, tree, shapes, found.pose, initial, prior_information, options);
    refined.searched = true;
    refined.peak_ratio = found.distinct_score > 0.0 ? found.score / found.distinct_score : 1e9;
    refined.surface_information = found.information;
    if (bound_by_surface) refined.information = withinSurface(refined.information, found.information);
    return refined;
  };

  if (search) {
    match = searchFirst();
  } else {
    match = icp(target, source, tree, shapes, initial, initial, prior_information, options);
    if (match.pairs < options.min_pairs || match.overlap < options.min_overlap) match = searchFirst();
  }
  judge(match, source.size(), options);
  return match;
}

ScanMatch matchScansFrom(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source, const Pose2& initial,
                         const ScanMatchOptions& options) {
  options.validate();
  if (std::optional<ScanMatch> refused = tooFewPoints(target, source, initial, options)) return *refused;
  const PreparedTarget prepared(target);
  ScanMatch match = icp(target, source, prepared.tree, prepared.shapes, initial, initial, Eigen::Matrix3d::Zero(), options);
  judge(match, source.size(), options);
  return match;
}

}  // namespace sonarmap
