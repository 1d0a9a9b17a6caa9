#pragma once
/// @file mapping_arguments.hpp
/// The mapping options as a user types them (`sonarmap map --resolution auto --beam-width 3 …`, or
/// the keyword arguments of the Python module's `map_sonar_log`): physical units a person reads
/// (metres, degrees, dB, probabilities), "auto" for what the mapper derives from the log, and their
/// checked conversion into MapperOptions. One translation shared by the command-line tool and the
/// Python module, so both map a log with the same options identically. Each option is an entry of
/// mappingOptionTable() (mapping_option_table.hpp); defaults are the library's (MapperOptions{}).

#include <string>
#include <vector>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/mapping/mapping_option_table.hpp"
#include "sonarmap/nav/mounting.hpp"  // sonarToBodyOfMounting: --mounting beside these options

namespace sonarmap {

/// The mapping options in the user's units, one field per entry of mappingOptionTable() (the
/// entry's link names the field; its unit, range, accepted words and help are the entry's). Numbers
/// are in the unit their name ends with (_m metres, _deg degrees, _db dB; the others are
/// probabilities and counts); strings hold a number or the option's word ("auto", "none") or one of
/// its words. A default-constructed MappingArguments holds the library's defaults (MapperOptions{}).
struct MappingArguments {
  /// Every option at the library's default, in the user's unit (setDefaultArgument).
  MappingArguments();

  std::string resolution;
  std::string detector;
  double false_alarm = 0.0;
  double min_echo_length_m = 0.0;
  std::string min_range;
  double max_near_field_m = 0.0;
  std::string intensity_span;
  bool local_reverberation = false;  ///< `--local-reverberation`
  std::string smoothing;
  double smoothing_range_m = 0.0;
  double smoothing_bearing_deg = 0.0;
  double cfar_training_m = 0.0;
  double cfar_guard_m = 0.0;
  std::string ray;
  double max_range_m = 0.0;
  double beam_width_deg = 0.0;
  bool beam_width_given = false;  ///< the user gave the beam width (else the sonar's, withSonarBeam)
  double max_voxel_updates_per_beam = 0.0;
  double hit_probability = 0.0;
  bool volume = false;  ///< `--3d`
  double vertical_aperture_deg = 0.0;
  bool vertical_aperture_given = false;  ///< the user gave the vertical aperture (else the sonar's)
  std::string water_surface_depth;
  unsigned threads = 0;
  /// The log's format (parseLogFormat's names), or auto: by the input's extension (inputFormat).
  /// Not a mapping option: it names the sonar whose beam widths apply (withSonarBeam).
  std::string format = "auto";
};

/// The log format of `input`: `format` (parseLogFormat's names) unless it is "auto", else by the
/// input's extension.
/// @throws ValueError for an unknown format name; FileError for an unknown extension.
LogFormat inputFormat(const std::string& input, const std::string& format);

/// `options` with the beam widths of the sonar that writes `format` (nominalBeam) where the user
/// gave none (beam_width_given, vertical_aperture_given), then validated.
/// @throws ValueError as MapperOptions::validate.
MapperOptions withSonarBeam(MapperOptions options, const MappingArguments& args, LogFormat format);

/// As above with the beam of a sonar given directly (e.g. a simulated head's widths).
/// @throws ValueError as above.
MapperOptions withSonarBeam(MapperOptions options, const MappingArguments& args, const NominalBeam& beam);

/// Turns the arguments into mapper options (applyArgument for each entry of mappingOptionTable()),
/// checking each value against its range or words.
/// @throws ValueError naming the option (as its command-line flag), its unit and its range (or
///         its words), or as MapperOptions::validate.
MapperOptions toMapperOptions(const MappingArguments& args);

/// `text` as a number > 0 (≥ 0 with `zero_allowed`) of `unit`, for the option `option`.
/// @throws ValueError naming the option otherwise.
double parseOptionNumber(const std::string& text, const char* option, const char* unit, bool zero_allowed = false);

}  // namespace sonarmap
