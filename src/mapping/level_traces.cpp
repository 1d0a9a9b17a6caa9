/// @file level_traces.cpp
/// Weak extended returns placed on the level surface their onset implies (see sweep_fan.hpp,
/// appendLevelTrace).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include <Eigen/Dense>

#include "sonarmap/mapping/sweep_fan.hpp"

namespace sonarmap {
namespace {

/// The elevation e in [−half, half] with A cos e + B sin e = s, nearest `prefer_rad`; NaN if none.
double elevationAtLevel(double a, double b, double s, double half_rad, double prefer_rad) {
  const double c = std::hypot(a, b);
  if (!(c > 0.0) || std::abs(s) > c) return std::numeric_limits<double>::quiet_NaN();
  const double delta = std::atan2(a, b);  // A cos e + B sin e = C sin(e + δ)
  const double base = std::asin(s / c);
  double best = std::numeric_limits<double>::quiet_NaN();
  for (double e : {base - delta, std::numbers::pi - base - delta}) {
    e = std::remainder(e, 2.0 * std::numbers::pi);
    if (std::abs(e) > half_rad + 1e-9) continue;
    if (std::isnan(best) || std::abs(e - prefer_rad) < std::abs(best - prefer_rad)) best = std::clamp(e, -half_rad, half_rad);
  }
  return best;
}

/// The edge of the aperture where a level surface enters the cone first (see appendLevelTrace).
struct TraceEdge {
  double elevation_rad;  ///< sonar frame: ± half the aperture
  bool seabed;           ///< the most downward edge, pointing down (else the most upward, pointing up)
};

/// The edges a beam's trace can start from: none when its aperture points both up and down.
std::optional<TraceEdge> traceEdge(const PlannedBeam& beam, double half_aperture_rad) {
  const Eigen::RowVector3d up = beam.sonar_to_map.linear().row(2);
  auto vertical = [&](double elevation_rad) {
    return up.dot(Eigen::Vector3d(std::cos(elevation_rad) * std::cos(beam.bearing_rad),
                                  std::cos(elevation_rad) * std::sin(beam.bearing_rad), std::sin(elevation_rad)));
  };
  const double low = vertical(-half_aperture_rad), high = vertical(half_aperture_rad);
  if (std::max(low, high) < 0.0) return TraceEdge{low <= high ? -half_aperture_rad : half_aperture_rad, true};
  if (std::min(low, high) > 0.0) return TraceEdge{low > high ? -half_aperture_rad : half_aperture_rad, false};
  return std::nullopt;  // a level head: the seabed's onset or the surface's, it cannot tell
}

Eigen::Vector3d direction(double bearing_rad, double elevation_rad) {
  return {std::cos(elevation_rad) * std::cos(bearing_rad), std::cos(elevation_rad) * std::sin(bearing_rad),
          std::sin(elevation_rad)};
}

/// The unit normal (z > 0) of the plane z = a + b x + c y fitted to `points` by least squares, the
/// points farther than 3 robust standard deviations dropped twice; none when fewer than 12 remain,
/// they spread along one line only, or the plane slopes more than 30°.
std::optional<Eigen::Vector3d> fitSlope(std::vector<Eigen::Vector3d> points) {
  for (int pass = 0; pass < 3; ++pass) {
    if (points.size() < 12) return std::nullopt;
    Eigen::MatrixXd a(points.size(), 3);
    Eigen::VectorXd z(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      a.row(static_cast<Eigen::Index>(i)) << 1.0, points[i].x(), points[i].y();
      z(static_cast<Eigen::Index>(i)) = points[i].z();
    }
    const Eigen::Vector3d plane = a.colPivHouseholderQr().solve(z);
    std::vector<double> residuals(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) residuals[i] = std::abs(z(static_cast<Eigen::Index>(i)) - a.row(static_cast<Eigen::Index>(i)).dot(plane));
    if (pass == 2) {
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const Eigen::Vector3d& p : points) mean += p.head<2>();
      mean /= static_cast<double>(points.size());
      Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
      for (const Eigen::Vector3d& p : points) spread += (p.head<2>() - mean) * (p.head<2>() - mean).transpose();
      const Eigen::Vector2d eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(spread).eigenvalues();
      if (!(eigenvalues(0) >= 0.0625 * eigenvalues(1)) || !(eigenvalues(1) > 0.0)) return std::nullopt;
      const Eigen::Vector3d normal = Eigen::Vector3d(-plane(1), -plane(2), 1.0).normalized();
      if (!(normal.z() >= std::cos(30.0 * std::numbers::pi / 180.0))) return std::nullopt;
      return normal;
    }
    std::vector<double> sorted = residuals;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double limit = 3.0 * 1.4826 * sorted[sorted.size() / 2] + 1e-6;
    std::vector<Eigen::Vector3d> kept;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (residuals[i] <= limit) kept.push_back(points[i]);
    }
    points.swap(kept);
  }
  return std::nullopt;
}

}  // namespace

