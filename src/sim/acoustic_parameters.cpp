/// @file acoustic_parameters.cpp
/// The simulator's options as acoustics parameters (see acoustic_parameters.hpp).

#include "sonarmap/sim/acoustic_parameters.hpp"

namespace sonarmap {

TransducerPattern transducerPatternOf(const MsisHeadOptions& head, const EchoModelOptions& echo) {
  return TransducerPattern{{head.horizontal_beam_width_rad, echo.horizontal.exponent},
                           {head.vertical_beam_width_rad, echo.vertical.exponent}};
}

ApertureSampling apertureSamplingOf(const ApertureAxis& axis) { return ApertureSampling{axis.rays, axis.extent}; }

ReceiverScale receiverScaleOf(const EchoModelOptions& echo) { return ReceiverScale{echo.ad_low_db, echo.ad_span_db}; }

ReceiverNoise receiverNoiseOf(const EchoModelOptions& echo) {
  return ReceiverNoise{echo.noise_level_db, echo.tvg_absorption_db_per_m};
}

FlatSeabedHead flatSeabedHeadOf(const MsisHeadOptions& head, const EchoModelOptions& echo) {
  return FlatSeabedHead{transducerPatternOf(head, echo).vertical, apertureSamplingOf(echo.vertical),
                        echo.pulse_length_m, head.binLength_m()};
}

ForwardModelHead forwardModelHeadOf(const MsisHeadOptions& head, const EchoModelOptions& echo) {
  return ForwardModelHead{head.horizontal_beam_width_rad,
                          head.vertical_beam_width_rad,
                          transducerPatternOf(head, echo),
                          apertureSamplingOf(echo.horizontal),
                          apertureSamplingOf(echo.vertical),
                          head.bins,
                          head.range_m,
                          echo.absorption_db_per_m,
                          echo.lambert_exponent};
}

}  // namespace sonarmap
