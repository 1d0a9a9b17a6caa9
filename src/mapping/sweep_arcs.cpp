/// @file sweep_arcs.cpp
/// A sweep's obstacle arcs, carved by the beams that saw water beyond them (see sweep_fan.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <utility>

#include "sonarmap/mapping/sweep_fan.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// A beam as the carving test needs it: where it saw water, in its own sonar frame.
struct WaterWedge {
  Eigen::Isometry3d map_to_sonar;
  Eigen::Vector3d origin_m;       ///< map frame
  double azimuth_rad = 0.0;       ///< the beam's axis in the map frame, [0, 2π)
  double left_x = 0.0, left_y = 0.0;    ///< the wedge's edges, sonar frame: bearing ± width / 2
  double right_x = 0.0, right_y = 0.0;
  double water_m = 0.0;           ///< water up to here: the echo's leading edge, or the free range
};

WaterWedge wedgeOf(const PlannedBeam& beam, double half_width_rad) {
  WaterWedge wedge;
  wedge.map_to_sonar = beam.sonar_to_map.inverse();
  wedge.origin_m = beam.sonar_to_map.translation();
  const Eigen::Vector3d axis = beam.sonar_to_map.linear() * Eigen::Vector3d(std::cos(beam.bearing_rad), std::sin(beam.bearing_rad), 0.0);
  wedge.azimuth_rad = std::atan2(axis.y(), axis.x());
  if (wedge.azimuth_rad < 0.0) wedge.azimuth_rad += kTwoPi;
  wedge.left_x = std::cos(beam.bearing_rad + half_width_rad);
  wedge.left_y = std::sin(beam.bearing_rad + half_width_rad);
  wedge.right_x = std::cos(beam.bearing_rad - half_width_rad);
  wedge.right_y = std::sin(beam.bearing_rad - half_width_rad);
  wedge.water_m = beam.water_range_m >= 0.0 ? beam.water_range_m : (beam.hit ? beam.hit_range_m : beam.free_range_m);
  return wedge;
}

/// Is `point_m` (map frame) inside the wedge, nearer than `range_m` in the sonar's plane?
bool inWedge(const WaterWedge& wedge, const Eigen::Vector3d& point_m, double range_m) {
  const Eigen::Vector3d v = wedge.map_to_sonar * point_m;
  if (v.x() * v.x() + v.y() * v.y() >= range_m * range_m) return false;
  // Between the right edge and the left edge (the wedge is narrower than a half turn).
  return wedge.right_x * v.y() - wedge.right_y * v.x() >= 0.0 && wedge.left_x * v.y() - wedge.left_y * v.x() <= 0.0;
}

/// Circular distance of two azimuths, [0, π].
double azimuthGap_rad(double a_rad, double b_rad) {
  const double d = std::fmod(std::abs(a_rad - b_rad), kTwoPi);
  return std::min(d, kTwoPi - d);
}

/// A beam's cone as the carving test needs it (the volume model).
struct WaterCone {
  WaterWedge wedge;
  Eigen::Vector3d axis;  ///< unit, map frame
  double tan_half_aperture = 0.0;
};

/// Is `point_m` (map frame) inside the cone, nearer than `range_m` from its sonar?
bool inCone(const WaterCone& cone, const Eigen::Vector3d& point_m, double range_m) {
  // Most points a cone is asked about lie beyond its range: the distance in the map frame tells
  // (a rotation keeps it to 1e-15; the margin leaves every case near the boundary to the test
  // below, in the sonar frame, as before), without rotating the point.
  if ((point_m - cone.wedge.origin_m).squaredNorm() >= range_m * range_m * (1.0 + 1e-9)) return false;
  const Eigen::Vector3d v = cone.wedge.map_to_sonar * point_m;
  if (v.squaredNorm() >= range_m * range_m) return false;
  const double horizontal_sq = v.x() * v.x() + v.y() * v.y();
  if (v.z() * v.z() > cone.tan_half_aperture * cone.tan_half_aperture * horizontal_sq) return false;
  const WaterWedge& w = cone.wedge;
  return w.right_x * v.y() - w.right_y * v.x() >= 0.0 && w.left_x * v.y() - w.left_y * v.x() <= 0.0;
}

