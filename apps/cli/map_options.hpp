#pragma once
// The options of `sonarmap map` (and `demo`), every one in physical units, and their conversion
// into the library's MapperOptions. Defaults are the library's (MapperOptions{}), not copies.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/mapper_options.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap map` as typed by the user. "auto" values are resolved per log or sweep.
struct MapArgs {
  std::string input;
  std::string output_bt;
  std::string map_png;
  std::string polar_png;
  std::string cartesian_png;
  std::string resolution = "auto";       ///< metres, or auto (autoResolution_m of the log's reach)
  std::string detector = "background";
  double false_alarm = MapperOptions{}.detector.background.calibration.false_alarm_probability;
  double min_contrast_db = MapperOptions{}.detector.background.calibration.min_contrast_db;
  double min_echo_length_m = MapperOptions{}.detector.background.min_echo_length_m;
  double leading_edge_db = MapperOptions{}.detector.background.leading_edge_db;
  std::string min_range = "auto";        ///< metres, or auto (the near-field clutter's end)
  std::string self_reflection = "auto";  ///< metres, or auto (the self-reflection band's end)
  std::string intensity_span = "auto";   ///< dB, or auto (the log's, else 45 dB)
  std::string smoothing = "none";
  double smoothing_range_m = MapperOptions{}.smoothing.range_m;
  double smoothing_bearing_deg = MapperOptions{}.smoothing.bearing_rad * 180.0 / 3.14159265358979323846;
  double cfar_training_m = MapperOptions{}.detector.cfar.training_m;
  double cfar_guard_m = MapperOptions{}.detector.cfar.guard_m;
  std::string ray = "dda";
  std::string aggregation = "max";
  double max_range_m = MapperOptions{}.max_range_m;
  std::string format = "auto";  ///< log format (parseLogFormat), or auto: by the input's extension
  double beam_width_deg = MapperOptions{}.beam_width_rad * 180.0 / 3.14159265358979323846;
  bool beam_width_given = false;         ///< --beam-width was on the command line
  bool vertical_aperture_given = false;  ///< --vertical-aperture was on the command line
  std::string range_tolerance = "auto";  ///< metres, or auto (a bin plus half a voxel plus each echo's rise)
  double max_voxel_updates = MapperOptions{}.max_voxel_updates;
  double hit_probability = MapperOptions{}.octree.occupancy.prob_hit;
  bool volume = false;  ///< --3d: the beam-volume model
  double vertical_aperture_deg = MapperOptions{}.vertical_aperture_rad * 180.0 / 3.14159265358979323846;
  unsigned threads = 1;  ///< threads tracing a sweep's free rays
  std::string free_aperture = "auto";  ///< degrees, or auto (half the vertical aperture)
  std::string clear_without_obstacle = "auto";  ///< yes, no, or auto (planar yes, --3d no)
  std::string arc_evidence = "pattern";
  bool quiet = false;
  bool tank_report = false;
  std::string nav_csv;           ///< navigation CSV (empty: the sonar is static at the map origin)
  std::vector<double> mounting;  ///< X,Y,Z (m), ROLL,PITCH,YAW (degrees) of the sonar in the body; empty: default
};

/// Adds the mapping options (everything but the input, outputs, --nav and --mounting) to `cmd`.
void addMappingOptions(CLI::App& cmd, MapArgs& args);

/// The input's log format: --format, or by the input's extension.
/// @throws ValueError (usage) for an unknown --format name; FileError for an unknown extension.
LogFormat inputFormat(const std::string& input, const std::string& format);

/// `options` with the beam widths of the sonar that writes `format` (nominalBeam) where the user
/// gave none (--beam-width, --vertical-aperture), and the free aperture following the vertical one.
MapperOptions withSonarBeam(MapperOptions options, const MapArgs& args, LogFormat format);

/// Turns the arguments into mapper options, checking each value's range with the option's name.
/// @throws ValueError (usage) naming the option, its unit and its range.
MapperOptions toMapperOptions(const MapArgs& args);

/// `text` as a number > 0 (≥ 0 with `zero_allowed`) of `unit`, for the option `option`.
/// @throws ValueError (usage) otherwise.
double parseNumber(const std::string& text, const char* option, const char* unit, bool zero_allowed = false);

}  // namespace sonarmap::cli
