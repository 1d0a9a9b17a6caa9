/// @file correlative_search.cpp
/// correlativeSearch (scan_matcher.hpp): Olson's correlative scan matching (ICRA 2009) over a
/// likelihood field made with OpenCV's distance transform.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "sonarmap/slam/scan_matcher.hpp"

namespace sonarmap {
namespace {

/// The target's likelihood field: exp(−d²/2σ²) of the distance to the nearest target point, on a
/// grid of `cell_m` whose cell (0, 0) has its corner at `origin`.
struct LikelihoodField {
  cv::Mat likelihood;  ///< CV_32F, rows along y, columns along x
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double cell_m = 1.0;

  float at(const Eigen::Vector2d& point) const {
    const double cx = std::floor((point.x() - origin.x()) / cell_m);
    const double cy = std::floor((point.y() - origin.y()) / cell_m);
    if (cx < 0 || cy < 0 || cx >= likelihood.cols || cy >= likelihood.rows) return 0.0F;
    return likelihood.at<float>(static_cast<int>(cy), static_cast<int>(cx));
  }
};

LikelihoodField likelihoodField(const std::vector<ScanPoint>& target, double cell_m, double sigma_m, double margin_m,
                                const std::vector<SurfaceSegment>& surfaces) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (const ScanPoint& point : target) {
    low = low.cwiseMin(point.xy_m);
    high = high.cwiseMax(point.xy_m);
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
  return field;
}

}  // namespace

CorrelativeResult correlativeSearch(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source,
                                    const Pose2& initial, double half_window_m, double half_window_rad,
                                    double sigma_m, int max_steps, const std::vector<SurfaceSegment>& surfaces) {
  CorrelativeResult result;
  result.pose = initial;
  if (target.empty() || source.empty()) return result;
  max_steps = std::max(3, max_steps);
  const double cell_m = std::max(sigma_m / 2.0, 2.0 * half_window_m / (max_steps - 1));
  const LikelihoodField field = likelihoodField(target, cell_m, sigma_m, half_window_m + 3.0 * sigma_m, surfaces);
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
  candidates.reserve(static_cast<std::size_t>(2 * yaw_steps + 1) * side * side);
  std::vector<Eigen::Vector2d> rotated(source.size());
  const double inverse_points = 1.0 / static_cast<double>(source.size());
  for (int iy = -yaw_steps; iy <= yaw_steps; ++iy) {
    const Pose2 turned{initial.x_m, initial.y_m, initial.yaw_rad + iy * yaw_step_rad};
    for (std::size_t i = 0; i < source.size(); ++i) rotated[i] = turned * source[i].xy_m;
    for (int ix = -xy_steps; ix <= xy_steps; ++ix) {
      for (int jy = -xy_steps; jy <= xy_steps; ++jy) {
        const Eigen::Vector2d shift(ix * field.cell_m, jy * field.cell_m);
        double sum = 0.0;
        for (const Eigen::Vector2d& point : rotated) sum += field.at(point + shift);
        candidates.push_back({static_cast<float>(sum * inverse_points), iy, ix, jy});
      }
    }
  }
  // The best candidate; ties go to the one found first (deterministic).
  const auto best = std::max_element(candidates.begin(), candidates.end(),
                                     [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
  result.score = best->score;
  result.pose = {initial.x_m + best->x * field.cell_m, initial.y_m + best->y * field.cell_m,
                 wrapAngle_rad(initial.yaw_rad + best->yaw * yaw_step_rad)};
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
