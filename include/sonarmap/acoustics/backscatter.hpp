#pragma once
/// @file backscatter.hpp
/// How strongly a surface scatters sound back towards the head: Lambert's law.
///
/// A surface that scatters the share ρ (its reflectivity, [0, 1]) of the incident energy
/// diffusely by Lambert's law has the backscattering strength per unit area and unit solid angle
///     S_b(ψ) = 10 log10 μ + 10 log10 sin^k ψ,   μ = ρ / π,
/// at grazing angle ψ (incidence θ = π/2 − ψ from the normal, sin ψ = cos θ), with k = 2 for
/// Lambert's law (Urick, "Principles of Underwater Sound", 3rd ed. 1983, ch. 8, bottom
/// backscattering; Lurton, "An Introduction to Underwater Acoustics", 2nd ed. 2010, Lambert's law
/// of seafloor backscatter). μ = 1/π (−5 dB) for a perfect diffuse scatterer; Mackenzie (1961,
/// JASA 33(11) 1498) measured μ = −27 dB for the deep-sea floor at 530 and 1030 Hz. Other k ≥ 1
/// make the surface more (k > 2) or less (k < 2) specular.
///
/// Bottom types: the simulator knows none by name; each scene primitive has a reflectivity ρ
/// (sim/builtin_scenes.hpp: concrete 0.9, steel 0.95, rock 0.7, sand 0.5, mud 0.3, rubble and weed
/// 0.06, timber 0.09), so only Lambert with the scene's ρ is here. The APL-UW sediment models
/// (APL-UW High-Frequency Ocean Environmental Acoustic Models Handbook, TR 9407, 1994: strengths
/// against grazing angle per sediment type) are not.
///
/// In the simulator's units (msis_simulator.hpp: 1 = the echo of a ρ = 1 reflector filling the
/// beam at normal incidence) a surface's echo per unit area is π · 10^(S_b/10) = ρ sin^k ψ
/// (lambertScatter): the 1/π of μ and of the reference cancel.

namespace sonarmap {

/// Lambert's coefficient μ = ρ / π of a surface of reflectivity `reflectivity` ([0, 1]).
/// @throws ValueError when the reflectivity is outside [0, 1] or NaN.
double lambertCoefficient(double reflectivity);

/// Backscattering strength S_b = 10 log10(ρ / π) + 10 log10 sin^k ψ, dB re 1 m² per m² and
/// steradian, at grazing angle `grazing_rad` ([0, π/2]); −infinity at ψ = 0 or ρ = 0.
/// @throws ValueError when the reflectivity is outside [0, 1], the grazing angle outside
///         [0, π/2], or lambert_exponent not ≥ 1 and finite.
double lambertStrength_db(double reflectivity, double grazing_rad, double lambert_exponent = 2.0);

/// The echo per unit area in the simulator's units, ρ cos^k θ = π · 10^(S_b/10), for incidence
/// cos θ = `cos_incidence` (= sin ψ; ≥ 0, a little above 1 from rounding is accepted).
/// @throws ValueError when the reflectivity is outside [0, 1], cos_incidence is negative or not
///         finite, or lambert_exponent is not ≥ 1 and finite.
double lambertScatter(double reflectivity, double cos_incidence, double lambert_exponent);

/// The echo per unit solid angle of the beam over the surface's footprint (r² / cos θ,
/// ensonified_area.hpp) without its r² (which twoWayLossPerSolidAngle carries): ρ cos^(k−1) θ.
/// What one ray of the simulator brings back from the surface it meets (msis_simulator.hpp, step 2).
/// @throws ValueError as lambertScatter.
double lambertScatterPerSolidAngle(double reflectivity, double cos_incidence, double lambert_exponent);

}  // namespace sonarmap
