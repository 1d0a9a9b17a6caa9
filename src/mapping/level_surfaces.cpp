/// @file level_surfaces.cpp
/// Level surfaces mapped from the pooled looks of every beam (see level_surfaces.hpp).

#include "sonarmap/mapping/level_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

LevelSurfaceEvidence::LevelSurfaceEvidence(double resolution_m, double level_db, double false_alarm)
    : resolution_m_(resolution_m) {
  if (!(std::isfinite(resolution_m) && resolution_m > 0.0)) {
    throw ValueError("level surface: resolution_m must be a finite number > 0, got " + std::to_string(resolution_m));
  }
  if (!std::isfinite(level_db)) throw ValueError("level surface: level_db must be finite");
  if (!(false_alarm > 0.0 && false_alarm < 0.5)) {
    throw ValueError("level surface: false_alarm must be in (0, 0.5), got " + std::to_string(false_alarm));
  }
  surface_mean_ = 1.0 + std::pow(10.0, level_db / 10.0);
  heard_evidence_ = -std::log(false_alarm);
}

std::uint64_t LevelSurfaceEvidence::columnOf(const Eigen::Vector3d& point_m) const {
  const auto x = static_cast<std::int64_t>(std::floor(point_m.x() / resolution_m_));
  const auto y = static_cast<std::int64_t>(std::floor(point_m.y() / resolution_m_));
  return (static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xFFFFFFFFu);
}

void LevelSurfaceEvidence::addLook(const Eigen::Vector3d& point_m, double evidence_nats,
                                   std::vector<std::uint64_t>& looked) {
  const std::uint64_t key = columnOf(point_m);
  // One cell is one look at a column, however many of its directions land in it.
  if (std::find(looked.begin(), looked.end(), key) != looked.end()) return;
  looked.push_back(key);
  Column& column = columns_[key];
  if (column.heard) return;
  column.evidence += evidence_nats;
  column.point_m = point_m;
  if (column.evidence >= heard_evidence_) {
    column.heard = true;
    ++heard_;
    newly_heard_.push_back(key);
  }
}

void LevelSurfaceEvidence::addBeam(const Eigen::Isometry3d& sonar_to_map, double bearing_rad, double width_rad,
                                   double aperture_rad, std::span<const float> cell_power, double bins_per_cell,
                                   const LevelPlane& plane) {
  if (!(std::isfinite(bins_per_cell) && bins_per_cell >= 1.0)) {
    throw ValueError("level surface: bins_per_cell must be a finite number ≥ 1, got " + std::to_string(bins_per_cell));
  }
  const double log_mean = std::log(surface_mean_), gain = 1.0 - 1.0 / surface_mean_;
  const Eigen::Vector3d origin_m = sonar_to_map.translation();
  const double height_m = plane.normal.dot(origin_m - plane.point_m);  // D: the head over the plane
  if (!(height_m > 0.0)) return;
  const Eigen::Matrix3d& rotation = sonar_to_map.linear();
  const double half_aperture_rad = 0.5 * aperture_rad;
  const double b = plane.normal.dot(rotation.col(2));  // n · R z_sonar
  for (std::size_t k = 0; k < cell_power.size(); ++k) {
    const double power = cell_power[k];
    if (std::isnan(power)) continue;
    const double range_m = (static_cast<double>(k) + 0.5) * resolution_m_;
    if (range_m <= height_m) continue;  // the shell does not reach the plane
    const double c = -height_m / range_m;
    const double evidence_nats = bins_per_cell * (power * gain - log_mean);  // λ of the file's comment
    looked_.clear();
    // Directions across the width at most a voxel apart at this range.
    const int across = std::max(1, static_cast<int>(std::ceil(width_rad * range_m / resolution_m_)));
    for (int i = 0; i < across; ++i) {
      const double phi_rad = bearing_rad + width_rad * ((i + 0.5) / across - 0.5);
      const Eigen::Vector3d level = rotation * Eigen::Vector3d(std::cos(phi_rad), std::sin(phi_rad), 0.0);
      const double a = plane.normal.dot(level);
      const double amplitude = std::hypot(a, b);
      if (!(amplitude > std::abs(c))) continue;
      const double phase_rad = std::atan2(b, a);
      const double spread_rad = std::acos(c / amplitude);
      for (const double e_rad : {phase_rad + spread_rad, phase_rad - spread_rad}) {
        const double wrapped_rad = std::remainder(e_rad, 2.0 * std::numbers::pi);
        if (std::abs(wrapped_rad) > half_aperture_rad) continue;
        const Eigen::Vector3d direction = rotation * Eigen::Vector3d(std::cos(wrapped_rad) * std::cos(phi_rad),
                                                                    std::cos(wrapped_rad) * std::sin(phi_rad),
                                                                    std::sin(wrapped_rad));
        addLook(origin_m + range_m * direction, evidence_nats, looked_);
      }
    }
  }
}

}  // namespace sonarmap