/// Whether cones `a` and `b` can hold a common direction as seen from a's sonar, by their
/// bearings: a direction in both lies within half a width of each beam's bearing, each measured in
/// its own sonar frame. Rotating a direction by θ (the angle between the two sonar frames) and
/// moving the origin (`parallax_rad`) changes its bearing by at most (θ + parallax) / cos e, e the
/// largest elevation it passes (half the aperture plus both angles), so the bearings differ by at
/// most a width plus that. Conservative: never false for cones that share a direction.
bool bearingsCanShare(const PlannedBeam& a, const PlannedBeam& b, const BeamShape& shape, double parallax_rad) {
  const double cos_rotation = std::clamp(0.5 * ((a.sonar_to_map.linear().cwiseProduct(b.sonar_to_map.linear())).sum() - 1.0), -1.0, 1.0);
  const double turn_rad = std::acos(cos_rotation) + parallax_rad;
  const double elevation_rad = 0.5 * shape.vertical_aperture_rad + turn_rad;
  if (elevation_rad >= 1.4) return true;  // near the poles bearings say nothing
  const double gap_rad = std::abs(std::remainder(a.bearing_rad - b.bearing_rad, kTwoPi));
  return gap_rad <= shape.width_rad + turn_rad / std::cos(elevation_rad) + 1e-9;
}

}  // namespace

double twoWayPattern(double elevation_rad, double aperture_rad) {
  const double u = 2.0 * elevation_rad / aperture_rad;
  return std::exp2(-2.0 * u * u);
}

namespace {

/// A vertical face is drawn only along directions within 75° of the horizontal: a steeper ray meets
/// it at over 75° incidence, where a face scatters little (Lambert's law: cos² 75° = −12 dB) and
/// its points would recede to 1 / cos s of the face's distance.
const double kMinFaceSlopeCos = std::cos(75.0 * std::numbers::pi / 180.0);

/// The cosines of the cone's most and least horizontal grid directions' map slopes (the rows ×
/// columns grid of planShellArcs; `column_dirs` the columns' cos, sin of bearing).
std::pair<double, double> slopeCosines(const PlannedBeam& beam, const BeamShape& shape, int rows,
                                       const std::vector<Eigen::Vector2d>& column_dirs) {
  const Eigen::RowVector3d up = beam.sonar_to_map.linear().row(2);  // map z of a sonar-frame direction
  double nearest = 0.0, farthest = 1.0;
  for (int r = 0; r <= rows; ++r) {
    const double elevation = 0.5 * shape.vertical_aperture_rad * (2.0 * r / rows - 1.0);
    for (const Eigen::Vector2d& dir : column_dirs) {
      const double sin_slope = up.dot(Eigen::Vector3d(std::cos(elevation) * dir.x(), std::cos(elevation) * dir.y(), std::sin(elevation)));
      const double cos_slope = std::sqrt(std::max(0.0, 1.0 - sin_slope * sin_slope));
      nearest = std::max(nearest, cos_slope);
      farthest = std::min(farthest, cos_slope);
    }
  }
  return {nearest, farthest};
}

/// A vertical face's horizontal distance across one beam's width (ObstacleSurface::kVertical): d(φ)
/// = d₀ + g · clamp(±(φ − φ_near), 0, w) at bearing φ of the beam's sonar frame, the face receding
/// at g metres per radian from the beam's near edge φ_near = bearing ∓ w / 2, where its leading
/// edge d₀ comes from (see faceRun).
struct FaceRun {
  double distance_m = 0.0;         ///< d₀, horizontal, metres
  double slope_m_per_rad = 0.0;    ///< g ≥ 0; 0: the face square to the beam, or not measured
  double near_bearing_rad = 0.0;   ///< φ_near, the beam's sonar frame
  double direction = 1.0;          ///< +1: receding with increasing bearing, −1: decreasing
  double width_rad = 0.0;          ///< w

