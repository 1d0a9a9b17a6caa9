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
      model_(forwardModelHeadOf(head, echo)),
      sidelobe_floor_(powerOfLevel(echo.sidelobe_level_db)) {}

void BeamEchoTracer::trace(const Eigen::Isometry3d& sonar_to_map, double bearing_rad,
                           std::vector<double>& energy) const {
  energy.assign(static_cast<std::size_t>(head_.bins), 0.0);
  const Beam beam{sonar_to_map.translation(), sonar_to_map.linear(), bearing_rad};
  for (const ApertureRay& ray : model_.rays()) traceRay(beam, ray, energy);
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
  const ReflectorHit surface{hit->surface.range_m, hit->surface.normal, hit->reflectivity};
  return DirectEcho{*hit, model_.footprintSpan_m(surface.range_m, surface.normal, cell),
                    model_.directEchoEnergy(ray, surface, cell)};
}

void BeamEchoTracer::traceRay(const Beam& beam, const ApertureRay& ray, std::vector<double>& energy) const {
  const RayCell cell = BeamForwardModel::rayCell(beam.sonar_to_map, beam.bearing_rad, ray);
  const std::optional<DirectEcho> echo = directEcho(beam, ray, cell);
  if (!echo) return;
  model_.deposit(echo->hit.surface.range_m, echo->span_m, echo->value, energy);
  if (echo_.multipath && echo_.specular_share > 0.0) traceMultipath(beam, ray, cell, echo->hit, echo->span_m, energy);
}

void BeamEchoTracer::traceDirect(const Eigen::Isometry3d& sonar_to_map, double bearing_rad,
                                 std::vector<std::vector<double>>& energy) const {
  energy.assign(primitive_count_, std::vector<double>(static_cast<std::size_t>(head_.bins), 0.0));
  const Beam beam{sonar_to_map.translation(), sonar_to_map.linear(), bearing_rad};
  for (const ApertureRay& ray : model_.rays()) {
    const std::optional<DirectEcho> echo = directEcho(beam, ray, BeamForwardModel::rayCell(beam.sonar_to_map, beam.bearing_rad, ray));
    if (echo) model_.deposit(echo->hit.surface.range_m, echo->span_m, echo->value, energy[echo->hit.primitive]);
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
  const double span_m = std::min(first_span_m, model_.footprintSpan_m(first_m + second_m, normal, bounced));
  model_.deposit(0.5 * path_m, span_m, weight * scatter * model_.propagationLoss(path_m), energy);
}

double BeamEchoTracer::receivePattern(const Beam& beam, const Eigen::Vector3d& arrival_map) const {
  const Eigen::Vector3d arrival = beam.sonar_to_map.transpose() * arrival_map;
  const double main_lobe = oneWayPattern(model_.head().pattern, wrapToPi(std::atan2(arrival.y(), arrival.x()) - beam.bearing_rad),
                                         std::asin(std::clamp(arrival.z(), -1.0, 1.0)));
  return std::max(main_lobe, sidelobe_floor_);  // the side and back lobes hear the rest
}

}  // namespace sonarmap::sim
