/// @file forward_model.cpp
/// The forward model of one beam (see forward_model.hpp).

#include "sonarmap/acoustics/forward_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "checks.hpp"
#include "sonarmap/acoustics/backscatter.hpp"
#include "sonarmap/acoustics/propagation.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {

void ForwardModelHead::validate() const {
  using acoustics_checks::nonNegative;
  using acoustics_checks::positive;
  using acoustics_checks::require;
  require(positive(horizontal_width_rad) && horizontal_width_rad < std::numbers::pi,
          "forward model: horizontal_width_rad must be in (0, π) radians", horizontal_width_rad);
  require(positive(vertical_width_rad) && vertical_width_rad < std::numbers::pi,
          "forward model: vertical_width_rad must be in (0, π) radians", vertical_width_rad);
  pattern.validate();
  horizontal.validate();
  vertical.validate();
  require(bins >= 1, "forward model: bins must be at least 1", bins);
  require(positive(range_m), "forward model: range_m must be a finite number > 0", range_m);
  require(nonNegative(absorption_db_per_m), "forward model: absorption_db_per_m must be a finite number ≥ 0",
          absorption_db_per_m);
  require(std::isfinite(lambert_exponent) && lambert_exponent >= 1.0,
          "forward model: lambert_exponent must be a finite number ≥ 1", lambert_exponent);
}

namespace {
const ForwardModelHead& validated(const ForwardModelHead& head) {
  head.validate();
  return head;
}
}  // namespace

BeamForwardModel::BeamForwardModel(const ForwardModelHead& head) : head_(validated(head)) {
  horizontal_step_rad_ = apertureStep_rad(head.horizontal, head.horizontal_width_rad);
  vertical_step_rad_ = apertureStep_rad(head.vertical, head.vertical_width_rad);
  double total_weight = 0.0;
  for (int i = 0; i < head.horizontal.rays; ++i) {
    for (int j = 0; j < head.vertical.rays; ++j) {
      ApertureRay ray;
      ray.horizontal_rad = apertureAngle_rad(head.horizontal, head.horizontal_width_rad, i);
      ray.elevation_rad = apertureAngle_rad(head.vertical, head.vertical_width_rad, j);
      ray.sin_elevation = std::sin(ray.elevation_rad);
      ray.cos_elevation = std::cos(ray.elevation_rad);
      ray.pattern = oneWayPattern(head.pattern, ray.horizontal_rad, ray.elevation_rad);
      // The two-way pattern times the ray's solid angle (cos v dh dv, the cells' dh dv equal).
      ray.weight = ray.pattern * ray.pattern * ray.cos_elevation;
      total_weight += ray.weight;
      rays_.push_back(ray);
    }
  }
  for (ApertureRay& ray : rays_) ray.weight /= total_weight;
}

RayCell RayCell::mirrored(const Eigen::Vector3d& normal) const {
  auto mirror = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d { return v - 2.0 * v.dot(normal) * normal; };
  return {mirror(direction), mirror(d_elevation), mirror(d_azimuth)};
}

RayCell BeamForwardModel::rayCell(const Eigen::Matrix3d& sonar_to_map, double bearing_rad, const ApertureRay& ray) {
  const double azimuth_rad = bearing_rad + ray.horizontal_rad;
  const double sin_v = ray.sin_elevation, cos_v = ray.cos_elevation;
  const double sin_h = std::sin(azimuth_rad), cos_h = std::cos(azimuth_rad);
  return {sonar_to_map * Eigen::Vector3d(cos_v * cos_h, cos_v * sin_h, sin_v),
          sonar_to_map * Eigen::Vector3d(-sin_v * cos_h, -sin_v * sin_h, cos_v),
          sonar_to_map * Eigen::Vector3d(-cos_v * sin_h, cos_v * cos_h, 0.0)};
}

