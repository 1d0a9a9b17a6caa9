#include "sonarmap/mapping/mapping_arguments.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/preprocess.hpp"

namespace sonarmap {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

std::string formatted(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

/// `text` as a number, "auto" as nullopt. @throws ValueError (usage) otherwise.
std::optional<double> autoOr(const std::string& text, const char* option, const char* unit, bool zero_allowed) {
  if (text == "auto") return std::nullopt;
  return parseOptionNumber(text, option, unit, zero_allowed);
}

/// @throws ValueError (usage) unless lo ≤ value ≤ hi (strict at an open end), naming the option.
void requireWithin(double value, double lo, double hi, bool open_lo, bool open_hi, const char* option,
                   const char* what) {
  const bool ok = std::isfinite(value) && (open_lo ? value > lo : value >= lo) && (open_hi ? value < hi : value <= hi);
  if (!ok) throw ValueError(std::string(option) + " expects " + what + ", got " + formatted(value));
}

/// --water-surface-depth: metres of either sign, or "none" as NaN (unknown). @throws ValueError (usage) otherwise.
double surfaceDepth_m(const std::string& text) {
  if (text == "none") return std::numeric_limits<double>::quiet_NaN();
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc{} || ptr != end || !std::isfinite(value)) {
    throw ValueError("--water-surface-depth expects metres (the surface's depth in the navigation, 0 with a depth "
                     "sensor) or none, got '" + text + "'");
  }
  return value;
}

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
  throw FileError("'" + input + "': unknown sonar log type '" + std::filesystem::path(input).extension().string() +
                  "', expected .mat, .csv, .V4LOG, .seanet (SeaNet wire capture) or .bin (Ping360), or name it with "
                  "--format");
}

MapperOptions withSonarBeam(MapperOptions options, const MappingArguments& args, LogFormat format) {
  return withSonarBeam(std::move(options), args, nominalBeam(format));
}

MapperOptions withSonarBeam(MapperOptions options, const MappingArguments& args, const NominalBeam& beam) {
  if (!args.beam_width_given) options.beam_width_rad = beam.width_rad;
  if (!args.vertical_aperture_given) options.vertical_aperture_rad = beam.vertical_aperture_rad;
  if (options.free_vertical_aperture_rad && *options.free_vertical_aperture_rad > options.vertical_aperture_rad) {
    throw ValueError("--free-aperture " + std::to_string(*options.free_vertical_aperture_rad / kRadPerDeg) +
                     " is wider than the vertical aperture");
  }
  options.validate();
  return options;
}

MapperOptions toMapperOptions(const MappingArguments& args) {
  MapperOptions options;
  options.resolution_m = autoOr(args.resolution, "--resolution", "metres", false);
  selectDetector(options.detector, args.detector);
  requireWithin(args.false_alarm, 0.0, 0.5, true, true, "--false-alarm", "a probability in (0, 0.5)");
  requireWithin(args.min_contrast_db, 0.0, 255.0, false, false, "--min-contrast", "dB in [0, 255]");
  requireWithin(args.min_echo_length_m, 0.0, 1e6, false, false, "--min-echo-length", "metres >= 0");
  requireWithin(args.leading_edge_db, 0.0, 255.0, false, false, "--leading-edge", "dB in [0, 255]");
  CalibrationOptions& calibration = options.detector.background.calibration;
  calibration.false_alarm_probability = args.false_alarm;
  calibration.min_contrast_db = args.min_contrast_db;
  options.detector.background.min_echo_length_m = args.min_echo_length_m;
  options.detector.cfar.min_echo_length_m = args.min_echo_length_m;
  options.detector.cfar.min_contrast_db = std::max(options.detector.cfar.min_contrast_db, args.min_contrast_db);
  options.detector.background.leading_edge_db = args.leading_edge_db;
  options.detector.min_range_m = autoOr(args.min_range, "--min-range", "metres", true);
  requireWithin(args.max_near_field_m, 0.0, 1e6, false, false, "--max-near-field", "metres >= 0");
  calibration.max_near_field_m = args.max_near_field_m;
  options.self_reflection_range_m = autoOr(args.self_reflection, "--self-reflection", "metres", true);
  options.detector.intensity_span_db = autoOr(args.intensity_span, "--intensity-span", "dB", false);
  options.smoothing.kind = parseSmoothing(args.smoothing);
  requireWithin(args.smoothing_range_m, 0.0, 1e6, false, false, "--smoothing-range", "metres >= 0");
  requireWithin(args.smoothing_bearing_deg, 0.0, 360.0, false, false, "--smoothing-bearing", "degrees in [0, 360]");
  options.smoothing.range_m = args.smoothing_range_m;
  options.smoothing.bearing_rad = args.smoothing_bearing_deg * kRadPerDeg;
  requireWithin(args.cfar_training_m, 0.0, 1e6, true, false, "--cfar-training", "metres > 0");
  requireWithin(args.cfar_guard_m, 0.0, 1e6, false, false, "--cfar-guard", "metres >= 0");
  options.detector.cfar.training_m = args.cfar_training_m;
  options.detector.cfar.guard_m = args.cfar_guard_m;
  options.ray = parseRayAlgorithm(args.ray);
  if (args.aggregation == "max") {
    options.octree.aggregation = InnerAggregation::kMax;
  } else if (args.aggregation == "mean") {
    options.octree.aggregation = InnerAggregation::kMean;
  } else {
    throw ValueError("unknown aggregation '" + args.aggregation + "', expected max or mean");
  }
  requireWithin(args.max_range_m, 0.0, std::numeric_limits<double>::infinity(), true, false, "--max-range",
                "metres > 0");
  options.max_range_m = args.max_range_m;
  requireWithin(args.beam_width_deg, 0.0, 180.0, false, true, "--beam-width", "degrees in [0, 180)");
  options.beam_width_rad = args.beam_width_deg * kRadPerDeg;
  options.range_tolerance_m = autoOr(args.range_tolerance, "--range-tolerance", "metres", true);
  requireWithin(args.max_voxel_updates, 0.0, std::numeric_limits<double>::infinity(), true, false,
                "--max-voxel-updates", "a count > 0");
  options.max_voxel_updates = args.max_voxel_updates;
  requireWithin(args.hit_probability, 0.5, 1.0, true, true, "--hit-probability", "a probability in (0.5, 1)");
  options.octree.occupancy.prob_hit = args.hit_probability;
  options.threads = args.threads;
  if (args.volume) options.beam_model = BeamModel::kVolume;
  requireWithin(args.vertical_aperture_deg, 0.0, 180.0, true, true, "--vertical-aperture", "degrees in (0, 180)");
  options.vertical_aperture_rad = args.vertical_aperture_deg * kRadPerDeg;
  options.arc_evidence = parseArcEvidence(args.arc_evidence);
  options.obstacle_surface = parseObstacleSurface(args.obstacle_surface);
  options.extended_returns = args.extended_returns;
  options.seabed_slope = args.seabed_slope;
  options.face_slope = args.face_slope;
  options.water_surface_depth_m = surfaceDepth_m(args.water_surface_depth);
  if (const std::optional<double> free_deg = autoOr(args.free_aperture, "--free-aperture", "degrees", false)) {
    requireWithin(*free_deg, 0.0, args.vertical_aperture_deg, true, false, "--free-aperture",
                  "degrees in (0, the vertical aperture]");
    options.free_vertical_aperture_rad = *free_deg * kRadPerDeg;
  }
  if (args.clear_without_obstacle != "auto") options.clear_without_obstacle = args.clear_without_obstacle == "yes";
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
