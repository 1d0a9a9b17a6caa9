#pragma once
/// @file sonar_equation.hpp
/// The sonar equation's closed forms for a simulated head, asked in the simulator's terms: a flat
/// seabed's echo power and the noise's mean power for a head known by its MsisHeadOptions and
/// EchoModelOptions (a preset, sonar_presets.hpp), so that what the simulator writes for a seabed
/// can be checked against physics, and a seabed's level set against a head's noise from published
/// backscattering strengths. Thin wrappers: the formulas, their derivation and their sources are
/// the acoustics layer's (acoustics/sonar_equation.hpp, acoustics/receiver_model.hpp), the options
/// converted by sim/acoustic_parameters.hpp.
///
/// Checked against the simulator (tests/sim/test_sonar_equation.cpp): within 0.7 dB over the
/// range, 1.1 dB at 4.8° grazing, where one ray spreads its energy over 0.5 m of range.

#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {

/// The mean power of a bin at `range_m` (after the TVG, before speckle and noise; in the echo
/// model's units, 1 = 0 dB re a perfect reflector filling the beam) of a flat seabed of reflectivity
/// `reflectivity` (Lambert with the echo model's lambert_exponent) lying `altitude_m` below the
/// head, whose axis points down by `tilt_rad` (the beam looking the way it tilts; 0: level):
/// acoustics' flatSeabedEchoPower with the head's vertical pattern and rays, pulse and bin length.
/// 0 where the seabed is nearer than the altitude or outside the echo model's rays.
/// @throws ValueError for invalid head or echo options, altitude_m or range_m not > 0 and finite,
///         reflectivity outside [0, 1], or tilt_rad outside [0, π/2).
double flatSeabedEchoPower(const MsisHeadOptions& head, const EchoModelOptions& echo, double altitude_m,
                           double reflectivity, double range_m, double tilt_rad = 0.0);

/// The mean power of the additive noise in a bin at `range_m` after the TVG, in the same units:
/// the noise before the gain (EchoModelOptions::noise_level_db) times r² · 10^(2 α r / 10), what
/// the simulator's receiver adds (msis_simulator.hpp, step 5; acoustics' meanNoisePower).
/// @throws ValueError for invalid echo options or range_m not > 0 and finite.
double meanNoisePower(const EchoModelOptions& echo, double range_m);

}  // namespace sonarmap
