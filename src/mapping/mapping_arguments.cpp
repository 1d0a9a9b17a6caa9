#include "sonarmap/mapping/mapping_arguments.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <utility>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

}  // namespace

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

Eigen::Isometry3d sonarToBodyOfMounting(const std::vector<double>& mounting) {
  if (mounting.empty()) return defaultSonarToBody();
  if (mounting.size() != 6 || !std::all_of(mounting.begin(), mounting.end(), [](double v) { return std::isfinite(v); })) {
    throw ValueError("--mounting expects six finite numbers X,Y,Z,ROLL,PITCH,YAW (metres, degrees)");
  }
  NavSample pose;  // the sonar's pose in the body frame, built as a fix's body pose in NED
  pose.position_ned_m = Eigen::Vector3d(mounting[0], mounting[1], mounting[2]);
  pose.roll_rad = mounting[3] * kRadPerDeg;
  pose.pitch_rad = mounting[4] * kRadPerDeg;
  pose.yaw_rad = mounting[5] * kRadPerDeg;
  return bodyToNed(pose);
}

std::array<double, 6> mountingOfPose(const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  const double roll = std::atan2(r(2, 1), r(2, 2));
  const double yaw = std::atan2(r(1, 0), r(0, 0));
  // + 0.0 turns a negative zero into 0.
  return {t.x() + 0.0, t.y() + 0.0, t.z() + 0.0, roll / kRadPerDeg + 0.0, pitch / kRadPerDeg + 0.0, yaw / kRadPerDeg + 0.0};
}

}  // namespace sonarmap