  double at(double bearing_rad) const {
    return distance_m + slope_m_per_rad * std::clamp(direction * (bearing_rad - near_bearing_rad), 0.0, width_rad);
  }
};

/// At most this many beams on either side of a beam measure its face's slope (faceRun).
constexpr std::size_t kMaxFaceNeighbours = 8;

/// The face across beam `b` of a sweep, from the beams beside it in bearing (b ± 1, b ± 2, … while
/// they hit and lie within half a beam width of b; the nearest on each side within a width). Each leading edge is the nearest point of the face
/// in its beam, at the beam's near edge: at oblique incidence the face recedes across the beam,
/// and the neighbours' face points (their face distances along their axes' azimuths), seen from
/// b's sonar at their axes' bearings in its frame, measure how fast: their distances are those of
/// the face at the near edges, one bearing step apart. A straight line fitted to them (least
/// squares, b's own among them) is the face's slope where it has points on both sides of b and
/// every point lies within `tolerance_m` of it (a plane: not a pile's near point, a corner, or
/// leading edges too noisy to tell), and where the echo lasted long enough for it: a face receding
/// by g · w across the beam echoes from d₀ to d₀ + g · w, so the beam's echo must end
/// (PlannedBeam::hit_end_m) no nearer than that less `tolerance_m`. Otherwise the face is square
/// to the beam, at d₀.
FaceRun faceRun(const std::vector<PlannedBeam>& beams, const std::vector<WaterCone>& cones,
                const std::vector<double>& face_m, std::size_t b, const BeamShape& shape, double tolerance_m) {
  const PlannedBeam& beam = beams[b];
  const double width_rad = shape.width_rad;
  FaceRun run{face_m[b], 0.0, beam.bearing_rad, 1.0, width_rad};
  // A bearing of the sonar frame must be one azimuth of the map across the aperture: the fan
  // rolled by ρ about the beam's axis turns the aperture's edge rows by (a / 2) sin ρ in azimuth,
  // at most half the beam's width here (a level head: 0; a tilted one looking to the side: no).
  const Eigen::Vector3d across = beam.sonar_to_map.linear() * Eigen::Vector3d(-std::sin(beam.bearing_rad), std::cos(beam.bearing_rad), 0.0);
  if (0.5 * shape.vertical_aperture_rad * std::abs(across.z()) > 0.5 * width_rad) return run;
  const Eigen::Vector3d& origin_m = cones[b].wedge.origin_m;
  std::array<Eigen::Vector2d, 2 * kMaxFaceNeighbours + 1> points;  // (bearing step, face distance)
  std::size_t count = 0;
  points[count++] = {0.0, face_m[b]};
  int sides = 0;
  for (const int side : {-1, 1}) {
    for (std::size_t k = 1; k <= kMaxFaceNeighbours; ++k) {
      const std::size_t n = side < 0 ? b - k : b + k;  // below the first beam, wraps past the end
      if (n >= beams.size() || !(face_m[n] > 0.0)) break;
      const WaterWedge& neighbour = cones[n].wedge;
      const Eigen::Vector3d seen = cones[b].wedge.map_to_sonar * (neighbour.origin_m + beams[n].hit_range_m * cones[n].axis);
      const double step_rad = std::remainder(std::atan2(seen.y(), seen.x()) - beam.bearing_rad, kTwoPi);
      // Within half a width, or the nearest beam on this side within a width.
      if (!(std::abs(step_rad) > 1e-6 && std::abs(step_rad) <= (k == 1 ? 1.0 : 0.5) * width_rad)) break;
      const Eigen::Vector3d point_m = neighbour.origin_m + face_m[n] * Eigen::Vector3d(std::cos(neighbour.azimuth_rad), std::sin(neighbour.azimuth_rad), 0.0);
      points[count++] = {step_rad, (point_m - origin_m).head<2>().norm()};
      sides |= step_rad < 0.0 ? 1 : 2;
    }
  }
  if (sides != 3) return run;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < count; ++i) mean += points[i];
  mean /= static_cast<double>(count);
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector2d d = points[i] - mean;
    sxx += d.x() * d.x();
    sxy += d.x() * d.y();
  }
  const double slope = sxy / sxx;  // sxx > 0: points on both sides
  for (std::size_t i = 0; i < count; ++i) {
    if (std::abs(points[i].y() - mean.y() - slope * (points[i].x() - mean.x())) > tolerance_m) return run;
  }
  if (!(std::abs(slope) * width_rad <= beam.hit_end_m - beam.hit_range_m + tolerance_m)) return run;  // NaN end: no slope
  if (slope == 0.0) return run;
  run.slope_m_per_rad = std::abs(slope);
  run.direction = slope > 0.0 ? 1.0 : -1.0;
  run.near_bearing_rad = beam.bearing_rad - run.direction * 0.5 * width_rad;
  return run;
}

