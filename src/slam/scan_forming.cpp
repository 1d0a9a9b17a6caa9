/// @file scan_forming.cpp
/// formScans (scan_forming.hpp): motion-compensated scans from a log's sweeps and its dead reckoning.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/core/statistics.hpp"
#include "sonarmap/mapping/detected_log.hpp"
#include "sonarmap/slam/scan_forming.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/sweeps.hpp"
#include "scan_points.hpp"

namespace sonarmap {
namespace {

using scan_points::deadReckoningAt;

/// What every scan of a sweep shares.
struct ScanGeometry {
  double bearing_sigma_rad = 0.0;
  double reach_m = 0.0;
  /// How far off its beam's axis a leading edge can be heard, radians (0: every point on its axis).
  double leading_edge_rad = 0.0;
};

/// The bearing from which each obstacle's leading edge came, as a turn from its beam's axis
/// (radians; 0 for a row without an obstacle or without a neighbour on both sides). The detector's
/// leading edge is where the echo comes within leading_edge_db of its peak (detectors.hpp): on a
/// surface seen at incidence α, the echo's rise across the range spreads over the beam, so that
/// point is heard `edge_rad` off the axis on the side of the surface's normal (its nearest part),
/// or from the normal itself where that lies within the beam (α < edge_rad). Where the surface's
/// range spread across that angle, r·tan α·edge_rad, is no larger than the echo's own rise at normal
/// incidence (the pulse and bin: `resolution_m`), the rise is the pulse's and the edge lies nearer
/// the axis: the angle is scaled by spread / (spread + resolution). α comes from the ranges of the
/// beams either side (dr/dθ = r tan α); a small target heard across several beams at one range (a
/// pile's arc) has α ≈ 0 and is not turned, nor is a beam between two surfaces (a corner).
std::vector<double> leadingEdgeTurns(const PolarImage& polar, const SweepDetection& detection, int first_row, int last_row,
                                     double edge_rad) {
  std::vector<double> turns(static_cast<std::size_t>(last_row - first_row), 0.0);
  if (!(edge_rad > 0.0)) return turns;
  std::vector<int> rows;  // the rows with an obstacle, in bearing order
  for (int row = first_row; row < last_row; ++row) {
    if (detection.detections[static_cast<std::size_t>(row)].hasObstacle()) rows.push_back(row);
  }
  const auto rangeOf = [&](int row) { return detection.detections[static_cast<std::size_t>(row)].range_m; };
  const auto bearingOf = [&](int row) { return polar.bearing_rad[static_cast<std::size_t>(row)]; };
  std::vector<double> rises;
  for (const int row : rows) rises.push_back(detection.detections[static_cast<std::size_t>(row)].rise_m);
  const double resolution_m = rises.empty() ? 0.0 : std::max(percentile(rises, 0.25), polar.bin_length_m);
  for (std::size_t i = 1; i + 1 < rows.size(); ++i) {
    const int before = rows[i - 1], row = rows[i], after = rows[i + 1];
    const double span_rad = bearingStep_rad(bearingOf(before), bearingOf(after));
    // Neighbours more than two beams away on either side do not describe the same surface.
    if (after - before > 4 || std::abs(span_rad) < 1e-9) continue;
    const double r = rangeOf(row), range_change_m = rangeOf(after) - rangeOf(before);
    // One surface: the range runs one way across the three beams (a corner or a ridge does not).
    if ((rangeOf(row) - rangeOf(before)) * (rangeOf(after) - rangeOf(row)) < 0.0) continue;
    const double incidence_rad = std::atan(range_change_m / (span_rad * r));  // signed: > 0 when the range grows with bearing
    // No farther than a surface at 80° could be (beyond, the neighbours are another surface).
    if (std::abs(incidence_rad) > 80.0 * std::numbers::pi / 180.0) continue;
    const double spread_m = r * std::tan(std::abs(incidence_rad)) * edge_rad;
    const double edge = edge_rad * spread_m / (spread_m + resolution_m);
    turns[static_cast<std::size_t>(row - first_row)] = -std::copysign(std::min(std::abs(incidence_rad), edge), incidence_rad);
  }
  return turns;
}

/// The scan of rows [first_row, last_row) of a sweep's polar image (its first beam `first_beam` in
/// the log); nullopt when its middle beam has no dead-reckoning pose.
std::optional<SonarScan> formScan(const PolarImage& polar, const SweepDetection& detection, int first_row, int last_row,
                                  std::size_t first_beam, const std::optional<NavInterpolator>& nav,
                                  const Eigen::Isometry3d& sonar_to_body, const ScanGeometry& geometry,
                                  const ScanFormingOptions& forming, bool known) {
  SonarScan scan;
  scan.first_beam = first_beam + static_cast<std::size_t>(first_row);
  scan.beams = static_cast<std::size_t>(last_row - first_row);
  scan.start_time_s = polar.time_s[static_cast<std::size_t>(first_row)];
  scan.end_time_s = polar.time_s[static_cast<std::size_t>(last_row - 1)];
  scan.time_s = polar.time_s[static_cast<std::size_t>(first_row + (last_row - first_row) / 2)];
  scan.reach_m = geometry.reach_m;
  const std::optional<Eigen::Isometry3d> reference = deadReckoningAt(nav, scan.time_s);
  if (!reference) return std::nullopt;  // the scan's middle lies outside the navigation
  scan.dead_reckoning = planarPose(*reference);
  const std::vector<double> turns = leadingEdgeTurns(polar, detection, first_row, last_row, geometry.leading_edge_rad);
  for (int row = first_row; row < last_row; ++row) {
    const BeamDetection& hit = detection.detections[static_cast<std::size_t>(row)];
    if (!hit.hasObstacle()) continue;
    const double time_s = polar.time_s[static_cast<std::size_t>(row)];
    const std::optional<Eigen::Isometry3d> body = deadReckoningAt(nav, time_s);
    if (!body) continue;
    const double bearing_rad = polar.bearing_rad[static_cast<std::size_t>(row)] + turns[static_cast<std::size_t>(row - first_row)];
    const Eigen::Vector3d in_sonar(hit.range_m * std::cos(bearing_rad), hit.range_m * std::sin(bearing_rad), 0.0);
    const Eigen::Isometry3d sonar_to_ned = *body * sonar_to_body;
    scan_points::Measurement m;
    m.point_ned_m = sonar_to_ned * in_sonar;
    m.origin_ned_m = sonar_to_ned.translation();
    m.body_to_ned = *body;
    m.time_s = time_s;
    m.range_m = hit.range_m;
    m.range_sigma_m =
        forming.range_sigma_m > 0.0 ? forming.range_sigma_m : std::max({polar.bin_length_m, hit.rise_m / 2.0, 0.02});
    m.bearing_sigma_rad = geometry.bearing_sigma_rad;
    scan_points::appendPoint(scan, m, forming, known);
  }
  return scan;
}

}  // namespace

void ScanFormingOptions::validate() const {
  odometry.validate();
  if (!(std::isfinite(range_sigma_m) && range_sigma_m >= 0.0) ||
      !(std::isfinite(bearing_sigma_rad) && bearing_sigma_rad >= 0.0)) {
    throw ValueError("scan forming: range and bearing sigmas must be ≥ 0");
  }
  if (!(std::isfinite(max_travel_m) && max_travel_m >= 0.0)) {
    throw ValueError("scan forming: max_travel_m must be ≥ 0 m");
  }
}

Pose2 planarPose(const Eigen::Isometry3d& body_to_ned) {
  const Eigen::Matrix3d r = body_to_ned.linear();
  return {body_to_ned.translation().x(), body_to_ned.translation().y(), std::atan2(r(1, 0), r(0, 0))};
}

std::vector<SonarScan> formScans(const SonarLog& log, const NavTrack& dead_reckoning,
                                 const Eigen::Isometry3d& sonar_to_body, const MapperOptions& options,
                                 const ScanFormingOptions& forming) {
  forming.validate();
  return formScans(detectSonarLog(log, options), dead_reckoning, sonar_to_body, forming);
}

std::vector<SonarScan> formScans(const DetectedLog& detected, const NavTrack& dead_reckoning,
                                 const Eigen::Isometry3d& sonar_to_body, const ScanFormingOptions& forming) {
  forming.validate();
  std::optional<NavInterpolator> nav;
  if (!dead_reckoning.empty()) nav.emplace(dead_reckoning);  // throws ValueError for an invalid track
  const bool known = nav.has_value();
  const double beam_width_rad = detected.options.beam_width_rad;

  std::vector<SonarScan> scans;
  for (const DetectedSweep& sweep : detected.sweeps) {
    const PolarImage& polar = sweep.polar;
    const SweepDetection& detection = sweep.detection;
    double step_rad = 0.0;
    if (polar.rows() > 1) step_rad = std::abs(bearingStep_rad(polar.bearing_rad[0], polar.bearing_rad[1]));
    ScanGeometry geometry;
    geometry.bearing_sigma_rad =
        forming.bearing_sigma_rad > 0.0 ? forming.bearing_sigma_rad : std::max(beam_width_rad, step_rad) / 2.0;
    if (forming.leading_edge_bearing) {
      // Where the two-way main lobe (Gaussian: one-way −3 dB at half the width) is leading_edge_db
      // below its axis: half the width at the detector's default 6 dB.
      const double leading_edge_db = detected.options.detector.background.leading_edge_db;
      geometry.leading_edge_rad = beam_width_rad / 2.0 * std::sqrt(leading_edge_db / 6.0);
    }
    for (int row = 0; row < polar.rows(); ++row) {
      geometry.reach_m = std::max(geometry.reach_m, polar.valid_bins[static_cast<std::size_t>(row)] * polar.bin_length_m);
    }
    // A sweep during which the vehicle travels farther than max_travel_m is cut into several scans,
    // each over about that much travel: dead reckoning's drift within a scan stays small.
    const double max_travel_m = forming.max_travel_m > 0.0 ? forming.max_travel_m : geometry.reach_m / 2.0;
    int first_row = 0;
    std::optional<Eigen::Vector2d> start;
    for (int row = 0; row <= polar.rows(); ++row) {
      bool cut = row == polar.rows();
      if (!cut && known) {
        const std::optional<Eigen::Isometry3d> body = deadReckoningAt(nav, polar.time_s[static_cast<std::size_t>(row)]);
        if (body) {
          const Eigen::Vector2d here = body->translation().head<2>();
          if (!start) start = here;
          cut = (here - *start).norm() > max_travel_m && row > first_row;
          if (cut) start = here;
        }
      }
      if (!cut) continue;
      std::optional<SonarScan> scan =
          formScan(polar, detection, first_row, row, sweep.first_beam, nav, sonar_to_body, geometry, forming, known);
      if (scan) scans.push_back(std::move(*scan));
      first_row = row;
    }
  }
  return scans;
}

}  // namespace sonarmap
