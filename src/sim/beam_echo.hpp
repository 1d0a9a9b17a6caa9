#pragma once
/// @file beam_echo.hpp
/// Private to the simulator: the geometric part of one beam's echo (steps 1–3 of
/// msis_simulator.hpp): rays across the aperture, direct echoes and one-bounce multipath, as
/// received energy per range bin before the pulse, the gain and the noise. The direct echoes are
/// the forward model's (acoustics/forward_model.hpp: the aperture's rays, Lambert's law, the two-way
/// loss, the footprint's range extent) on the scene's surfaces; the multipath glint is the
/// simulator's own.

#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/acoustics/forward_model.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap::sim {

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
  struct DirectEcho;  // where a ray's direct echo lands and how much it brings
  /// The ray's direct echo (step 2), or nothing when it meets no surface within the range.
  std::optional<DirectEcho> directEcho(const Beam& beam, const ApertureRay& ray, const RayCell& cell) const;
  /// A ray's direct echo, then its multipath.
  void traceRay(const Beam& beam, const ApertureRay& ray, std::vector<double>& energy) const;
  /// `first_span_m`: the footprint span of the ray's direct echo.
  void traceMultipath(const Beam& beam, const ApertureRay& ray, const RayCell& cell, const SceneHit& first,
                      double first_span_m, std::vector<double>& energy) const;
  /// One-way receive pattern for an echo arriving along `arrival_map` (unit, map frame, from the
  /// head towards where the echo comes from), never below the side-lobe floor.
  double receivePattern(const Beam& beam, const Eigen::Vector3d& arrival_map) const;

  SceneRayCaster scene_;
  std::size_t primitive_count_ = 0;
  const MsisHeadOptions& head_;
  const EchoModelOptions& echo_;
  BeamForwardModel model_;
  double sidelobe_floor_ = 0.0;  // one-way power of the side and back lobes
};

}  // namespace sonarmap::sim