TraceSlopes fitTraceSlopes(const std::vector<PlannedBeam>& beams, const BeamShape& shape) {
  const double half_aperture_rad = 0.5 * shape.vertical_aperture_rad;
  TraceSlopes slopes;
  if (!(half_aperture_rad > 0.0)) return slopes;
  std::vector<Eigen::Vector3d> seabed, surface;
  for (const PlannedBeam& beam : beams) {
    if (beam.hit || !(beam.trace_onset_m <= beam.trace_end_m)) continue;
    const std::optional<TraceEdge> edge = traceEdge(beam, half_aperture_rad);
    if (!edge) continue;
    (edge->seabed ? seabed : surface).push_back(beam.sonar_to_map * (beam.trace_onset_m * direction(beam.bearing_rad, edge->elevation_rad)));
  }
  slopes.seabed_normal = fitSlope(std::move(seabed));
  slopes.surface_normal = fitSlope(std::move(surface));
  return slopes;
}

void appendLevelTrace(const PlannedBeam& beam, const BeamShape& shape, double voxel_m, ArcEvidence evidence,
                      std::vector<HitPoint>& hits, const TraceSlopes& slopes) {
  const double half_aperture_rad = 0.5 * shape.vertical_aperture_rad;
  if (!(half_aperture_rad > 0.0) || !(beam.trace_onset_m <= beam.trace_end_m)) return;
  const std::optional<TraceEdge> edge = traceEdge(beam, half_aperture_rad);
  if (!edge) return;
  // The surface: through the onset point on the edge, level or with the sweep's fitted slope.
  const std::optional<Eigen::Vector3d>& fitted = edge->seabed ? slopes.seabed_normal : slopes.surface_normal;
  const Eigen::Vector3d normal = fitted ? *fitted : Eigen::Vector3d::UnitZ();
  const double offset_m = normal.dot(beam.sonar_to_map.linear() * direction(beam.bearing_rad, edge->elevation_rad)) * beam.trace_onset_m;
  const Eigen::RowVector3d normal_in_sonar = normal.transpose() * beam.sonar_to_map.linear();
  const double half_rad = 0.5 * shape.width_rad;
  const double step_m = 0.5 * voxel_m;
  const int columns = std::max(1, static_cast<int>(std::ceil(shape.width_rad * beam.trace_end_m / voxel_m)));
  for (double range_m = beam.trace_onset_m; range_m <= beam.trace_end_m + 1e-9; range_m += step_m) {
    for (int c = 0; c <= columns; ++c) {
      const double bearing_rad = beam.bearing_rad - half_rad + shape.width_rad * c / columns;
      const Eigen::Vector3d flat(std::cos(bearing_rad), std::sin(bearing_rad), 0.0);
      const double elevation_rad =
          elevationAtLevel(normal_in_sonar.dot(flat), normal_in_sonar.z(), offset_m / range_m, half_aperture_rad, edge->elevation_rad);
      if (std::isnan(elevation_rad)) continue;
      const Eigen::Vector3d point_m = beam.sonar_to_map * (range_m * direction(bearing_rad, elevation_rad));
      const double weight = evidence == ArcEvidence::kBeamPattern ? twoWayPattern(elevation_rad, shape.vertical_aperture_rad) : 1.0;
      hits.push_back({point_m, weight});
    }
  }
}

}  // namespace sonarmap
