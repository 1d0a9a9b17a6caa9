/// @file correlative_search.cpp
/// correlativeSearch (scan_matcher.hpp): Olson's correlative scan matching (ICRA 2009) over a
/// likelihood field made with OpenCV's distance transform.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

#include <opencv2/imgproc.hpp>

#include "sonarmap/slam/scan_matcher.hpp"

namespace sonarmap {
namespace {

/// The likelihood a point that fits no target point keeps in the posterior's mixture (a target
/// seen from elsewhere, clutter): a tenth of one that fits exactly (Thrun et al. 2005,
/// "Probabilistic Robotics" §6.4, the likelihood field's z_rand).
constexpr double kOutlierLikelihood = 0.1;

/// The target's likelihood field: exp(−d²/2σ²) of the distance to the nearest target point, on a
/// grid of `cell_m` whose cell (0, 0) has its corner at `origin`. A cell no target scan heard
/// (outside every coverage disc) holds −1: a point there says nothing about the pose.
struct LikelihoodField {
  cv::Mat likelihood;  ///< CV_32F, rows along y, columns along x
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell_m = 1.0;

  float at(const Eigen::Vector2d& point) const {
    const double cx = std::floor((point.x() - origin.x()) / cell_m);
    const double cy = std::floor((point.y() - origin.y()) / cell_m);
    if (cx < 0 || cy < 0 || cx >= likelihood.cols || cy >= likelihood.rows) return outside;
    return likelihood.at<float>(static_cast<int>(cy), static_cast<int>(cx));
  }
  float outside = 0.0F;  ///< beyond the grid: 0 (heard, nothing there), or −1 with coverage
  /// log((kOutlierLikelihood + L) / kOutlierLikelihood) of a likelihood L in [0, 1], tabulated
  /// at steps of 1/1023.
  static double logAt(float likelihood) {
    static const std::vector<double> table = [] {
      std::vector<double> values(1024);
      for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::log1p(static_cast<double>(i) / 1023.0 / kOutlierLikelihood);
      return values;
    }();
    return table[static_cast<std::size_t>(likelihood * 1023.0F + 0.5F)];
  }
};

LikelihoodField likelihoodField(const std::vector<ScanPoint>& target, double cell_m, double sigma_m, double margin_m,
                                const std::vector<SurfaceSegment>& surfaces, const std::vector<CoverageDisc>& coverage = {}) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (const ScanPoint& point : target) {
    low = low.cwiseMin(point.xy_m);
    high = high.cwiseMax(point.xy_m);
  }
  for (const CoverageDisc& disc : coverage) {  // a point a target scan heard, with nothing there, scores 0
    low = low.cwiseMin(disc.centre_m - Eigen::Vector2d::Constant(disc.radius_m));
    high = high.cwiseMax(disc.centre_m + Eigen::Vector2d::Constant(disc.radius_m));
  }
  LikelihoodField field;
  // Never more than 4096 cells across: the cell grows for a target that spans kilometres.
  const double span_m = std::max(high.x() - low.x(), high.y() - low.y()) + 2.0 * margin_m;
  field.cell_m = std::max(cell_m, span_m / 4096.0);
  field.origin = low - Eigen::Vector2d::Constant(margin_m);
  const int cols = static_cast<int>(std::ceil((high.x() - low.x() + 2.0 * margin_m) / field.cell_m)) + 1;
  const int rows = static_cast<int>(std::ceil((high.y() - low.y() + 2.0 * margin_m) / field.cell_m)) + 1;
  cv::Mat free(rows, cols, CV_8U, cv::Scalar(255));
  for (const ScanPoint& point : target) {
    const int cx = static_cast<int>((point.xy_m.x() - field.origin.x()) / field.cell_m);
    const int cy = static_cast<int>((point.xy_m.y() - field.origin.y()) / field.cell_m);
    free.at<std::uint8_t>(cy, cx) = 0;
  }
  const auto cellOf = [&field](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>((p.x() - field.origin.x()) / field.cell_m), static_cast<int>((p.y() - field.origin.y()) / field.cell_m));
  };
  for (const SurfaceSegment& surface : surfaces) cv::line(free, cellOf(surface.a), cellOf(surface.b), cv::Scalar(0));
  cv::Mat distance_cells;
  cv::distanceTransform(free, distance_cells, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  const double scale = field.cell_m * field.cell_m / (2.0 * sigma_m * sigma_m);
  cv::Mat exponent = distance_cells.mul(distance_cells) * (-scale);
  cv::exp(exponent, field.likelihood);
  if (!coverage.empty()) {
    cv::Mat heard(rows, cols, CV_8U, cv::Scalar(0));
    for (const CoverageDisc& disc : coverage) {
      cv::circle(heard, cellOf(disc.centre_m), static_cast<int>(std::ceil(disc.radius_m / field.cell_m)), cv::Scalar(255), cv::FILLED);
    }
    field.likelihood.setTo(cv::Scalar(-1.0F), heard == 0);
    field.outside = -1.0F;
  }
  return field;
}

/// The posterior of the pose over the search's grid: each candidate's log-likelihood (every point
/// a mixture of the field's likelihood and kOutlierLikelihood, the points a target scan did not
/// hear standing in at the mean of those it did) plus the prior's log-density; its mean and
/// covariance (Olson 2009, §IV-C: the covariance of the score distribution), and the information
/// the scans add to the prior's, Σ_post⁻¹ − Σ_prior⁻¹, its negative directions clamped to 0.
struct GridPosterior {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();  ///< (dx, dy, dyaw) from the initial pose
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
};

GridPosterior gridPosterior(const std::vector<Eigen::Vector3d>& offsets, const std::vector<double>& log_likelihoods,
                            const Eigen::Matrix3d& prior_covariance) {
  GridPosterior posterior;
  const Eigen::Matrix3d prior_information = (prior_covariance + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
  std::vector<double> log_weights(offsets.size());
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < offsets.size(); ++c) {
    log_weights[c] = log_likelihoods[c] - 0.5 * offsets[c].dot(prior_information * offsets[c]);
    top = std::max(top, log_weights[c]);
  }
  if (!std::isfinite(top)) return posterior;
  double total = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (std::size_t c = 0; c < offsets.size(); ++c) {
    const double w = std::exp(log_weights[c] - top);
    total += w;
    first += w * offsets[c];
    second += w * offsets[c] * offsets[c].transpose();
  }
  posterior.mean = first / total;
  const Eigen::Matrix3d covariance = second / total - posterior.mean * posterior.mean.transpose();
  const Eigen::Matrix3d gained = (covariance + 1e-12 * Eigen::Matrix3d::Identity()).inverse() - prior_information;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (gained + gained.transpose()));
  posterior.information = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
  return posterior;
}

}  // namespace

