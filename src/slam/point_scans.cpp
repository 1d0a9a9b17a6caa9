/// @file point_scans.cpp
/// Point-scan CSV and the SLAM back end on point scans (point_scans.hpp).

#include "sonarmap/slam/point_scans.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>

#include "sonarmap/core/errors.hpp"
#include "../io/csv_fields.hpp"
#include "sonarmap/io/text_input.hpp"
#include "scan_points.hpp"

namespace sonarmap {
namespace {

constexpr std::string_view kColumns[] = {"scan", "time_s", "x_m", "y_m"};
constexpr std::string_view kHeader = "scan,time_s,x_m,y_m";
/// The largest scan number: every integer up to it is a double exactly.
constexpr double kLargestScan = 9007199254740992.0;  // 2^53

/// Why `next` may not follow `previous` in a point-scan file; empty when it may.
std::string orderProblem(const BodyPoint& previous, const BodyPoint& next) {
  if (next.scan < previous.scan) {
    return "scan " + std::to_string(next.scan) + " after scan " + std::to_string(previous.scan) +
           ": scans must come in increasing number, each scan's rows together";
  }
  if (next.time_s < previous.time_s) {
    return csv::formatNumber(next.time_s) + " s is earlier than the row before (" + csv::formatNumber(previous.time_s) +
           " s); times must not decrease";
  }
  return {};
}

/// Which of the points [first, last) of one scan are the leading edges of their echoes. A beam's
/// echo above a detector's threshold often spans several bins: a user's detections may list every
/// one, a radial streak behind the surface. The surface is where the sound first met it, the
/// echo's nearest point (the leading edge: what the beam detector of `map --slam` reports, one
/// point per beam). Points of one echo share their beam's time and line of sight from the body's
/// origin; they follow one another along it within 3 range σ, the range resolution's limit for
/// telling two returns apart, and lie within one range σ of the line through the nearest. Points at
/// one time that are farther apart (a second target behind a gap, or another bearing) start echoes
/// of their own.
std::vector<bool> leadingEdges(const std::vector<BodyPoint>& points, std::size_t first, std::size_t last,
                               double range_sigma_m) {
  std::vector<bool> keep(last - first, true);
  struct Echo {
    Eigen::Vector2d direction;  // unit vector of the leading edge's line of sight
    double last_range_m;        // range of the echo's farthest point so far
  };
  for (std::size_t begin = first; begin < last;) {
    std::size_t end = begin + 1;
    while (end < last && points[end].time_s == points[begin].time_s) ++end;
    if (end - begin > 1) {
      std::vector<std::size_t> by_range(end - begin);
      for (std::size_t i = 0; i < by_range.size(); ++i) by_range[i] = begin + i;
      std::sort(by_range.begin(), by_range.end(),
                [&](std::size_t a, std::size_t b) { return points[a].xy_m.norm() < points[b].xy_m.norm(); });
      // The echoes found so far by the bearing of their line of sight, for the few near a point's.
      std::multimap<double, Echo> echoes;
      for (const std::size_t i : by_range) {
        const Eigen::Vector2d& xy = points[i].xy_m;
        const double range_m = xy.norm();
        const double bearing_rad = std::atan2(xy.y(), xy.x());
        const double window_rad = range_m > range_sigma_m ? std::asin(range_sigma_m / range_m) : std::numbers::pi;
        bool continues = false;
        for (const double shift : {0.0, -2.0 * std::numbers::pi, 2.0 * std::numbers::pi}) {  // across ±π
          const auto lower = echoes.lower_bound(bearing_rad + shift - window_rad);
          const auto upper = echoes.upper_bound(bearing_rad + shift + window_rad);
          for (auto it = lower; it != upper && !continues; ++it) {
            Echo& echo = it->second;
            const double across_m = std::abs(echo.direction.x() * xy.y() - echo.direction.y() * xy.x());
            if (range_m - echo.last_range_m <= 3.0 * range_sigma_m && across_m <= range_sigma_m) {
              echo.last_range_m = range_m;
              continues = true;
            }
          }
        }
        if (continues) {
          keep[i - first] = false;
        } else {
          echoes.emplace(bearing_rad, Echo{range_m > 0.0 ? Eigen::Vector2d(xy / range_m) : Eigen::Vector2d::UnitX(), range_m});
        }
      }
    }
    begin = end;
  }
  return keep;
}

}  // namespace

std::vector<BodyPoint> readPointScans(std::istream& in, const std::string& source) {
  csv::LineReader reader(in, source);
  if (!reader.next()) reader.failFile("empty, expected the header row " + std::string(kHeader));
  for (std::size_t c = 0; c < std::size(kColumns); ++c) reader.expectName(c, kColumns[c]);
  if (reader.fields().size() != std::size(kColumns)) {
    reader.fail("header has " + std::to_string(reader.fields().size()) + " columns, expected exactly " +
                std::string(kHeader));
  }
  std::vector<BodyPoint> points;
  while (reader.next()) {
    if (reader.fields().size() != std::size(kColumns)) {
      reader.fail(std::to_string(reader.fields().size()) + " field(s), expected 4: " + std::string(kHeader));
    }
    const double scan = reader.finiteNumber(0, kColumns[0], "a scan number");
    if (!(scan >= 0.0 && scan <= kLargestScan && std::floor(scan) == scan)) {
      reader.failField(0, kColumns[0], "expected an integer in [0, 2^53], got " + csv::formatNumber(scan));
    }
    BodyPoint point;
    point.scan = static_cast<std::size_t>(scan);
    point.time_s = reader.finiteNumber(1, kColumns[1], "seconds");
    point.xy_m = Eigen::Vector2d(reader.finiteNumber(2, kColumns[2], "metres"), reader.finiteNumber(3, kColumns[3], "metres"));
    if (!points.empty()) {
      const std::string problem = orderProblem(points.back(), point);
      if (!problem.empty()) reader.fail(problem);
    }
    points.push_back(point);
  }
  if (points.empty()) reader.failFile("no points: only the header row");
  return points;
}

std::vector<BodyPoint> readPointScansCsv(const std::string& path) {
  const std::unique_ptr<std::istream> in = openTextInput(path);
  return readPointScans(*in, path);
}

void checkPointScans(const std::vector<BodyPoint>& points) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const BodyPoint& point = points[i];
    if (!(std::isfinite(point.time_s) && point.xy_m.allFinite()) || static_cast<double>(point.scan) > kLargestScan) {
      throw ValueError("point scans: point " + std::to_string(i) + " holds a value that is not finite or a scan beyond 2^53");
    }
    if (i > 0) {
      const std::string problem = orderProblem(points[i - 1], point);
      if (!problem.empty()) throw ValueError("point scans: point " + std::to_string(i) + ": " + problem);
    }
  }
}