/// planArcs of the beam-volume model (sweep_fan.hpp).
void planShellArcs(const std::vector<PlannedBeam>& beams, const BeamShape& shape, double voxel_m, double tolerance_m,
                   ArcEvidence evidence, ObstacleSurface surface, bool face_slope, std::vector<HitPoint>& hits) {
  const double half_rad = 0.5 * shape.width_rad;
  const double half_aperture_rad = 0.5 * shape.vertical_aperture_rad;
  std::vector<WaterCone> cones;
  cones.reserve(beams.size());
  for (const PlannedBeam& beam : beams) {
    WaterCone cone{wedgeOf(beam, half_rad), {}, std::tan(half_aperture_rad)};
    cone.axis = beam.sonar_to_map.linear() * Eigen::Vector3d(std::cos(beam.bearing_rad), std::sin(beam.bearing_rad), 0.0);
    cones.push_back(cone);
  }
  // A cone holds directions within this angle of its axis (both half-widths at once).
  const double cone_radius_rad = std::hypot(half_rad, half_aperture_rad);
  std::vector<std::size_t> candidates;
  std::vector<char> row_kept;
  std::vector<double> column_bearing_rad;     // each column's bearing, sonar frame
  std::vector<Eigen::Vector2d> column_dirs;  // cos, sin of each column's bearing
  std::vector<double> column_face_m;         // a vertical face's horizontal distance at each column
  std::vector<HitPoint> trace;
  // Each obstacle's grid: columns across the width and rows across the aperture, at most a voxel
  // apart at its range; and, for a vertical face, the cosines of the grid's most and least
  // horizontal map slopes (the face's distance is the range times the first).
  auto grid = [&](const PlannedBeam& beam, double range_m) {
    const int columns = std::max(1, static_cast<int>(std::ceil(shape.width_rad * range_m / voxel_m)));
    column_bearing_rad.clear();
    column_dirs.clear();
    for (int c = 0; c <= columns; ++c) {
      const double angle = beam.bearing_rad - half_rad + shape.width_rad * c / columns;
      column_bearing_rad.push_back(angle);
      column_dirs.emplace_back(std::cos(angle), std::sin(angle));
    }
    return std::max(1, static_cast<int>(std::ceil(shape.vertical_aperture_rad * range_m / voxel_m)));
  };
  std::vector<std::pair<double, double>> slope_cos(beams.size(), {0.0, 1.0});
  std::vector<double> face_m(beams.size(), 0.0);  // each obstacle's face distance, horizontal; 0: none
  if (surface == ObstacleSurface::kVertical) {
    for (std::size_t b = 0; b < beams.size(); ++b) {
      if (!beams[b].hit) continue;
      const int rows = grid(beams[b], beams[b].hit_range_m);
      slope_cos[b] = slopeCosines(beams[b], shape, rows, column_dirs);
      face_m[b] = beams[b].hit_range_m * slope_cos[b].first;
    }
  }
  for (std::size_t b = 0; b < beams.size(); ++b) {
    const PlannedBeam& beam = beams[b];
    const bool traced = beam.traced();
    if (!beam.hit && !traced) continue;
    const double range_m = beam.hit ? beam.hit_range_m : beam.trace_onset_m;
    candidates.clear();
    for (std::size_t n = 0; n < beams.size(); ++n) {
      if (n == b) continue;
      const double offset_m = (cones[n].wedge.origin_m - cones[b].wedge.origin_m).norm();
      const double reach_m = cones[n].wedge.water_m - tolerance_m;
      if (reach_m <= range_m - offset_m) continue;  // saw no water as far as this shell
      // The two cones can share a direction only if their axes are within two cone radii, plus the
      // parallax of the sonar's motion at this range.
      const double parallax_rad = std::asin(std::min(1.0, 2.0 * offset_m / range_m));
      if (cones[n].axis.dot(cones[b].axis) < std::cos(std::min(std::numbers::pi, 2.0 * cone_radius_rad + parallax_rad))) continue;
      if (!bearingsCanShare(beams[b], beams[n], shape, parallax_rad)) continue;
      candidates.push_back(n);
    }
    auto carved = [&](const Eigen::Vector3d& point_m) {
      return std::any_of(candidates.begin(), candidates.end(), [&](std::size_t n) {
        return inCone(cones[n], point_m, cones[n].wedge.water_m - tolerance_m);
      });
    };
    if (traced) {  // a weak extended return: its level trace, less what other beams saw as water
      trace.clear();
      appendLevelTrace(beam, shape, voxel_m, evidence, trace);
      std::copy_if(trace.begin(), trace.end(), std::back_inserter(hits), [&](const HitPoint& p) { return !carved(p.point_m); });
      continue;
    }
    int rows = grid(beam, range_m);
    // A vertical face: its horizontal distance across the beam, and the farthest range the echo
    // allows. Its points are farther than the shell's and step in height by r de / cos s: rows at
    // most a voxel apart there.
    FaceRun face;
    double face_end_m = std::numeric_limits<double>::infinity();
    const Eigen::RowVector3d up = beam.sonar_to_map.linear().row(2);
    if (surface == ObstacleSurface::kVertical) {
      face = face_slope ? faceRun(beams, cones, face_m, b, shape, tolerance_m) : FaceRun{face_m[b]};
      if (beam.hit_end_m >= range_m) face_end_m = beam.hit_end_m + tolerance_m;
      const double steepest_cos = std::max(slope_cos[b].second, kMinFaceSlopeCos);
      const double farthest_m = face.distance_m + face.slope_m_per_rad * shape.width_rad;
      const double reach_m = std::min(farthest_m / steepest_cos, face_end_m);  // face_end_m: infinite or past range_m
      rows = std::max(rows, static_cast<int>(std::ceil(shape.vertical_aperture_rad * reach_m / (voxel_m * steepest_cos))));
      column_face_m.clear();
      for (const double bearing_rad : column_bearing_rad) column_face_m.push_back(face.at(bearing_rad));
    }
    const std::size_t first = hits.size();  // the beam's shell: hits[first, end)
    row_kept.assign(static_cast<std::size_t>(rows) + 1, 0);
    for (int r = 0; r <= rows; ++r) {
      const double elevation = -half_aperture_rad + shape.vertical_aperture_rad * r / rows;
      const double weight = evidence == ArcEvidence::kBeamPattern ? twoWayPattern(elevation, shape.vertical_aperture_rad) : 1.0;
      const double cos_elevation = std::cos(elevation), sin_elevation = std::sin(elevation);
      for (std::size_t c = 0; c < column_dirs.size(); ++c) {
        const Eigen::Vector2d& dir = column_dirs[c];
        const Eigen::Vector3d unit(cos_elevation * dir.x(), cos_elevation * dir.y(), sin_elevation);
        double point_range_m = range_m;
        if (surface == ObstacleSurface::kVertical) {
          const double sin_slope = up.dot(unit);
          const double cos_slope = std::sqrt(std::max(0.0, 1.0 - sin_slope * sin_slope));
          if (cos_slope < kMinFaceSlopeCos) continue;
          point_range_m = column_face_m[c] / cos_slope;
          if (point_range_m > face_end_m) continue;  // beyond the echo: the face ends before
        }
        const Eigen::Vector3d point_m = beam.sonar_to_map * (point_range_m * unit);
        if (carved(point_m)) continue;
        hits.push_back({point_m, weight});
        row_kept[static_cast<std::size_t>(r)] = 1;
      }
    }
    if (evidence == ArcEvidence::kSpreadUniform) {
      const auto kept_rows = static_cast<double>(std::count(row_kept.begin(), row_kept.end(), 1));
      for (std::size_t i = first; i < hits.size(); ++i) hits[i].weight = 1.0 / kept_rows;
    }
  }
}

}  // namespace

