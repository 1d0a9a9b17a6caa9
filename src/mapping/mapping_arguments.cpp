#include "sonarmap/mapping/mapping_arguments.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <utility>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
double parseOptionNumber(const std::string& text, const char* option, const char* unit, bool zero_allowed) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc{} || ptr != end || !std::isfinite(value) || value < 0.0 || (!zero_allowed && value == 0.0)) {
    throw ValueError(std::string(option) + " expects a number of " + unit + (zero_allowed ? " >= 0" : " > 0") +
                     " or auto, got '" + text + "'");
  }
  return value;
}

LogFormat inputFormat(const std::string& input, const std::string& format) {
  if (format != "auto") return parseLogFormat(format);
  if (const std::optional<LogFormat> by_extension = logFormatOfPath(input)) return *by_extension;
  throw FileError(unknownLogTypeMessage(input) + " with --format");
}

MapperOptions withSonarBeam(MapperOptions options, const MappingArguments& args, LogFormat format) {
  return withSonarBeam(std::move(options), args, nominalBeam(format));
}

MapperOptions withSonarBeam(MapperOptions options, const MappingArguments& args, const NominalBeam& beam) {
  if (!args.beam_width_given) options.beam_width_rad = beam.width_rad;
  if (!args.vertical_aperture_given) options.vertical_aperture_rad = beam.vertical_aperture_rad;
  options.validate();
  return options;
}

MappingArguments::MappingArguments() {
  for (const MappingOption& option : mappingOptionTable()) setDefaultArgument(option, *this);
}

MapperOptions toMapperOptions(const MappingArguments& args) {
  MapperOptions options;
  for (const MappingOption& option : mappingOptionTable()) applyArgument(option, args, options);
  options.validate();
  return options;
}

}  // namespace sonarmap