CorrelativeResult correlativeSearch(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source,
                                    const Pose2& initial, const Eigen::Matrix3d& prior_covariance, double sigma_m, int max_steps,
                                    const std::vector<SurfaceSegment>& surfaces, const std::vector<CoverageDisc>& coverage) {
  CorrelativeResult result;
  result.pose = initial;
  if (target.empty() || source.empty()) return result;
  const double half_window_m = std::min(3.0 * std::sqrt(prior_covariance.topLeftCorner<2, 2>().eigenvalues().real().maxCoeff()), 1e4);
  const double half_window_rad = std::min(3.0 * std::sqrt(prior_covariance(2, 2)), 20.0 * 3.14159265358979323846 / 180.0);
  max_steps = std::max(3, max_steps);
  const double cell_m = std::max(sigma_m / 2.0, 2.0 * half_window_m / (max_steps - 1));
  const LikelihoodField field = likelihoodField(target, cell_m, sigma_m, half_window_m + 3.0 * sigma_m, surfaces, coverage);
  double reach_m = 0.0;
  for (const ScanPoint& point : source) reach_m = std::max(reach_m, point.xy_m.norm());
  // A heading step moves the farthest point by about one cell.
  const double yaw_step_rad = std::max(field.cell_m / std::max(reach_m, field.cell_m), half_window_rad / (max_steps / 2));
  const int yaw_steps = half_window_rad > 0.0 ? static_cast<int>(std::ceil(half_window_rad / yaw_step_rad)) : 0;
  const int xy_steps = static_cast<int>(std::ceil(half_window_m / field.cell_m));
  const int side = 2 * xy_steps + 1;

  struct Candidate {
    float score;
    int yaw, x, y;
  };
  std::vector<Candidate> candidates;
  const std::size_t count = static_cast<std::size_t>(2 * yaw_steps + 1) * side * side;
  candidates.reserve(count);
  std::vector<Eigen::Vector3d> offsets;
  std::vector<double> log_likelihoods;
  offsets.reserve(count);
  log_likelihoods.reserve(count);
  std::vector<Eigen::Vector2d> rotated(source.size());
  const double points = static_cast<double>(source.size());
  const double inverse_points = 1.0 / points;
  for (int iy = -yaw_steps; iy <= yaw_steps; ++iy) {
    const Pose2 turned{initial.x_m, initial.y_m, initial.yaw_rad + iy * yaw_step_rad};
    for (std::size_t i = 0; i < source.size(); ++i) rotated[i] = turned * source[i].xy_m;
    for (int ix = -xy_steps; ix <= xy_steps; ++ix) {
      for (int jy = -xy_steps; jy <= xy_steps; ++jy) {
        const Eigen::Vector2d shift(ix * field.cell_m, jy * field.cell_m);
        double sum = 0.0, log_sum = 0.0, heard = 0.0;
        for (const Eigen::Vector2d& point : rotated) {
          const float likelihood = field.at(point + shift);
          if (likelihood < 0.0F) continue;  // no target scan heard there
          sum += likelihood;
          log_sum += LikelihoodField::logAt(likelihood);
          heard += 1.0;
        }
        // The points no target scan heard stand in at the mean of those it did: they neither
        // reward nor cost a pose. A pose that leaves most of the scan unheard is not scored.
        const bool scored = heard >= 0.5 * points;
        candidates.push_back({scored ? static_cast<float>(heard == points ? sum * inverse_points : sum / heard) : 0.0F, iy, ix, jy});
        offsets.emplace_back(ix * field.cell_m, jy * field.cell_m, iy * yaw_step_rad);
        log_likelihoods.push_back(scored ? log_sum * points / heard : -std::numeric_limits<double>::infinity());
      }
    }
  }
  // The best candidate; ties go to the one found first (deterministic).
  const auto best = std::max_element(candidates.begin(), candidates.end(),
                                     [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
  result.score = best->score;
  result.pose = {initial.x_m + best->x * field.cell_m, initial.y_m + best->y * field.cell_m,
                 wrapAngle_rad(initial.yaw_rad + best->yaw * yaw_step_rad)};
  const GridPosterior posterior = gridPosterior(offsets, log_likelihoods, prior_covariance);
  result.posterior_pose = {initial.x_m + posterior.mean.x(), initial.y_m + posterior.mean.y(),
                           wrapAngle_rad(initial.yaw_rad + posterior.mean.z())};
  result.information = posterior.information;
  // A second peak: a local maximum (over the headings) of the translation grid farther than
  // max(3 cells, 2σ) from the best, with a valley between them (the score on the straight line
  // between drops below 90 % of the lower peak). A ridge along a wall is one peak, not several.
  std::vector<float> grid(static_cast<std::size_t>(side) * side, 0.0F);
  const auto cell = [&](int x, int y) -> float& { return grid[static_cast<std::size_t>((x + xy_steps) * side + (y + xy_steps))]; };
  for (const Candidate& candidate : candidates) cell(candidate.x, candidate.y) = std::max(cell(candidate.x, candidate.y), candidate.score);
  const double distinct_cells = std::max(3.0, 2.0 * sigma_m / field.cell_m);
  for (int x = -xy_steps; x <= xy_steps; ++x) {
    for (int y = -xy_steps; y <= xy_steps; ++y) {
      const float peak = cell(x, y);
      if (std::hypot(x - best->x, y - best->y) <= distinct_cells || peak <= result.distinct_score) continue;
      bool local_max = true;
      for (int dx = -1; dx <= 1 && local_max; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          const int nx = x + dx, ny = y + dy;
          if (std::abs(nx) > xy_steps || std::abs(ny) > xy_steps || (dx == 0 && dy == 0)) continue;
          if (cell(nx, ny) > peak) {
            local_max = false;
            break;
          }
        }
      }
      if (!local_max) continue;
      const int samples = static_cast<int>(std::ceil(std::hypot(x - best->x, y - best->y)));
      float valley = peak;
      for (int i = 1; i < samples; ++i) {
        const double f = static_cast<double>(i) / samples;
        valley = std::min(valley, cell(static_cast<int>(std::lround(best->x + f * (x - best->x))),
                                       static_cast<int>(std::lround(best->y + f * (y - best->y)))));
      }
      if (valley < 0.9F * peak) result.distinct_score = peak;
    }
  }
  return result;
}

double typicalPointSigma(const std::vector<ScanPoint>& points) {
  if (points.empty()) return 1e-3;
  std::vector<double> sigmas;
  sigmas.reserve(points.size());
  for (const ScanPoint& point : points) sigmas.push_back(std::sqrt(point.covariance_m2.trace()));
  std::nth_element(sigmas.begin(), sigmas.begin() + static_cast<std::ptrdiff_t>(sigmas.size() / 2), sigmas.end());
  return std::max(sigmas[sigmas.size() / 2], 1e-3);
}

std::vector<std::vector<double>> pointLikelihoods(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source,
                                                  const std::vector<Pose2>& poses) {
  std::vector<std::vector<double>> likelihoods(poses.size(), std::vector<double>(source.size(), 0.0));
  if (target.empty() || source.empty()) return likelihoods;
  const double sigma_m = typicalPointSigma(source);
  // Beyond 3σ of the target the likelihood is 0 (LikelihoodField::at outside the grid).
  const LikelihoodField field = likelihoodField(target, sigma_m / 2.0, sigma_m, 3.0 * sigma_m, {});
  for (std::size_t p = 0; p < poses.size(); ++p) {
    for (std::size_t i = 0; i < source.size(); ++i) likelihoods[p][i] = field.at(poses[p] * source[i].xy_m);
  }
  return likelihoods;
}

}  // namespace sonarmap