void planArcs(const std::vector<PlannedBeam>& beams, const BeamShape& shape, double voxel_m, double tolerance_m,
              ArcEvidence evidence, std::vector<HitPoint>& hits, ObstacleSurface surface, bool face_slope) {
  if (shape.vertical_aperture_rad <= 0.0 || shape.width_rad <= 0.0) {
    return planArcs(beams, shape.width_rad, voxel_m, tolerance_m, hits);
  }
  hits.clear();
  planShellArcs(beams, shape, voxel_m, tolerance_m, evidence, surface, face_slope, hits);
}

void planArcs(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m, double tolerance_m,
              std::vector<HitPoint>& hits) {
  hits.clear();
  if (beam_width_rad <= 0.0) {  // one ray per beam: its single point
    for (const PlannedBeam& beam : beams) {
      if (beam.hit) {
        hits.push_back({beam.sonar_to_map * Eigen::Vector3d(beam.hit_range_m * std::cos(beam.bearing_rad),
                                                             beam.hit_range_m * std::sin(beam.bearing_rad), 0.0)});
      }
    }
    return;
  }
  const double half_rad = 0.5 * beam_width_rad;
  std::vector<WaterWedge> wedges;
  wedges.reserve(beams.size());
  for (const PlannedBeam& beam : beams) wedges.push_back(wedgeOf(beam, half_rad));
  // The beams by azimuth, so that those that can overlap an arc are a window of this order.
  std::vector<std::size_t> order(beams.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return wedges[a].azimuth_rad < wedges[b].azimuth_rad; });
  double spread_m = 0.0;  // how far the sonar moved within the sweep (0 for a static sweep)
  for (const WaterWedge& wedge : wedges) spread_m = std::max(spread_m, (wedge.origin_m - wedges.front().origin_m).norm());

  std::vector<std::size_t> candidates;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t b = order[k];
    const PlannedBeam& beam = beams[b];
    if (!beam.hit) continue;
    // Another beam can cover a point of this arc only if its axis is within a beam width, plus
    // the parallax of the sonar's motion at this range.
    const double parallax_rad = std::asin(std::min(1.0, 2.0 * spread_m / beam.hit_range_m));
    const double window_rad = beam_width_rad + parallax_rad;
    candidates.clear();
    auto consider = [&](std::size_t n) {
      if (n == b) return;
      // It must have seen water beyond this arc, from wherever it was.
      const double reach_m = wedges[n].water_m - tolerance_m;
      if (reach_m <= beam.hit_range_m - (wedges[n].origin_m - wedges[b].origin_m).norm()) return;
      candidates.push_back(n);
    };
    for (std::size_t step = 1; step < order.size(); ++step) {  // counter-clockwise, then clockwise
      const std::size_t n = order[(k + step) % order.size()];
      if (azimuthGap_rad(wedges[n].azimuth_rad, wedges[b].azimuth_rad) > window_rad) break;
      consider(n);
    }
    for (std::size_t step = 1; step < order.size(); ++step) {
      const std::size_t n = order[(k + order.size() - step) % order.size()];
      if (azimuthGap_rad(wedges[n].azimuth_rad, wedges[b].azimuth_rad) > window_rad) break;
      consider(n);
    }
    // The arc, points at most a voxel apart, each kept unless a candidate saw water beyond it.
    const int intervals = std::max(1, static_cast<int>(std::ceil(beam_width_rad * beam.hit_range_m / voxel_m)));
    for (int i = 0; i <= intervals; ++i) {
      const double angle = beam.bearing_rad - half_rad + beam_width_rad * i / intervals;
      const Eigen::Vector3d point_m =
          beam.sonar_to_map * Eigen::Vector3d(beam.hit_range_m * std::cos(angle), beam.hit_range_m * std::sin(angle), 0.0);
      const bool carved = std::any_of(candidates.begin(), candidates.end(), [&](std::size_t n) {
        return inWedge(wedges[n], point_m, wedges[n].water_m - tolerance_m);
      });
      if (!carved) hits.push_back({point_m});
    }
  }
}

}  // namespace sonarmap
