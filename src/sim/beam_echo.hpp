#pragma once
/// @file beam_echo.hpp
/// Private to the simulator: the geometric part of one beam's echo (steps 1–3 of
/// msis_simulator.hpp): rays across the aperture, direct echoes and one-bounce multipath, as
/// received energy per range bin before the pulse, the gain and the noise. The beam pattern, the
/// aperture's cells, Lambert's law and the two-way loss are the acoustics layer's
/// (acoustics/beam_pattern.hpp, backscatter.hpp, propagation.hpp); the ray geometry, the footprint's
/// range extent and the multipath glint are the simulator's own.

#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/acoustics/beam_pattern.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap::sim {

/// One direction of the aperture grid, relative to the beam's axis (sonar frame).
struct ApertureRay {
  double horizontal_rad = 0.0;  ///< added to the bearing (clockwise, beam.hpp)
  double elevation_rad = 0.0;   ///< above the horizontal plane of the sonar
  double sin_elevation = 0.0;
  double cos_elevation = 1.0;
  double pattern = 0.0;  ///< one-way pattern p(h) p(v)
  double weight = 0.0;   ///< p(h)² p(v)² cos v, normalised so that the grid's weights add up to 1
};

/// Traces the beams of one head in one scene.
class BeamEchoTracer {
 public:
  /// Keeps references to `scene`, `head` and `echo`: they must outlive the tracer.
  BeamEchoTracer(const Scene& scene, const MsisHeadOptions& head, const EchoModelOptions& echo);

  /// Sets `energy` (head.bins values) to the energy received from each range bin of the beam at
  /// `bearing_rad` (sonar frame) from a head at `sonar_to_map`.
  void trace(const Eigen::Isometry3d& sonar_to_map, double bearing_rad, std::vector<double>& energy) const;

  /// As trace(), the direct echoes only (step 2, no multipath), split by the primitive that
  /// returned them: `energy` gets one vector of head.bins values per scene primitive.
  void traceDirect(const Eigen::Isometry3d& sonar_to_map, double bearing_rad,
                   std::vector<std::vector<double>>& energy) const;

 private:
  struct Beam;     // one beam's pose and axis
  struct RayCell;  // one ray's direction and its derivatives across the ray's cell
  struct DirectEcho;  // where a ray's direct echo lands and how much it brings
  /// The ray's direction and derivatives across its cell (map frame).
  RayCell rayCell(const Beam& beam, const ApertureRay& ray) const;
  /// The ray's direct echo (step 2), or nothing when it meets no surface within the range.
  std::optional<DirectEcho> directEcho(const Beam& beam, const ApertureRay& ray, const RayCell& cell) const;
  /// A ray's direct echo, then its multipath.
  void traceRay(const Beam& beam, const ApertureRay& ray, std::vector<double>& energy) const;
  /// `first_span_m`: the footprint span of the ray's direct echo.
  void traceMultipath(const Beam& beam, const ApertureRay& ray, const RayCell& cell, const SceneHit& first,
                      double first_span_m, std::vector<double>& energy) const;
  /// Range extent of the surface a ray cell meets at `range_m` (at most range_m of the head).
  double footprintSpan(double range_m, const Eigen::Vector3d& normal, const RayCell& cell) const;
  /// One-way receive pattern for an echo arriving along `arrival_map` (unit, map frame, from the
  /// head towards where the echo comes from), never below the side-lobe floor.
  double receivePattern(const Beam& beam, const Eigen::Vector3d& arrival_map) const;
  /// Two-way loss per solid angle over a path of total length path_m, seen at range path_m / 2
  /// (twoWayLossPerSolidAngle), at one bin from the head at least: a surface touching the head
  /// does not blow up.
  double propagationLoss(double path_m) const;
  /// Adds `value` spread evenly over ranges [center_m − span_m/2, center_m + span_m/2].
  void deposit(double center_m, double span_m, double value, std::vector<double>& energy) const;

  SceneRayCaster scene_;
  std::size_t primitive_count_ = 0;
  const MsisHeadOptions& head_;
  const EchoModelOptions& echo_;
  TransducerPattern pattern_;
  std::vector<ApertureRay> rays_;
  double horizontal_step_rad_ = 0.0;
  double vertical_step_rad_ = 0.0;
  double sidelobe_floor_ = 0.0;  // one-way power of the side and back lobes
};

}  // namespace sonarmap::sim
