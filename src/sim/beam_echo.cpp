/// @file beam_echo.cpp
/// Rays across the aperture, direct echoes and one-bounce multipath (see beam_echo.hpp).

#include "beam_echo.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sonarmap/acoustics/backscatter.hpp"
#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/acoustics/propagation.hpp"
#include "sonarmap/sim/acoustic_parameters.hpp"

namespace sonarmap::sim {
namespace {

double wrapToPi(double angle_rad) { return std::remainder(angle_rad, 2.0 * std::numbers::pi); }

}  // namespace

struct BeamEchoTracer::Beam {
  Eigen::Vector3d origin_m;      // the head, map frame
  Eigen::Matrix3d sonar_to_map;  // rotation
  double bearing_rad = 0.0;
};

BeamEchoTracer::BeamEchoTracer(const Scene& scene, const MsisHeadOptions& head, const EchoModelOptions& echo)
    : scene_(scene),
      primitive_count_(scene.primitives.size()),
      head_(head),
      echo_(echo),
      pattern_(transducerPatternOf(head, echo)),
      sidelobe_floor_(powerOfLevel(echo.sidelobe_level_db)) {
  const ApertureSampling horizontal = apertureSamplingOf(echo.horizontal);
  const ApertureSampling vertical = apertureSamplingOf(echo.vertical);
  horizontal_step_rad_ = apertureStep_rad(horizontal, head.horizontal_beam_width_rad);
  vertical_step_rad_ = apertureStep_rad(vertical, head.vertical_beam_width_rad);
  double total_weight = 0.0;
  for (int i = 0; i < echo.horizontal.rays; ++i) {
    for (int j = 0; j < echo.vertical.rays; ++j) {
      ApertureRay ray;
      ray.horizontal_rad = apertureAngle_rad(horizontal, head.horizontal_beam_width_rad, i);
      ray.elevation_rad = apertureAngle_rad(vertical, head.vertical_beam_width_rad, j);
      ray.sin_elevation = std::sin(ray.elevation_rad);
      ray.cos_elevation = std::cos(ray.elevation_rad);
      ray.pattern = oneWayPattern(pattern_, ray.horizontal_rad, ray.elevation_rad);
      // The two-way pattern times the ray's solid angle (cos v dh dv, the cells' dh dv equal).
      ray.weight = ray.pattern * ray.pattern * ray.cos_elevation;
      total_weight += ray.weight;
      rays_.push_back(ray);
    }
  }
  for (ApertureRay& ray : rays_) ray.weight /= total_weight;
}

void BeamEchoTracer::trace(const Eigen::Isometry3d& sonar_to_map, double bearing_rad,
                           std::vector<double>& energy) const {
  energy.assign(static_cast<std::size_t>(head_.bins), 0.0);
  const Beam beam{sonar_to_map.translation(), sonar_to_map.linear(), bearing_rad};
  for (const ApertureRay& ray : rays_) traceRay(beam, ray, energy);
}

/// A ray's direction and its derivatives across the ray's angular cell (map frame).
struct BeamEchoTracer::RayCell {
  Eigen::Vector3d direction;
  Eigen::Vector3d d_elevation;  // ∂direction/∂v
  Eigen::Vector3d d_azimuth;    // ∂direction/∂h

