/// @file level_traces.cpp
/// Weak extended returns placed on the level surface their onset implies (see sweep_fan.hpp,
/// appendLevelTrace).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "sonarmap/mapping/sweep_fan.hpp"

namespace sonarmap {
namespace {

/// Where the rays of one bearing's column meet a plane: the elevation e with A cos e + B sin e = s,
/// A and B the components along the plane's normal of the bearing's unit vector in the sonar's
/// plane and of the sonar's z axis, s the plane's distance over the range. Solved as
/// C sin(e + δ) = s, C and δ computed once per column.
class LevelCrossing {
 public:
  LevelCrossing(double a, double b) : amplitude_(std::hypot(a, b)), phase_rad_(std::atan2(a, b)) {}

  /// The elevation in [−half, half] where the direction's component along the plane's normal is
  /// `s`, nearest `prefer_rad`; NaN if none.
  double elevation(double s, double half_rad, double prefer_rad) const {
    if (!(amplitude_ > 0.0) || std::abs(s) > amplitude_) return std::numeric_limits<double>::quiet_NaN();
    const double base = std::asin(s / amplitude_);
    double best = std::numeric_limits<double>::quiet_NaN();
    for (double e : {base - phase_rad_, std::numbers::pi - base - phase_rad_}) {
      if (std::abs(e) > std::numbers::pi) e = std::remainder(e, 2.0 * std::numbers::pi);  // else e itself
      if (std::abs(e) > half_rad + 1e-9) continue;
      if (std::isnan(best) || std::abs(e - prefer_rad) < std::abs(best - prefer_rad)) best = std::clamp(e, -half_rad, half_rad);
    }
    return best;
  }

 private:
  double amplitude_;  ///< C
  double phase_rad_;  ///< δ
};

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
  // What each column's points share at every range: its bearing's cosine and sine, and the level
  // equation's amplitude and phase (LevelCrossing).
  struct Column {
    double cos_bearing, sin_bearing;
    LevelCrossing crossing;
  };
  std::vector<Column> grid;
  grid.reserve(static_cast<std::size_t>(columns) + 1);
  for (int c = 0; c <= columns; ++c) {
    const double bearing_rad = beam.bearing_rad - half_rad + shape.width_rad * c / columns;
    const double cos_bearing = std::cos(bearing_rad), sin_bearing = std::sin(bearing_rad);
    grid.push_back({cos_bearing, sin_bearing, LevelCrossing(up.dot(Eigen::Vector3d(cos_bearing, sin_bearing, 0.0)), up.z())});
  }
  for (double range_m = beam.trace_onset_m; range_m <= beam.trace_end_m + 1e-9; range_m += step_m) {
    for (const Column& column : grid) {
      const double elevation_rad = column.crossing.elevation(level_m / range_m, half_aperture_rad, edge->elevation_rad);
      if (std::isnan(elevation_rad)) continue;
      const double cos_elevation = std::cos(elevation_rad);
      const Eigen::Vector3d unit(cos_elevation * column.cos_bearing, cos_elevation * column.sin_bearing, std::sin(elevation_rad));
      const Eigen::Vector3d point_m = beam.sonar_to_map * (range_m * unit);
      const double weight = evidence == ArcEvidence::kBeamPattern ? twoWayPattern(elevation_rad, shape.vertical_aperture_rad) : 1.0;
      hits.push_back({point_m, weight});
    }
  }
}

}  // namespace sonarmap
