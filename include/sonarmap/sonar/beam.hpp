#pragma once
/// @file beam.hpp
/// One MSIS beam and a log of beams (paper §2.1).
///
/// Sonar frame (nav/navigation.hpp states the frames once): x along the head's "ahead" (bearing 0),
/// y to starboard, z down for a head mounted upright (FRD, as the vehicle's body frame); bearing is
/// measured from +x towards +y, clockwise seen from above, in radians within [0, 2π): a beam at
/// bearing b points along (cos b, sin b, 0). Every reader maps its head's ahead to 0 and its count
/// to this direction. Bin i covers ranges [i, i+1) × bin_length_m from the transducer.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sonarmap {

/// One beam: the echo intensities along one bearing at one time.
struct Beam {
  double time_s = 0.0;        ///< time of the beam in seconds (the log's own clock)
  double bearing_rad = 0.0;   ///< bearing in the sonar frame, radians in [0, 2π), clockwise from ahead
  double bin_length_m = 0.0;  ///< length of one bin along the beam, metres (> 0)
  std::vector<std::uint8_t> intensities{};  ///< echo intensity per bin, 0…255, bin 0 nearest
  /// dB span the intensities 0…255 cover, when the format records it (SeaNet: ADspan × 80 / 255);
  /// unset otherwise (polar_units.hpp then assumes kDefaultIntensitySpan_db).
  std::optional<double> intensity_span_db{};
  /// The receiver gain setting the head reports, in the head's own units, when the format records
  /// it (Ping360 device_data gain_setting: 0 low, 1 normal, 2 high; SeaNet mtHeadData: the gain
  /// byte). Beams of different settings are not calibrated together (sweeps.hpp).
  std::optional<int> gain_setting{};
  /// Length in range of the transmitted pulse, c·τ/2, metres (> 0), when the format records it
  /// (Ping360 device_data: transmit_duration τ in µs at the reader's sound speed; Ping Viewer sets
  /// τ to 8000·R/c µs, a pulse of 0.4 % of the range R: 8 mm at 2 m, 0.2 m at 50 m); unset
  /// otherwise. A surface's echo is as long as the pulse at least, so the detector never asks an
  /// echo to be longer than this (detectors.hpp, BackgroundOptions::min_echo_length_m).
  std::optional<double> pulse_length_m{};
};

/// The beam of a sonar as its maker states it (−3 dB widths).
struct NominalBeam {
  double width_rad = 0.0;              ///< horizontal beam width, radians
  double vertical_aperture_rad = 0.0;  ///< vertical beam width, radians
};

/// Beams read from a file, in recording order, with the count of beams the reader rejected.
struct SonarLog {
  std::vector<Beam> beams;
  std::size_t skipped_beams = 0;         ///< malformed beams that were dropped (not in `beams`)
  std::vector<std::string> skip_reasons;  ///< one line per skipped beam, for the user
  /// What the file says of the sonar that recorded it, when it says anything (a Ping Viewer log's
  /// device_information and recorder: "Ping360 (firmware 3.1.1), recorded by Ping Viewer v2.1.0 on
  /// Windows 7 SP 1"); empty otherwise.
  std::string sonar;
  /// Lines for the user about data the reader kept but had to interpret (a time stamp it could not
  /// read, a clock that wrapped); not skips.
  std::vector<std::string> notes;
  /// UTC, in seconds since 1970, at the beams' time_s = 0, when the file says
  /// (formats/log_clock.hpp): 0 for a ROS log (header stamps are UTC), a Ping Viewer log's start
  /// from its file name; unset for files that do not say.
  std::optional<double> clock_utc_s;
  /// The frame the file names for the sonar (a ROS log's header frame_id: where /tf_static places
  /// it on the vehicle); empty when it names none.
  std::string frame_id;
  /// The sonar's beam when the file records it (a recorded dive's messages: dive_recorder.hpp);
  /// unset otherwise (the format's, nominalBeam, applies).
  std::optional<NominalBeam> nominal_beam;
};

}  // namespace sonarmap
