#pragma once
/// @file forward_model.hpp
/// The forward model of one beam: the expected energy of each range bin, before the pulse, the
/// gain, speckle and noise, given the surfaces around the head. The simulator makes its echoes with
/// it (sim/msis_simulator.hpp, steps 1–3) and the 3D mapper inverts it.
///
/// The aperture is a grid of directions (ApertureSampling over each plane): the ray of cell j at
/// horizontal angle h_j and elevation v_j carries the weight
///     w_j = p_h(h_j)² p_v(v_j)² cos v_j / Σ_i p_h(h_i)² p_v(v_i)² cos v_i
/// (the two-way pattern times the cell's solid angle, beam_pattern.hpp), so that a reflector of
/// reflectivity 1 filling the beam at normal incidence returns 1 after the TVG (sonar_equation.hpp's
/// units, once the TVG of propagation.hpp has given back r² and the absorption). A ray meeting a surface of reflectivity ρ at range r and incidence cos θ brings
///     E_j = w_j · ρ cos^(k−1) θ · 10^(−α·2r/10) / r²
/// (lambertScatterPerSolidAngle × twoWayLossPerSolidAngle: Lambert's law, spherical spreading and
/// absorption; Urick 1983 ch. 2 and 8), spread evenly over the range its cell's footprint spans
/// on the surface, r/cos θ · (|n·∂u/∂v| Δv + |n·∂u/∂h| Δh) (the surface taken flat across the cell,
/// u the ray's direction, n the normal). A level surface is sampled the same way; its closed form
/// for a flat seabed is flatSeabedEchoPower (sonar_equation.hpp), which this model reproduces
/// (tests/acoustics/test_forward_model.cpp).
///
/// Frames: the sonar frame of sonar/beam.hpp (FRD: x the head's ahead, y starboard, z down; bearing
/// clockwise seen from above; a ray of elevation v leans towards the sonar frame's +z by v, the
/// pattern being symmetric in v) and the map frame of the pose `sonar_to_map`. Ranges in metres,
/// angles in radians.

#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/acoustics/beam_pattern.hpp"

namespace sonarmap {

/// What the forward model needs of a head.
struct ForwardModelHead {
  double horizontal_width_rad = 0.0;  ///< −3 dB horizontal beam width, (0, π)
  double vertical_width_rad = 0.0;    ///< −3 dB vertical aperture, (0, π)
  TransducerPattern pattern;          ///< the one-way patterns of both planes (widths as above)
  ApertureSampling horizontal;        ///< the aperture's cells across the bearing
  ApertureSampling vertical;          ///< the aperture's cells in elevation
  int bins = 0;                       ///< range bins of a beam, ≥ 1
  double range_m = 0.0;               ///< the beam's range (bins × bin length), > 0
  double absorption_db_per_m = 0.0;   ///< α, one-way, ≥ 0
  double lambert_exponent = 2.0;      ///< k, ≥ 1 (backscatter.hpp)

  double binLength_m() const { return range_m / bins; }
  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// One direction of the aperture grid, relative to the beam's axis (sonar frame).
struct ApertureRay {
  double horizontal_rad = 0.0;  ///< added to the bearing (clockwise)
  double elevation_rad = 0.0;   ///< out of the plane the head turns in, towards the sonar frame's +z
  double sin_elevation = 0.0;
  double cos_elevation = 1.0;
  double pattern = 0.0;  ///< one-way pattern p_h(h) p_v(v)
  double weight = 0.0;   ///< w_j of the file's comment: the grid's weights add up to 1
};

/// A ray's direction and its derivatives across the ray's cell, map frame.
struct RayCell {
  Eigen::Vector3d direction;
  Eigen::Vector3d d_elevation;  ///< ∂direction/∂v
  Eigen::Vector3d d_azimuth;    ///< ∂direction/∂h

  /// The cell after a mirror reflection at a surface of unit normal `normal` (a linear map).
  RayCell mirrored(const Eigen::Vector3d& normal) const;
};

/// Where a ray meets a surface: its range, the surface's unit normal (map frame, facing the ray)
/// and reflectivity ρ ∈ [0, 1].
struct ReflectorHit {
  double range_m = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double reflectivity = 0.0;
};

/// The forward model of one head (see the file's comment).
class BeamForwardModel {
 public:
  /// @throws ValueError for an invalid head.
  explicit BeamForwardModel(const ForwardModelHead& head);

  const ForwardModelHead& head() const { return head_; }
  /// The aperture's rays, horizontal cells outer, vertical inner.
  const std::vector<ApertureRay>& rays() const { return rays_; }
  double horizontalStep_rad() const { return horizontal_step_rad_; }
  double verticalStep_rad() const { return vertical_step_rad_; }

  /// The cell of `ray` of the beam at `bearing_rad` of a head whose rotation is `sonar_to_map`.
  static RayCell rayCell(const Eigen::Matrix3d& sonar_to_map, double bearing_rad, const ApertureRay& ray);

