#pragma once
/// @file ensonified_area.hpp
/// The area of a surface that contributes to one echo: the A of the sonar equation's
/// 10 log10 A for boundary reverberation (Urick, "Principles of Underwater Sound", 3rd ed. 1983,
/// ch. 8; Lurton, "An Introduction to Underwater Acoustics", 2nd ed. 2010, backscattered level
/// of the seafloor).
///
/// Pulse-limited surface: at range r an echo of range extent L (the pulse's cτ/2, or the range
/// the receiver sums) comes from a strip of the surface L / cos ψ long along the range (ψ the
/// grazing angle) and, across it, the arc the beam's horizontal pattern covers at that range: an
/// arc of radius r cos v (v the direction's elevation from the beam's plane) and of the
/// equivalent two-way width Φ (beam_pattern.hpp), so
///     A = r cos v · Φ · L / cos ψ.
/// For a level head over a flat seabed v = −ψ and A = Φ r L, Urick's pulse-limited area.
/// Beam-limited footprint: a cone of solid angle Ω meets a surface at range r and incidence θ
/// (to the normal) over r² Ω / cos θ.
/// The simulator (msis_simulator.hpp) uses neither directly: its rays carry r² / cos θ inside
/// twoWayLossPerSolidAngle (propagation.hpp) and lambertScatterPerSolidAngle (backscatter.hpp),
/// and its water column has no volume reverberation, so no volume cell is here.

namespace sonarmap {

/// Pulse-limited area A = r cos v · Φ · L / cos ψ, m².
/// @param range_m              r, > 0.
/// @param grazing_rad          ψ, between the incoming direction and the surface, [0, π/2).
/// @param pulse_length_m       L, the echo's range extent, > 0.
/// @param equivalent_width_rad Φ, the horizontal pattern's equivalent two-way width (equivalentBeamWidth_rad), > 0.
/// @param elevation_rad        v, the direction's elevation from the beam's plane, (−π/2, π/2).
/// @throws ValueError for any argument outside its range or not finite.
double pulseLimitedArea_m2(double range_m, double grazing_rad, double pulse_length_m, double equivalent_width_rad,
                           double elevation_rad);

/// Area a cone of solid angle `solid_angle_sr` (> 0) covers on a surface at `range_m` (> 0),
/// met at incidence θ with cos θ = `cos_incidence` (in (0, 1]): r² Ω / cos θ, m².
/// @throws ValueError for any argument outside its range or not finite.
double footprintArea_m2(double range_m, double solid_angle_sr, double cos_incidence);

}  // namespace sonarmap
