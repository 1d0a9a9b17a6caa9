/// @file level_traces.cpp
/// Weak extended returns placed on the level surface their onset implies (see sweep_fan.hpp,
/// appendLevelTrace).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

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

/// The unit direction at `bearing_rad` and `elevation_rad`, sonar frame.
Eigen::Vector3d direction(double bearing_rad, double elevation_rad) {
  return {std::cos(elevation_rad) * std::cos(bearing_rad), std::cos(elevation_rad) * std::sin(bearing_rad),
          std::sin(elevation_rad)};
}

/// The edge of the aperture where a level surface enters the cone first (see appendLevelTrace).
struct TraceEdge {
  double elevation_rad;  ///< sonar frame: ± half the aperture
  bool seabed;           ///< the most downward edge, pointing down (else the most upward, pointing up)
};

/// The edges a beam's trace can start from: none when its aperture points both up and down, unless
/// `below_surface_margin_m` is set (appendLevelTrace): then the lower edge when the trace's onset
/// lies nearer, by more than the margin, than where the known water surface enters the upper edge.
std::optional<TraceEdge> traceEdge(const PlannedBeam& beam, double half_aperture_rad,
                                   std::optional<double> below_surface_margin_m = std::nullopt) {
  const Eigen::RowVector3d up = beam.sonar_to_map.linear().row(2);
  auto vertical = [&](double elevation_rad) { return up.dot(direction(beam.bearing_rad, elevation_rad)); };
  const double low = vertical(-half_aperture_rad), high = vertical(half_aperture_rad);
  const double lower_rad = low <= high ? -half_aperture_rad : half_aperture_rad;
  if (std::max(low, high) < 0.0) return TraceEdge{lower_rad, true};
  if (std::min(low, high) > 0.0) return TraceEdge{-lower_rad, false};
  // A level head: the seabed's onset or the surface's. Only a known surface tells them apart.
  const double above_m = beam.surface_z_m - beam.sonar_to_map.translation().z();
  if (!below_surface_margin_m || !(above_m > 0.0)) return std::nullopt;  // NaN: unknown surface
  const double surface_onset_m = above_m / std::max(low, high);
  if (beam.trace_onset_m < surface_onset_m - *below_surface_margin_m) return TraceEdge{lower_rad, true};
  return std::nullopt;
}

}  // namespace

bool isLevelReturn(const PlannedBeam& beam, const BeamShape& shape, double onset_m, double end_m, double tolerance_m) {
  const double half_aperture_rad = 0.5 * shape.vertical_aperture_rad;
  if (!(half_aperture_rad > 0.0) || !(onset_m > 0.0 && onset_m <= end_m)) return false;
  const std::optional<TraceEdge> edge = traceEdge(beam, half_aperture_rad);
  if (!edge) return false;
  // The steepest ray of the cone (the edge a level surface enters by): a vertical face at
  // horizontal distance d echoes from d / cos e of each ray's slope e, so at most to onset / cos e.
  const double slope_sin = beam.sonar_to_map.linear().row(2).dot(direction(beam.bearing_rad, edge->elevation_rad));
  if (!edge->seabed) {
    // The known water surface enters a cone that points up at `above / slope` (its top ray): a
    // return that starts there is the surface, however soon the beam's range cuts it short.
    const double above_m = beam.surface_z_m - beam.sonar_to_map.translation().z();
    if (above_m > 0.0 && std::abs(onset_m - above_m / slope_sin) <= tolerance_m) return true;
  }
  return end_m > onset_m / std::sqrt(std::max(1e-12, 1.0 - slope_sin * slope_sin)) + tolerance_m;
}

std::optional<Eigen::Vector3d> seabedOnsetPoint(const PlannedBeam& beam, const BeamShape& shape) {
  const double half_aperture_rad = 0.5 * shape.vertical_aperture_rad;
  if (!(half_aperture_rad > 0.0) || !beam.traced()) return std::nullopt;
  const std::optional<TraceEdge> edge = traceEdge(beam, half_aperture_rad);
  if (!edge || !edge->seabed) return std::nullopt;
  return beam.sonar_to_map * (beam.trace_onset_m * direction(beam.bearing_rad, edge->elevation_rad));
}

void appendLevelTrace(const PlannedBeam& beam, const BeamShape& shape, double voxel_m, ArcEvidence evidence,
                      std::vector<HitPoint>& hits) {
  const double half_aperture_rad = 0.5 * shape.vertical_aperture_rad;
  if (!(half_aperture_rad > 0.0) || !(beam.trace_onset_m <= beam.trace_end_m)) return;
  const std::optional<TraceEdge> edge = traceEdge(beam, half_aperture_rad, voxel_m);
  if (!edge) return;
  // The surface: the plane through the onset point on the edge with the trace's normal (level
  // unless the seabed's slope was measured), `level_m` from the sonar along that normal.
  const Eigen::RowVector3d up = (beam.sonar_to_map.linear().transpose() * beam.trace_normal).transpose();  // sonar frame
  const double level_m = beam.trace_onset_m * up.dot(direction(beam.bearing_rad, edge->elevation_rad));
  const double half_rad = 0.5 * shape.width_rad;
  const double step_m = 0.5 * voxel_m;
  const int columns = std::max(1, static_cast<int>(std::ceil(shape.width_rad * beam.trace_end_m / voxel_m)));
  for (double range_m = beam.trace_onset_m; range_m <= beam.trace_end_m + 1e-9; range_m += step_m) {
    for (int c = 0; c <= columns; ++c) {
      const double bearing_rad = beam.bearing_rad - half_rad + shape.width_rad * c / columns;
      const Eigen::Vector3d flat(std::cos(bearing_rad), std::sin(bearing_rad), 0.0);
      const double elevation_rad =
          elevationAtLevel(up.dot(flat), up.z(), level_m / range_m, half_aperture_rad, edge->elevation_rad);
      if (std::isnan(elevation_rad)) continue;
      const Eigen::Vector3d point_m = beam.sonar_to_map * (range_m * direction(bearing_rad, elevation_rad));
      const double weight = evidence == ArcEvidence::kBeamPattern ? twoWayPattern(elevation_rad, shape.vertical_aperture_rad) : 1.0;
      hits.push_back({point_m, weight});
    }
  }
}

}  // namespace sonarmap
