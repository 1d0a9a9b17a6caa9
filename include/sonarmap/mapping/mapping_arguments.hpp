#pragma once
/// @file mapping_arguments.hpp
/// The mapping options as a user types them (`sonarmap map --resolution auto --beam-width 3 …`, or
/// the keyword arguments of the Python module's `map_sonar_log`): physical units a person reads
/// (metres, degrees, dB, probabilities), "auto" for what the mapper derives from the log, and their
/// checked conversion into MapperOptions. One translation shared by the command-line tool and the
/// Python module, so both map a log with the same options identically. Defaults are the library's
/// (MapperOptions{}), not copies.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/mapper_options.hpp"

namespace sonarmap {

/// The mapping options in user units. Strings hold a number or "auto" (resolved per log or sweep).
/// Each field's name is the command-line flag's (`--false-alarm` → false_alarm) with its unit.
struct MappingArguments {
  std::string resolution = "auto";       ///< metres, or auto (autoResolution_m of the log's reach)
  std::string detector = "background";   ///< parseDetector's names
  double false_alarm = MapperOptions{}.detector.background.calibration.false_alarm_probability;
  double min_contrast_db = MapperOptions{}.detector.background.calibration.min_contrast_db;
  double min_echo_length_m = MapperOptions{}.detector.background.min_echo_length_m;
  double leading_edge_db = MapperOptions{}.detector.background.leading_edge_db;
  std::string min_range = "auto";        ///< metres, or auto (the near-field clutter's end)
  /// metres ≥ 0: the farthest the automatic minimum range's clutter may reach (CalibrationOptions)
  double max_near_field_m = MapperOptions{}.detector.background.calibration.max_near_field_m;
  std::string self_reflection = "auto";  ///< metres, or auto (the self-reflection band's end)
  std::string intensity_span = "auto";   ///< dB, or auto (the log's, else 45 dB)
  std::string smoothing = "none";        ///< none | gaussian | median | mean
  double smoothing_range_m = MapperOptions{}.smoothing.range_m;
  double smoothing_bearing_deg = MapperOptions{}.smoothing.bearing_rad * 180.0 / 3.14159265358979323846;
  double cfar_training_m = MapperOptions{}.detector.cfar.training_m;
  double cfar_guard_m = MapperOptions{}.detector.cfar.guard_m;
  std::string ray = "dda";               ///< dda | bresenham
  std::string aggregation = "max";       ///< inner nodes: max | mean
  double max_range_m = MapperOptions{}.max_range_m;
  std::string format = "auto";  ///< log format (parseLogFormat), or auto: by the input's extension
  double beam_width_deg = MapperOptions{}.beam_width_rad * 180.0 / 3.14159265358979323846;
  bool beam_width_given = false;         ///< the user gave the beam width (else the sonar's, withSonarBeam)
  bool vertical_aperture_given = false;  ///< the user gave the vertical aperture (else the sonar's)
  std::string range_tolerance = "auto";  ///< metres, or auto (a bin plus half a voxel plus each echo's rise)
  double max_voxel_updates = MapperOptions{}.max_voxel_updates;
  double hit_probability = MapperOptions{}.octree.occupancy.prob_hit;
  bool volume = false;  ///< `--3d`: the beam-volume model (BeamModel::kVolume)
  double vertical_aperture_deg = MapperOptions{}.vertical_aperture_rad * 180.0 / 3.14159265358979323846;
  unsigned threads = 1;  ///< threads tracing a sweep's free rays, ≥ 1
  std::string free_aperture = "auto";           ///< degrees, or auto (half the vertical aperture)
  std::string clear_without_obstacle = "auto";  ///< yes, no, or auto (planar yes, volume no)
  std::string arc_evidence = "pattern";         ///< whole | uniform | pattern
  std::string obstacle_surface = "vertical";    ///< --3d: vertical | shell (ObstacleSurface)
  bool extended_returns = true;                 ///< --3d: weak extended returns on their level surface
  bool seabed_slope = true;                     ///< --3d: seabed traces follow the fitted slope
  bool face_slope = true;                       ///< --3d: oblique faces recede across their beams
  /// --3d: the water surface's depth in the navigation's frame, metres (any sign), or none: unknown
  /// (MapperOptions::water_surface_depth_m).
  std::string water_surface_depth = "0";
};

/// The log format of `input`: `format` (parseLogFormat's names) unless it is "auto", else by the
/// input's extension.
/// @throws ValueError for an unknown format name; FileError for an unknown extension.
LogFormat inputFormat(const std::string& input, const std::string& format);

/// `options` with the beam widths of the sonar that writes `format` (nominalBeam) where the user
/// gave none (beam_width_given, vertical_aperture_given), then validated.
/// @throws ValueError when the free aperture is wider than the vertical aperture, or as
///         MapperOptions::validate.
MapperOptions withSonarBeam(MapperOptions options, const MappingArguments& args, LogFormat format);

/// As above with the beam of a sonar given directly (e.g. a simulated head's widths).
/// @throws ValueError as above.
MapperOptions withSonarBeam(MapperOptions options, const MappingArguments& args, const NominalBeam& beam);

/// Turns the arguments into mapper options, checking each value's range.
/// @throws ValueError naming the option (as its command-line flag), its unit and its range.
MapperOptions toMapperOptions(const MappingArguments& args);

/// `text` as a number > 0 (≥ 0 with `zero_allowed`) of `unit`, for the option `option`.
/// @throws ValueError naming the option otherwise.
double parseOptionNumber(const std::string& text, const char* option, const char* unit, bool zero_allowed = false);

/// The sonar's mounting (sonar frame → body frame FRD, navigation.hpp) from X, Y, Z in metres and
/// ROLL, PITCH, YAW in degrees (Z-Y-X Euler angles, as a NavSample's attitude); empty: the default
/// mounting, upright and aligned (defaultSonarToBody()).
/// @throws ValueError when the list is neither empty nor six finite numbers.
Eigen::Isometry3d sonarToBodyOfMounting(const std::vector<double>& mounting);

/// The inverse of sonarToBodyOfMounting for any rigid pose (rotation `r`, translation `t`): X, Y, Z
/// in metres, then ROLL, PITCH, YAW in degrees of r = Rz(yaw)·Ry(pitch)·Rx(roll) (pitch in
/// [−90°, 90°]); the numbers of map --mounting and eval --sensor-pose.
std::array<double, 6> mountingOfPose(const Eigen::Matrix3d& r, const Eigen::Vector3d& t);

}  // namespace sonarmap