double BeamForwardModel::footprintSpan_m(double range_m, const Eigen::Vector3d& normal, const RayCell& cell) const {
  // On a locally flat surface the range changes across the cell by dr/dα = r (n · ∂u/∂α) / cos θ.
  const double cos_incidence = std::max(-normal.dot(cell.direction), 1e-6);
  const double span_m = range_m / cos_incidence *
                        (std::abs(normal.dot(cell.d_elevation)) * vertical_step_rad_ +
                         std::abs(normal.dot(cell.d_azimuth)) * horizontal_step_rad_);
  return std::min(span_m, head_.range_m);
}

double BeamForwardModel::propagationLoss(double path_m) const {
  return twoWayLossPerSolidAngle(path_m, head_.absorption_db_per_m, head_.binLength_m());
}

double BeamForwardModel::directEchoEnergy(const ApertureRay& ray, const ReflectorHit& hit, const RayCell& cell) const {
  const double cos_incidence = std::max(-hit.normal.dot(cell.direction), 0.0);
  const double backscatter = lambertScatterPerSolidAngle(hit.reflectivity, cos_incidence, head_.lambert_exponent);
  return ray.weight * backscatter * propagationLoss(2.0 * hit.range_m);
}

void BeamForwardModel::deposit(double centre_m, double span_m, double energy_value, std::vector<double>& energy) const {
  const double bin_m = head_.binLength_m();
  const double begin_m = std::max(0.0, centre_m - 0.5 * span_m);
  const double end_m = std::min(head_.range_m, centre_m + 0.5 * span_m);
  if (end_m - begin_m < 1e-3 * bin_m) {  // narrower than a bin: all into the centre's bin
    const auto bin = static_cast<std::size_t>(centre_m / bin_m);
    if (bin < energy.size()) energy[bin] += energy_value;
    return;
  }
  const double density = energy_value / span_m;  // what falls outside [0, range_m] is lost
  const auto first = static_cast<std::size_t>(begin_m / bin_m);
  for (std::size_t bin = first; bin < energy.size() && static_cast<double>(bin) * bin_m < end_m; ++bin) {
    const double overlap_m = std::min(end_m, (bin + 1) * bin_m) - std::max(begin_m, bin * bin_m);
    if (overlap_m > 0.0) energy[bin] += density * overlap_m;
  }
}

ScattererGain::ScattererGain(const TransducerPattern& pattern, double cross_section_m2) {
  pattern.validate();
  acoustics_checks::require(acoustics_checks::nonNegative(cross_section_m2),
                            "forward model: cross_section_m2 must be a finite number ≥ 0", cross_section_m2);
  twice_inverse_h_ = 2.0 / pattern.horizontal.width_rad;
  twice_inverse_v_ = 2.0 / pattern.vertical.width_rad;
  exponent_h_ = pattern.horizontal.exponent;
  exponent_v_ = pattern.vertical.exponent;
  scale_ = cross_section_m2 / equivalentSolidAngle_sr(pattern);
  gaussian_ = exponent_h_ == 2.0 && exponent_v_ == 2.0;
}

double equivalentSolidAngle_sr(const TransducerPattern& pattern) {
  return equivalentBeamWidth_rad(pattern.horizontal) * equivalentBeamWidth_rad(pattern.vertical);
}

std::optional<ReflectorHit> planeHit(const Eigen::Vector3d& point_map, const Eigen::Vector3d& normal_map,
                                   double reflectivity, const Eigen::Vector3d& origin_map,
                                   const Eigen::Vector3d& direction_map, double max_range_m) {
  const double height_m = normal_map.dot(origin_map - point_map);  // > 0: the origin in front
  const double closing = -normal_map.dot(direction_map);            // > 0: the ray runs towards it
  if (!(height_m > 0.0 && closing > 0.0)) return std::nullopt;
  const double range_m = height_m / closing;
  if (!(range_m <= max_range_m)) return std::nullopt;
  return ReflectorHit{range_m, normal_map, reflectivity};
}

}  // namespace sonarmap
