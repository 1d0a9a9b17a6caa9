#pragma once
/// @file acoustic_parameters.hpp
/// The simulator's options in the acoustics layer's terms (acoustics/): the simulator makes its
/// echoes with the acoustics layer's formulas, and a caller that knows a head by its
/// MsisHeadOptions and EchoModelOptions (a preset, sonar_presets.hpp) gets the same parameters
/// for them here. Copies of the fields, nothing computed; the options are not validated (the
/// acoustics functions validate what they are given).

#include "sonarmap/acoustics/beam_pattern.hpp"
#include "sonarmap/acoustics/forward_model.hpp"
#include "sonarmap/acoustics/receiver_model.hpp"
#include "sonarmap/acoustics/sonar_equation.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {

/// Both planes' patterns: the head's −3 dB widths with the echo model's exponents.
TransducerPattern transducerPatternOf(const MsisHeadOptions& head, const EchoModelOptions& echo);

/// The cells of one axis of the echo model's aperture grid (rays, extent).
ApertureSampling apertureSamplingOf(const ApertureAxis& axis);

/// The A/D mapping (ad_low_db, ad_span_db).
ReceiverScale receiverScaleOf(const EchoModelOptions& echo);

/// The additive noise and the TVG it goes through (noise_level_db, tvg_absorption_db_per_m).
ReceiverNoise receiverNoiseOf(const EchoModelOptions& echo);

/// What the flat-seabed closed form needs: the vertical pattern and cells, the pulse length and
/// the head's bin length.
FlatSeabedHead flatSeabedHeadOf(const MsisHeadOptions& head, const EchoModelOptions& echo);

/// What the forward model (acoustics/forward_model.hpp) needs: widths, patterns and aperture cells,
/// bins and range, the water's absorption and the Lambert exponent.
ForwardModelHead forwardModelHeadOf(const MsisHeadOptions& head, const EchoModelOptions& echo);

}  // namespace sonarmap
