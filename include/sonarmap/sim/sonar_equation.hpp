#pragma once
/// @file sonar_equation.hpp
/// The echo level of a flat seabed under a level or tilted head, in closed form: the sonar equation for a
/// pulse-limited extended surface (Urick, "Principles of Underwater Sound", 3rd ed. 1983, ch. 8,
/// boundary reverberation), in the units of the simulator's echo model (msis_simulator.hpp), so
/// that what the simulator writes for a seabed can be checked against physics, and a seabed's
/// level set against a head's noise from published backscattering strengths.
///
/// Sonar equation of the echo level of an extended surface: EL = SL − 2 TL + S_b + 10 log A, with
/// S_b the backscattering strength per unit area and A the area a bin ensonifies. In the echo model:
///  - SL − 2 TL: the transmit and receive patterns p(h)² p(v)², spherical spreading r⁻⁴ and
///    absorption, which the TVG (20 log r + 2αr) restores but for r⁻²; levels are in dB re the echo
///    of a reflector of reflectivity 1 filling the beam at normal incidence.
///  - S_b: Lambert's law with exponent k (msis: lambert_exponent), S_b(ψ) = 10 log(ρ/π) +
///    10 log sin^k ψ at grazing angle ψ for a surface that scatters the share ρ (its reflectivity)
///    of the incident energy (Lambert's μ = ρ / π; Mackenzie 1961, JASA 33(11) 1498: μ = −27 dB for
///    the deep-sea floor at 530 and 1030 Hz).
///  - A: pulse-limited, the annulus of width L / cos ψ (L the pulse length, m, the range extent
///    the receiver sums) at range r across the horizontal pattern.
///
/// For a level head at altitude h over a flat seabed, the ray at depression −v meets the seabed at
/// r = h / sin(−v) with grazing angle ψ = −v; the energy per metre of range after the TVG is
///
///     e(r) = ρ p(v_r)² sin^(k+1) ψ_r / (h · V),   V = ∫ p(v)² cos v dv over the echo model's rays,
///
/// (the horizontal pattern cancels against the rays' normalisation) and a bin, which sums a pulse
/// length of it, has the power P(r) = e(r) · L: for Lambert (k = 2) and the flat part of the
/// vertical pattern, ρ h² L / (V r³), the classic pulse-limited bottom reverberation under a
/// 20 log r TVG. A head tilted down by τ, along the beam that looks the way it tilts, sees the ray
/// at depression ψ at elevation v = τ − ψ in its own frame: e(r) = ρ p(v)² cos v sin^(k+1) ψ /
/// (h V cos ψ).
///
/// Checked against the simulator (tests/sim/test_sonar_equation.cpp): within 0.7 dB over the
/// range, 1.1 dB at 4.8° grazing, where one ray spreads its energy over 0.5 m of range.

#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {

/// The mean power of a bin at range `range_m` (after the TVG, before speckle and noise; in the echo
/// model's units, 1 = 0 dB re a perfect reflector filling the beam) of a flat seabed of reflectivity
/// `reflectivity` lying `altitude_m` below the head, whose axis points down by `tilt_rad` (the beam
/// looking the way it tilts; 0: level); see the file's comment. 0 where the seabed is nearer than
/// the altitude or outside the echo model's rays. Valid where the echo varies little over a pulse
/// length.
/// @throws ValueError for invalid head or echo options, altitude_m or range_m not > 0 and finite,
///         reflectivity outside [0, 1], or tilt_rad outside [0, π/2).
double flatSeabedEchoPower(const MsisHeadOptions& head, const EchoModelOptions& echo, double altitude_m,
                           double reflectivity, double range_m, double tilt_rad = 0.0);

/// The mean power of the additive noise in a bin at `range_m` after the TVG, in the same units: the
/// noise before the gain (EchoModelOptions::noise_level_db) times r² · 10^(2 α r / 10), what the
/// simulator's receiver adds (msis_simulator.hpp, step 5).
/// @throws ValueError for invalid echo options or range_m not > 0 and finite.
double meanNoisePower(const EchoModelOptions& echo, double range_m);

}  // namespace sonarmap
