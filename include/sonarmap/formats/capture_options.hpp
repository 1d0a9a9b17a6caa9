#pragma once
/// @file capture_options.hpp
/// Options of the readers of raw sonar wire captures (seanet_capture.hpp, ping360_reader.hpp):
/// how head settings become metres and, for captures without a clock, seconds.

namespace sonarmap {

/// How a raw capture's head settings become beam geometry and times.
struct CaptureOptions {
  /// Speed of sound in m/s (> 0, finite): a bin spans its sample interval × speed / 2.
  double sound_speed_m_s = 1500.0;
  /// Seconds between beams for a capture without a clock (≥ 0, finite): beam i gets time
  /// i × beam_interval_s. Neither SeaNet's mtHeadData nor Ping360's device_data carry a time, so
  /// a raw capture's beams are all at 0 s by default (sweeps are found from bearings, not times;
  /// navigation cannot be matched without a clock). Ping Viewer logs have their own timestamps
  /// and ignore this.
  double beam_interval_s = 0.0;
};

}  // namespace sonarmap
