#pragma once
/// @file sonar_equation.hpp
/// The sonar equation of an extended surface, in the units of an echo model normalised to its
/// beam, and its closed form for a flat seabed under a level or tilted head.
///
/// Echo level of an extended surface (Urick, "Principles of Underwater Sound", 3rd ed. 1983,
/// ch. 2 and ch. 8, boundary reverberation): EL = SL − 2 TL + S_b + 10 log10 A, with S_b the
/// backscattering strength per unit area (backscatter.hpp) and A the ensonified area
/// (ensonified_area.hpp). Levels here are re the echo of a reflector of reflectivity 1 filling
/// the beam at normal incidence, after a TVG that restores 20 log r + 2αr (propagation.hpp). In
/// those units the source level, the r⁻⁴ and absorption of 2 TL with the TVG's gain, and the
/// beam's two-way equivalent solid angle Ω = ∫ p_h² p_v² dΩ (beam_pattern.hpp) leave
///     P = p_h(h)² p_v(v)² · ρ sin^k ψ · A / (r² Ω)
/// for a patch of area A at range r seen in direction (h, v) at grazing angle ψ (surfaceEchoPower).
///
/// Flat seabed. A pulse-limited annulus, A = r cos v · Φ_h · L / cos ψ, with Ω = Φ_h · V
/// (V = elevationPatternIntegral, the vertical pattern integrated over the aperture's cells), so
/// the horizontal pattern cancels:
///     P(r) = ρ p_v(v)² cos v sin^(k+1) ψ · L / (h · V · cos ψ),   sin ψ = h / r,
/// for a seabed `altitude_m` = h below the head; a head tilted down by τ, along the beam that
/// looks the way it tilts, sees the seabed at depression ψ at elevation v = τ − ψ in its own frame
/// (level head: v = −ψ and P = ρ p_v² sin^k ψ L / (r V)). For Lambert (k = 2) where the vertical
/// pattern is flat, ρ h² L / (V r³): the classic pulse-limited bottom reverberation under a
/// 20 log r TVG. L is what the receiver sums, pulseBins · bin length (receiver_model.hpp). Valid
/// where the echo varies little over a pulse length.
///
/// Checked against the simulator (tests/sim/test_sonar_equation.cpp): within 0.7 dB over the
/// range, 1.1 dB at 4.8° grazing, where one ray spreads its energy over 0.5 m of range.

#include "sonarmap/acoustics/beam_pattern.hpp"

namespace sonarmap {

/// The echo power of a patch in the units of the file's comment: two_way_pattern · scatter_per_area
/// · area_m2 / (range_m² · equivalent_solid_angle_sr).
/// @param two_way_pattern            p_h² p_v² of the patch's direction, [0, 1].
/// @param scatter_per_area           ρ sin^k ψ (lambertScatter), ≥ 0.
/// @param area_m2                    the patch's area, ≥ 0.
/// @param range_m                    > 0.
/// @param equivalent_solid_angle_sr  Ω of the beam, > 0.
/// @throws ValueError for any argument outside its range or not finite.
double surfaceEchoPower(double two_way_pattern, double scatter_per_area, double area_m2, double range_m,
                        double equivalent_solid_angle_sr);

/// What the flat-seabed closed form needs of a head.
struct FlatSeabedHead {
  BeamPattern vertical;               ///< the vertical (elevation) pattern
  ApertureSampling vertical_sampling; ///< the aperture's cells the echo is normalised over (V)
  double pulse_length_m = 0.0;        ///< range extent of the pulse, > 0
  double bin_length_m = 0.0;          ///< range bin length, > 0

  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// A flat seabed below the head.
struct FlatSeabed {
  double altitude_m = 0.0;        ///< h, how far below the head, > 0
  double reflectivity = 0.5;      ///< ρ, [0, 1]
  double lambert_exponent = 2.0;  ///< k, ≥ 1 (backscatter.hpp)

  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// The mean power of a bin at `range_m` (after the TVG, before speckle and noise; 1 = 0 dB re a
/// perfect reflector filling the beam) of `seabed` under `head`, whose axis points down by
/// `tilt_rad` (the beam looking the way it tilts; 0: level); see the file's comment. 0 where the
/// seabed is nearer than the altitude or outside the aperture's cells (± extent half widths).
/// @throws ValueError for an invalid head or seabed, range_m not > 0 and finite, or tilt_rad
///         outside [0, π/2).
double flatSeabedEchoPower(const FlatSeabedHead& head, const FlatSeabed& seabed, double range_m, double tilt_rad = 0.0);

}  // namespace sonarmap