void writePointScans(std::ostream& out, const std::vector<BodyPoint>& points) {
  checkPointScans(points);
  std::string text(kHeader);
  text += '\n';
  for (const BodyPoint& point : points) {
    text += std::to_string(point.scan);
    for (const double value : {point.time_s, point.xy_m.x(), point.xy_m.y()}) {
      text += ',';
      csv::appendNumber(text, value);
    }
    text += '\n';
  }
  out << text;
}

std::vector<BodyPoint> pointScansOf(const DetectedLog& detected, const Eigen::Isometry3d& sonar_to_body) {
  std::vector<BodyPoint> points;
  for (std::size_t s = 0; s < detected.sweeps.size(); ++s) {
    const DetectedSweep& sweep = detected.sweeps[s];
    for (std::size_t row = 0; row < sweep.detection.detections.size(); ++row) {
      const BeamDetection& hit = sweep.detection.detections[row];
      if (!hit.hasObstacle()) continue;
      const double bearing_rad = sweep.polar.bearing_rad[row];
      const Eigen::Vector3d in_body =
          sonar_to_body * Eigen::Vector3d(hit.range_m * std::cos(bearing_rad), hit.range_m * std::sin(bearing_rad), 0.0);
      points.push_back({s, sweep.polar.time_s[row], in_body.head<2>()});
    }
  }
  return points;
}

void PointScanOptions::validate() const {
  if (!(std::isfinite(range_sigma_m) && range_sigma_m > 0.0)) {
    throw ValueError("point scans: the range sigma must be > 0 m, got " + std::to_string(range_sigma_m));
  }
  if (!(std::isfinite(bearing_sigma_rad) && bearing_sigma_rad > 0.0)) {
    throw ValueError("point scans: the bearing sigma must be > 0 rad, got " + std::to_string(bearing_sigma_rad));
  }
}

std::vector<SonarScan> formPointScans(const std::vector<BodyPoint>& points, const NavTrack& dead_reckoning,
                                      const PointScanOptions& options, const ScanFormingOptions& forming) {
  options.validate();
  forming.validate();
  checkPointScans(points);
  std::optional<NavInterpolator> nav;
  if (!dead_reckoning.empty()) nav.emplace(dead_reckoning);  // throws ValueError for an invalid track
  const bool known = nav.has_value();
  std::vector<SonarScan> scans;
  for (std::size_t first = 0; first < points.size();) {
    std::size_t last = first + 1;
    while (last < points.size() && points[last].scan == points[first].scan) ++last;
    SonarScan scan;
    scan.first_beam = first;  // the scan's first row of the file
    scan.beams = last - first;
    scan.start_time_s = points[first].time_s;
    scan.end_time_s = points[last - 1].time_s;
    scan.time_s = points[first + (last - first) / 2].time_s;
    const std::optional<Eigen::Isometry3d> reference = scan_points::deadReckoningAt(nav, scan.time_s);
    if (reference) {
      scan.dead_reckoning = planarPose(*reference);
      const std::vector<bool> leading = leadingEdges(points, first, last, options.range_sigma_m);
      for (std::size_t i = first; i < last; ++i) {
        if (!leading[i - first]) {
          ++scan.points_behind_echoes;
          continue;
        }
        const BodyPoint& point = points[i];
        const std::optional<Eigen::Isometry3d> body = scan_points::deadReckoningAt(nav, point.time_s);
        if (!body) continue;
        scan_points::Measurement m;
        m.point_ned_m = *body * Eigen::Vector3d(point.xy_m.x(), point.xy_m.y(), 0.0);
        m.origin_ned_m = body->translation();
        m.body_to_ned = *body;
        m.time_s = point.time_s;
        m.range_m = point.xy_m.norm();
        m.range_sigma_m = options.range_sigma_m;
        m.bearing_sigma_rad = options.bearing_sigma_rad;
        scan.reach_m = std::max(scan.reach_m, m.range_m);
        scan_points::appendPoint(scan, m, forming, known);
      }
      scans.push_back(std::move(scan));
    }
    first = last;
  }
  return scans;
}

SlamResult localizePointScans(const std::vector<BodyPoint>& points, const NavTrack& dead_reckoning,
                              const PointScanOptions& options, const SlamOptions& slam) {
  slam.validate();
  const SlamOptions tuned = withNavigationPeriod(slam, dead_reckoning);
  std::vector<SonarScan> scans = formPointScans(points, dead_reckoning, options, tuned.forming);
  std::size_t behind = 0;
  for (const SonarScan& scan : scans) behind += scan.points_behind_echoes;
  SlamResult result = localizeScans(std::move(scans), dead_reckoning, tuned);
  result.report.points_behind_echoes = behind;
  return result;
}

}  // namespace sonarmap