  /// The cell after a mirror reflection at a surface of unit normal `normal` (a linear map).
  RayCell mirrored(const Eigen::Vector3d& normal) const {
    auto mirror = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d { return v - 2.0 * v.dot(normal) * normal; };
    return {mirror(direction), mirror(d_elevation), mirror(d_azimuth)};
  }
};

double BeamEchoTracer::footprintSpan(double range_m, const Eigen::Vector3d& normal, const RayCell& cell) const {
  // On a locally flat surface the range changes across the cell by dr/dα = r (n · ∂d/∂α) / cos θ.
  const double cos_incidence = std::max(-normal.dot(cell.direction), 1e-6);
  const double span_m = range_m / cos_incidence *
                        (std::abs(normal.dot(cell.d_elevation)) * vertical_step_rad_ +
                         std::abs(normal.dot(cell.d_azimuth)) * horizontal_step_rad_);
  return std::min(span_m, head_.range_m);
}

BeamEchoTracer::RayCell BeamEchoTracer::rayCell(const Beam& beam, const ApertureRay& ray) const {
  const double azimuth_rad = beam.bearing_rad + ray.horizontal_rad;
  const double sin_v = ray.sin_elevation, cos_v = ray.cos_elevation;
  const double sin_h = std::sin(azimuth_rad), cos_h = std::cos(azimuth_rad);
  return {beam.sonar_to_map * Eigen::Vector3d(cos_v * cos_h, cos_v * sin_h, sin_v),
          beam.sonar_to_map * Eigen::Vector3d(-sin_v * cos_h, -sin_v * sin_h, cos_v),
          beam.sonar_to_map * Eigen::Vector3d(-cos_v * sin_h, cos_v * cos_h, 0.0)};
}

struct BeamEchoTracer::DirectEcho {
  SceneHit hit;
  double span_m = 0.0;  // the footprint's range extent
  double value = 0.0;   // received energy
};

std::optional<BeamEchoTracer::DirectEcho> BeamEchoTracer::directEcho(const Beam& beam, const ApertureRay& ray,
                                                                     const RayCell& cell) const {
  const std::optional<SceneHit> hit = scene_.firstHit(beam.origin_m, cell.direction, head_.range_m);
  if (!hit) return std::nullopt;
  const double range_m = hit->surface.range_m;
  const double cos_incidence = std::max(-hit->surface.normal.dot(cell.direction), 0.0);
  const double backscatter = lambertScatterPerSolidAngle(hit->reflectivity, cos_incidence, echo_.lambert_exponent);
  return DirectEcho{*hit, footprintSpan(range_m, hit->surface.normal, cell),
                    ray.weight * backscatter * propagationLoss(2.0 * range_m)};
}

void BeamEchoTracer::traceRay(const Beam& beam, const ApertureRay& ray, std::vector<double>& energy) const {
  const RayCell cell = rayCell(beam, ray);
  const std::optional<DirectEcho> echo = directEcho(beam, ray, cell);
  if (!echo) return;
  deposit(echo->hit.surface.range_m, echo->span_m, echo->value, energy);
  if (echo_.multipath && echo_.specular_share > 0.0) traceMultipath(beam, ray, cell, echo->hit, echo->span_m, energy);
}

void BeamEchoTracer::traceDirect(const Eigen::Isometry3d& sonar_to_map, double bearing_rad,
                                 std::vector<std::vector<double>>& energy) const {
  energy.assign(primitive_count_, std::vector<double>(static_cast<std::size_t>(head_.bins), 0.0));
  const Beam beam{sonar_to_map.translation(), sonar_to_map.linear(), bearing_rad};
  for (const ApertureRay& ray : rays_) {
    const std::optional<DirectEcho> echo = directEcho(beam, ray, rayCell(beam, ray));
    if (echo) deposit(echo->hit.surface.range_m, echo->span_m, echo->value, energy[echo->hit.primitive]);
  }
}

void BeamEchoTracer::traceMultipath(const Beam& beam, const ApertureRay& ray, const RayCell& cell,
                                    const SceneHit& first, double first_span_m, std::vector<double>& energy) const {
  const double first_m = first.surface.range_m;
  const Eigen::Vector3d bounce_point_m = beam.origin_m + first_m * cell.direction;
  const RayCell bounced = cell.mirrored(first.surface.normal);
  const std::optional<SceneHit> second =
      scene_.firstHit(bounce_point_m, bounced.direction, 2.0 * head_.range_m - first_m);
  if (!second) return;
  const double second_m = second->surface.range_m;
  const Eigen::Vector3d scatter_point_m = bounce_point_m + second_m * bounced.direction;
  const Eigen::Vector3d to_head = beam.origin_m - scatter_point_m;
  const double back_m = to_head.norm();
  const double path_m = first_m + second_m + back_m;
  if (0.5 * path_m >= head_.range_m || back_m <= 0.0) return;
  const Eigen::Vector3d back_direction = to_head / back_m;
  const Eigen::Vector3d& normal = second->surface.normal;  // faces the bounced ray
  const double cos_out = normal.dot(back_direction);
  if (cos_out <= 0.0) return;  // the head is behind the second surface
  if (scene_.firstHit(beam.origin_m, -back_direction, back_m * (1.0 - 1e-6))) return;  // shadowed
  const Eigen::Vector3d second_mirror = bounced.direction - 2.0 * bounced.direction.dot(normal) * normal;
  const double glint_angle_rad = std::acos(std::clamp(second_mirror.dot(back_direction), -1.0, 1.0));
  const double glint = echo_.glint_gain * std::exp(-0.5 * std::pow(glint_angle_rad / echo_.glint_width_rad, 2.0));
  // Transmit pattern × receive pattern (in the direction the echo arrives from) × cos v.
  const double weight = ray.weight / ray.pattern * receivePattern(beam, -back_direction);
  const double scatter = first.reflectivity * echo_.specular_share * second->reflectivity * (cos_out + glint);
  // The double-bounce path varies across the cell less than either surface's footprint (not at
  // all for a corner reflector): spread it over the smaller of the two.
  const double span_m = std::min(first_span_m, footprintSpan(first_m + second_m, normal, bounced));
  deposit(0.5 * path_m, span_m, weight * scatter * propagationLoss(path_m), energy);
}

double BeamEchoTracer::receivePattern(const Beam& beam, const Eigen::Vector3d& arrival_map) const {
  const Eigen::Vector3d arrival = beam.sonar_to_map.transpose() * arrival_map;
  const double main_lobe = oneWayPattern(pattern_, wrapToPi(std::atan2(arrival.y(), arrival.x()) - beam.bearing_rad),
                                         std::asin(std::clamp(arrival.z(), -1.0, 1.0)));
  return std::max(main_lobe, sidelobe_floor_);  // the side and back lobes hear the rest
}

double BeamEchoTracer::propagationLoss(double path_m) const {
  return twoWayLossPerSolidAngle(path_m, echo_.absorption_db_per_m, head_.binLength_m());
}

void BeamEchoTracer::deposit(double center_m, double span_m, double value, std::vector<double>& energy) const {
  const double bin_m = head_.binLength_m();
  const double begin_m = std::max(0.0, center_m - 0.5 * span_m);
  const double end_m = std::min(head_.range_m, center_m + 0.5 * span_m);
  if (end_m - begin_m < 1e-3 * bin_m) {  // narrower than a bin: all into the centre's bin
    const auto bin = static_cast<std::size_t>(center_m / bin_m);
    if (bin < energy.size()) energy[bin] += value;
    return;
  }
  const double density = value / span_m;  // what falls outside [0, range_m] is lost
  const auto first = static_cast<std::size_t>(begin_m / bin_m);
  for (std::size_t bin = first; bin < energy.size() && static_cast<double>(bin) * bin_m < end_m; ++bin) {
    const double overlap_m = std::min(end_m, (bin + 1) * bin_m) - std::max(begin_m, bin * bin_m);
    if (overlap_m > 0.0) energy[bin] += density * overlap_m;
  }
}

}  // namespace sonarmap::sim