  /// Range extent of a flat surface of unit normal `normal` that `cell` meets at `range_m`: at
  /// most the head's range.
  double footprintSpan_m(double range_m, const Eigen::Vector3d& normal, const RayCell& cell) const;

  /// Two-way loss per solid angle over a path of length `path_m` heard at range path / 2, never
  /// nearer than one bin (twoWayLossPerSolidAngle).
  double propagationLoss(double path_m) const;

  /// E_j of the file's comment for `ray` meeting `hit`.
  double directEchoEnergy(const ApertureRay& ray, const ReflectorHit& hit, const RayCell& cell) const;

  /// Adds `energy_value` spread evenly over ranges [centre − span/2, centre + span/2] to `energy`
  /// (one value per bin; what falls outside [0, range] is lost; narrower than a thousandth of a bin:
  /// all into the centre's bin).
  void deposit(double centre_m, double span_m, double energy_value, std::vector<double>& energy) const;

  /// The expected energy per bin (head().bins values, replacing `energy`'s contents) of the beam at
  /// `bearing_rad` of a head at `sonar_to_map`, from the direct echoes of the surfaces `first_hit`
  /// finds: first_hit(origin_map, direction_map, max_range_m) → std::optional<ReflectorHit>, the
  /// nearest surface along the ray.
  template <class FirstHit>
  void directEchoes(const Eigen::Isometry3d& sonar_to_map, double bearing_rad, FirstHit&& first_hit,
                    std::vector<double>& energy) const {
    energy.assign(static_cast<std::size_t>(head_.bins), 0.0);
    const Eigen::Vector3d origin = sonar_to_map.translation();
    for (const ApertureRay& ray : rays_) {
      const RayCell cell = rayCell(sonar_to_map.linear(), bearing_rad, ray);
      const std::optional<ReflectorHit> hit = first_hit(origin, cell.direction, head_.range_m);
      if (!hit) continue;
      deposit(hit->range_m, footprintSpan_m(hit->range_m, hit->normal, cell), directEchoEnergy(ray, *hit, cell), energy);
    }
  }

 private:
  ForwardModelHead head_;
  std::vector<ApertureRay> rays_;
  double horizontal_step_rad_ = 0.0;
  double vertical_step_rad_ = 0.0;
};

/// The echo of a small scatterer (a voxel of a surface, a pile's patch) in the units of the file's
/// comment, for many scatterers of one cross-section and one pattern (checked once: for the
/// mapper's inner loops): p_h(h)² p_v(v)² · σ / (r² Ω) at range r in direction (h, v) from the
/// beam's axis, σ the cross-section (ρ cos^k θ · A of surfaceEchoPower, sonar_equation.hpp), Ω the
/// beam's two-way equivalent solid angle (equivalentSolidAngle_sr). The mapper's inversion
/// (mapping/volume_inversion.hpp) explains each range cell as the water plus a sum of these.
class ScattererGain {
 public:
  /// @throws ValueError for an invalid pattern or a cross-section not ≥ 0 and finite.
  ScattererGain(const TransducerPattern& pattern, double cross_section_m2);
  /// The echo at `range_m` (> 0; not checked) in direction (`horizontal_rad`, `elevation_rad`).
  double operator()(double horizontal_rad, double elevation_rad, double range_m) const noexcept {
    return twoWay(horizontal_rad, elevation_rad) * scale_ / (range_m * range_m);
  }
  /// The two-way pattern p_h(h)² p_v(v)² of that direction (2^−2|2θ/W|^n per plane).
  double twoWay(double horizontal_rad, double elevation_rad) const noexcept {
    const double h = std::abs(horizontal_rad * twice_inverse_h_), v = std::abs(elevation_rad * twice_inverse_v_);
    if (gaussian_) return std::exp2(-2.0 * (h * h + v * v));
    return std::exp2(-2.0 * (std::pow(h, exponent_h_) + std::pow(v, exponent_v_)));
  }

 private:
  double twice_inverse_h_, twice_inverse_v_, exponent_h_, exponent_v_, scale_;
  bool gaussian_;  ///< both exponents 2
};

/// The two-way equivalent solid angle Ω = ∫ p_h² p_v² dΩ of a pattern, steradians: the product of
/// both planes' equivalent widths (equivalentBeamWidth_rad; cos v ≈ 1 over the narrow plane's
/// width, Urick 1983 ch. 8).
/// @throws ValueError for an invalid pattern.
double equivalentSolidAngle_sr(const TransducerPattern& pattern);

/// The nearest hit of a ray on the plane through `point_map` with unit normal `normal_map` and
/// reflectivity `reflectivity`, seen from its front side (the normal towards the ray's origin),
/// within `max_range_m`; nothing when the ray runs parallel to it, away from it, or the origin lies
/// behind it. The forward model's simplest surface (a level seabed: normal +z up in the map).
std::optional<ReflectorHit> planeHit(const Eigen::Vector3d& point_map, const Eigen::Vector3d& normal_map,
                                   double reflectivity, const Eigen::Vector3d& origin_map,
                                   const Eigen::Vector3d& direction_map, double max_range_m);

}  // namespace sonarmap
