#include "map_options.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {
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
  return parseNumber(text, option, unit, zero_allowed);
}

/// @throws ValueError (usage) unless lo ≤ value ≤ hi (strict at an open end), naming the option.
void requireWithin(double value, double lo, double hi, bool open_lo, bool open_hi, const char* option,
                   const char* what) {
  const bool ok = std::isfinite(value) && (open_lo ? value > lo : value >= lo) && (open_hi ? value < hi : value <= hi);
  if (!ok) throw ValueError(std::string(option) + " expects " + what + ", got " + formatted(value));
}

}  // namespace

double parseNumber(const std::string& text, const char* option, const char* unit, bool zero_allowed) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc{} || ptr != end || !std::isfinite(value) || value < 0.0 || (!zero_allowed && value == 0.0)) {
    throw ValueError(std::string(option) + " expects a number of " + unit + (zero_allowed ? " >= 0" : " > 0") +
                     " or auto, got '" + text + "'");
  }
  return value;
}

void addMappingOptions(CLI::App& cmd, MapArgs& args) {
  cmd.add_option("--resolution", args.resolution,
                 "Voxel edge in METRES, or auto: about 1/256 of the log's reach, rounded to 1, 2 or 5 x 10^k m "
                 "(Micron at 5 m: 0.02; SeaKing at 30 m: 0.1; Ping360 at 50 m: 0.2)")
      ->capture_default_str();
  cmd.add_option("--detector", args.detector,
                 "background (calibrated per sweep) | cfar-ca | cfar-so | cfar-go | cfar-os | threshold (paper 8.2) | "
                 "canny (paper 9)")
      ->capture_default_str();
  cmd.add_option("--false-alarm", args.false_alarm,
                 "PROBABILITY per bin that noise alone is taken for an echo, in (0, 0.5): sets the echo threshold "
                 "above the background by the speckle model (1e-6: 16.9 dB); raise it to see weaker targets")
      ->capture_default_str();
  cmd.add_option("--min-contrast", args.min_contrast_db,
                 "Least rise of an echo above the background in DB, whatever --false-alarm gives")
      ->capture_default_str();
  cmd.add_option("--min-echo-length", args.min_echo_length_m,
                 "Least length of an echo along the beam in METRES (at least one bin): shorter ones are speckle")
      ->capture_default_str();
  cmd.add_option("--leading-edge", args.leading_edge_db,
                 "An obstacle's range is where its echo rises to within this many DB of its peak (6: the nearest "
                 "surface within the -3 dB beam)")
      ->capture_default_str();
  cmd.add_option("--min-range", args.min_range,
                 "Detector's minimum range in METRES, or auto: the end of the near-field clutter measured on each "
                 "sweep (the vehicle's own returns, the transducer's ringing)")
      ->capture_default_str();
  cmd.add_option("--self-reflection", args.self_reflection,
                 "Zero the bins nearer than this in METRES before detection, or auto: the self-reflection band's end "
                 "measured on each sweep")
      ->capture_default_str();
  cmd.add_option("--intensity-span", args.intensity_span,
                 "The DB span of the intensities 0..255, or auto: the log's (SeaNet ADspan), else 45 dB")
      ->capture_default_str();
  cmd.add_option("--smoothing", args.smoothing, "none | gaussian | median | mean (polar image, before detection)")
      ->capture_default_str();
  cmd.add_option("--smoothing-range", args.smoothing_range_m,
                 "Smoothing along the beam in METRES (Gaussian sigma, or the kernel's length)")
      ->capture_default_str();
  cmd.add_option("--smoothing-bearing", args.smoothing_bearing_deg,
                 "Smoothing across beams in DEGREES (Gaussian sigma, or the kernel's width)")
      ->capture_default_str();
  cmd.add_option("--cfar-training", args.cfar_training_m, "CFAR training window per side in METRES")
      ->capture_default_str();
  cmd.add_option("--cfar-guard", args.cfar_guard_m, "CFAR guard window per side in METRES")->capture_default_str();
  cmd.add_option("--ray", args.ray, "dda | bresenham")->capture_default_str();
  cmd.add_option("--aggregation", args.aggregation, "Inner nodes: max | mean")->capture_default_str();
  cmd.add_option("--max-range", args.max_range_m,
                 "Use beams up to this range in METRES: longer ones clear free space up to it, their obstacle dropped")
      ->capture_default_str();
  cmd.add_option("--format", args.format,
                 "Log format: auto (by extension: .mat, .csv, .V4LOG, .seanet, .bin) | mat | csv | v4log | seanet | "
                 "ping360 (a raw capture of any name)")
      ->capture_default_str();
  cmd.add_option("--beam-width", args.beam_width_deg,
                 "Horizontal beam width in DEGREES (default the sonar's: Tritech 3, Ping360 2): each beam clears its "
                 "wedge; 0 = one ray per beam (the paper)")
      ->capture_default_str()
      ->each([&args](const std::string&) { args.beam_width_given = true; });
  cmd.add_option("--range-tolerance", args.range_tolerance,
                 "A beam's free space ends this many METRES before its obstacle, or auto: a bin plus half a voxel plus the echo's rise (leading edge to peak)")
      ->capture_default_str();
  cmd.add_option("--max-voxel-updates", args.max_voxel_updates,
                 "Refuse a log that needs more VOXEL UPDATES than this (estimated before mapping)")
      ->capture_default_str();
  cmd.add_option("--hit-probability", args.hit_probability,
                 "P(occupied | echo), a PROBABILITY in (0.5, 1): 0.9 lets one echo outweigh earlier free space")
      ->capture_default_str();
  cmd.add_flag("--3d", args.volume,
               "Map the whole beam volume (width x vertical aperture) into a 3D map instead of the sonar's plane");
  cmd.add_option("--vertical-aperture", args.vertical_aperture_deg,
                 "Vertical beam width in DEGREES for --3d (default the sonar's: Tritech 35, Ping360 25; SeaKing 40)")
      ->capture_default_str()
      ->each([&args](const std::string&) { args.vertical_aperture_given = true; });
  cmd.add_option("--free-aperture", args.free_aperture,
                 "--3d: vertical extent in DEGREES of the cone a beam clears (where its silence proves water), or "
                 "auto: half the vertical aperture")
      ->capture_default_str();
  cmd.add_option("--clear-without-obstacle", args.clear_without_obstacle,
                 "Whether a beam without an obstacle clears its wedge or cone up to where its echo shows water: yes | no | "
                 "auto (yes for the plane, no for --3d, where a grazing seabed returns below any threshold)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "yes", "no"}));
  cmd.add_option("--arc-evidence", args.arc_evidence,
                 "--3d: how an echo's evidence is shared over its shell: whole | uniform | pattern")
      ->capture_default_str();
  cmd.add_option("--threads", args.threads, "Threads tracing each sweep's free rays (the map is identical for any count)")
      ->capture_default_str()
      ->check(CLI::Range(1U, 64U));
  cmd.add_flag("-q,--quiet", args.quiet, "No progress bar");
  cmd.add_flag("--tank-report", args.tank_report,
               "Also print how well the occupied cells at z = 0 trace a rectangular tank's walls");
}

LogFormat inputFormat(const std::string& input, const std::string& format) {
  if (format != "auto") return parseLogFormat(format);
  if (const std::optional<LogFormat> by_extension = logFormatOfPath(input)) return *by_extension;
  throw FileError("'" + input + "': unknown sonar log type '" + std::filesystem::path(input).extension().string() +
                  "', expected .mat, .csv, .V4LOG, .seanet (SeaNet wire capture) or .bin (Ping360), or name it with "
                  "--format");
}

MapperOptions withSonarBeam(MapperOptions options, const MapArgs& args, LogFormat format) {
  const NominalBeam beam = nominalBeam(format);
  if (!args.beam_width_given) options.beam_width_rad = beam.width_rad;
  if (!args.vertical_aperture_given) options.vertical_aperture_rad = beam.vertical_aperture_rad;
  if (options.free_vertical_aperture_rad && *options.free_vertical_aperture_rad > options.vertical_aperture_rad) {
    throw ValueError("--free-aperture " + std::to_string(*options.free_vertical_aperture_rad / kRadPerDeg) +
                     " is wider than the vertical aperture");
  }
  options.validate();
  return options;
}

MapperOptions toMapperOptions(const MapArgs& args) {
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
  if (const std::optional<double> free_deg = autoOr(args.free_aperture, "--free-aperture", "degrees", false)) {
    requireWithin(*free_deg, 0.0, args.vertical_aperture_deg, true, false, "--free-aperture",
                  "degrees in (0, the vertical aperture]");
    options.free_vertical_aperture_rad = *free_deg * kRadPerDeg;
  }
  if (args.clear_without_obstacle != "auto") options.clear_without_obstacle = args.clear_without_obstacle == "yes";
  options.validate();
  return options;
}

}  // namespace sonarmap::cli
