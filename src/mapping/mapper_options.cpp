/// @file mapper_options.cpp
/// MapperOptions validation, the automatic resolution and the work budget (see mapper_options.hpp).

#include "sonarmap/mapping/mapper_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kAutoVoxelsPerReach = 256.0;
constexpr double kFinestAutoResolution_m = 0.001;

std::string metres(double value_m) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g m", value_m);
  return text;
}

void checkOptionalLength(const std::optional<double>& value_m, const char* name, bool zero_allowed) {
  if (!value_m) return;
  const bool ok = std::isfinite(*value_m) && (zero_allowed ? *value_m >= 0.0 : *value_m > 0.0);
  if (!ok) {
    throw ValueError(std::string(name) + " must be a finite number of metres " + (zero_allowed ? ">= 0" : "> 0") +
                     ", got " + std::to_string(*value_m));
  }
}

/// The voxel updates of one beam reaching `range_m` (> 0) whose wedge spans `width_rad`, at `voxel_m`
/// (estimateVoxelUpdates' terms).
double beamUpdates(const MapperOptions& options, double voxel_m, double range_m, double width_rad) {
  if (options.beam_model == BeamModel::kVolume) {
    // The free cone (its core) in volume, the shell (whole aperture) in area.
    const double free_rad = std::max(freeVerticalAperture_rad(options), voxel_m / range_m);
    const double aperture_rad = std::max(options.vertical_aperture_rad, voxel_m / range_m);
    return width_rad * free_rad * range_m * range_m * range_m / (3.0 * voxel_m * voxel_m * voxel_m) +
           aperture_rad * range_m * range_m / (voxel_m * voxel_m);
  }
  return width_rad * range_m * range_m / (2.0 * voxel_m * voxel_m) + range_m / voxel_m;
}

/// Whether mapping at options.resolution_m (set) surely fits options.max_voxel_updates, told from
/// the survey's reaches alone: each wedge taken as wide as the beam (or a voxel), never narrower
/// than the bearing step estimateVoxelUpdates limits it to, so the bound is at least the estimate
/// (with a margin for the sums' rounding). False when the survey could not count the reaches.
bool surelyFits(const LogSurvey& survey, const MapperOptions& options) {
  if (!survey.reaches_counted) return false;
  const double voxel_m = *options.resolution_m;
  double bound = 0.0;
  for (const auto& [reach_m, beams] : survey.beams_by_reach) {
    const double range_m = std::min(reach_m, options.max_range_m);
    if (!(range_m > 0.0)) continue;
    bound += static_cast<double>(beams) * beamUpdates(options, voxel_m, range_m, std::max(options.beam_width_rad, voxel_m / range_m));
  }
  return bound * (1.0 + 1e-9) <= options.max_voxel_updates;
}

}  // namespace

RayAlgorithm parseRayAlgorithm(std::string_view name) {
  if (name == "dda") return RayAlgorithm::kDDA;
  if (name == "bresenham") return RayAlgorithm::kBresenham;
  throw ValueError("unknown ray algorithm '" + std::string(name) + "', expected dda or bresenham");
}

BeamModel parseBeamModel(std::string_view name) {
  if (name == "planar") return BeamModel::kPlanar;
  if (name == "volume") return BeamModel::kVolume;
  throw ValueError("unknown beam model '" + std::string(name) + "', expected planar or volume");
}

double freeVerticalAperture_rad(const MapperOptions& options) { return 0.5 * options.vertical_aperture_rad; }

bool clearsWithoutObstacle(const MapperOptions& options) { return options.beam_model == BeamModel::kPlanar; }

void MapperOptions::validate() const {
  checkOptionalLength(resolution_m, "resolution", false);
  checkOptionalLength(self_reflection_range_m, "self-reflection range", true);
  checkOptionalLength(range_tolerance_m, "range tolerance", true);
  if (!(max_range_m > 0.0)) throw ValueError("max range must be > 0 m, got " + std::to_string(max_range_m));
  if (!(beam_width_rad >= 0.0 && beam_width_rad < std::numbers::pi)) {
    throw ValueError("beam width must be within [0, pi) rad, got " + std::to_string(beam_width_rad));
  }
  if (beam_model == BeamModel::kVolume && !(vertical_aperture_rad > 0.0 && vertical_aperture_rad < std::numbers::pi)) {
    throw ValueError("vertical aperture must be within (0, pi) rad, got " + std::to_string(vertical_aperture_rad));
  }
  if (!(max_voxel_updates > 0.0)) {
    throw ValueError("the voxel-update budget must be > 0, got " + std::to_string(max_voxel_updates));
  }
  if (std::isinf(water_surface_depth_m)) throw ValueError("the water surface's depth must be finite or NaN (unknown)");
  if (threads == 0) throw ValueError("the mapper needs at least one thread");
  smoothing.validate();
  detector.validate();
  extended.validate();
  octree.occupancy.validate();
}

double autoResolution_m(double reach_m) {
  if (!(std::isfinite(reach_m) && reach_m > 0.0)) {
    throw ValueError("automatic resolution: the sonar's reach must be > 0 m, got " + std::to_string(reach_m));
  }
  const double target = std::max(reach_m / kAutoVoxelsPerReach, kFinestAutoResolution_m);
  // Nearest of 1, 2, 5 × 10^k in log scale.
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  double best = decade;
  for (const double step : {1.0, 2.0, 5.0, 10.0}) {
    if (std::abs(std::log(step * decade / target)) < std::abs(std::log(best / target))) best = step * decade;
  }
  return best;
}

double logReach_m(const SonarLog& log, double max_range_m) {
  double reach_m = 0.0;
  for (const Beam& beam : log.beams) {
    reach_m = std::max(reach_m, static_cast<double>(beam.intensities.size()) * beam.bin_length_m);
  }
  return std::min(reach_m, max_range_m);
}

double logReach_m(const LogSurvey& survey, double max_range_m) { return std::min(survey.reach_m, max_range_m); }

AutoResolution autoResolutionForLog(const LogSurvey& survey, const BeamPass& pass, const MapperOptions& options) {
  options.validate();
  const RangeScale* most_used = mostUsedRangeScale(survey.scales);
  if (most_used == nullptr || !(most_used->reach_m > 0.0)) {
    throw ValueError("automatic resolution: the log has no beam with bins");
  }
  AutoResolution chosen{0.0, *most_used, survey.scales.size(), survey.beams, false};
  chosen.scale.reach_m = std::min(chosen.scale.reach_m, options.max_range_m);
  chosen.resolution_m = autoResolution_m(chosen.scale.reach_m);
  const double coarsest_m = autoResolution_m(logReach_m(survey, options.max_range_m));
  MapperOptions trial = options;
  for (;;) {
    trial.resolution_m = chosen.resolution_m;
    if (chosen.resolution_m >= coarsest_m || surelyFits(survey, trial) ||
        estimateVoxelUpdates(survey, pass, trial) <= options.max_voxel_updates) {
      break;
    }
    // The next of 1, 2, 5 × 10^k: ×2 from a 1 or a 5, ×2.5 from a 2.
    const double mantissa = chosen.resolution_m / std::pow(10.0, std::floor(std::log10(chosen.resolution_m) + 1e-9));
    chosen.resolution_m *= std::abs(mantissa - 2.0) < 0.01 ? 2.5 : 2.0;
    chosen.coarsened = true;
  }
  return chosen;
}

AutoResolution autoResolutionForLog(const SonarLog& log, const MapperOptions& options) {
  const BeamPass pass = passOver(log);
  return autoResolutionForLog(surveyLog(pass), pass, options);
}

MapperOptions resolveForLog(const MapperOptions& options, const LogSurvey& survey, const BeamPass& pass) {
  options.validate();
  MapperOptions resolved = options;
  if (!resolved.resolution_m) resolved.resolution_m = autoResolutionForLog(survey, pass, options).resolution_m;
  return resolved;
}

MapperOptions resolveForLog(const MapperOptions& options, const SonarLog& log) {
  const BeamPass pass = passOver(log);
  return resolveForLog(options, surveyLog(pass), pass);
}

namespace {
/// The resolution estimates use: the option, else the automatic one (a 1 mm floor for a log
/// without bins).
double resolutionOrAuto_m(const LogSurvey& survey, const BeamPass& pass, const MapperOptions& options) {
  if (options.resolution_m) return *options.resolution_m;
  const double reach_m = logReach_m(survey, options.max_range_m);
  return reach_m > 0.0 ? autoResolutionForLog(survey, pass, options).resolution_m : autoResolution_m(1e-3);
}
}  // namespace

double estimateVoxelUpdates(const LogSurvey& survey, const BeamPass& pass, const MapperOptions& options) {
  const double voxel_m = resolutionOrAuto_m(survey, pass, options);
  // Each beam's wedge spans at most the bearing step to the next beam (the last: from the one
  // before; a log of one beam: 2π): a beam is counted when the next arrives.
  double updates = 0.0;
  std::size_t seen = 0;
  double held_range_m = 0.0, held_bearing_rad = 0.0, step_rad = kTwoPi;
  auto count = [&](double range_m, double step) {
    if (!(range_m > 0.0)) return;
    // The union of overlapping wedges grows by one bearing step per beam; a ray is a line of voxels.
    updates += beamUpdates(options, voxel_m, range_m, std::min(std::max(options.beam_width_rad, voxel_m / range_m), step));
  };
  pass([&](const Beam& beam) {
    const double range_m = std::min(static_cast<double>(beam.intensities.size()) * beam.bin_length_m, options.max_range_m);
    if (seen > 0) {
      step_rad = std::abs(std::remainder(beam.bearing_rad - held_bearing_rad, kTwoPi));
      count(held_range_m, step_rad);
    }
    held_range_m = range_m;
    held_bearing_rad = beam.bearing_rad;
    ++seen;
  });
  if (seen > 0) count(held_range_m, step_rad);
  return updates;
}

double estimateVoxelUpdates(const SonarLog& log, const MapperOptions& options) {
  const BeamPass pass = passOver(log);
  return estimateVoxelUpdates(surveyLog(pass), pass, options);
}

std::vector<std::string> optionWarnings(const MapperOptions& options, const SonarLog& log) {
  return optionWarnings(options, surveyLog(passOver(log)));
}

std::vector<std::string> optionWarnings(const MapperOptions& options, const LogSurvey& survey) {
  std::vector<std::string> lines;
  const double reach_m = logReach_m(survey, std::numeric_limits<double>::infinity());
  if (!(reach_m > 0.0)) return lines;
  char text[320];
  auto add = [&](const char* what, double value_m) {
    std::snprintf(text, sizeof text, "%s %s is beyond the log's reach (%s): %s", what, metres(value_m).c_str(),
                  metres(reach_m).c_str(), "nothing can be detected");
    lines.emplace_back(text);
  };
  if (options.detector.min_range_m && *options.detector.min_range_m >= reach_m) {
    add("the detector's minimum range (--min-range)", *options.detector.min_range_m);
  }
  if (options.self_reflection_range_m && *options.self_reflection_range_m >= reach_m) {
    add("the self-reflection range (--self-reflection)", *options.self_reflection_range_m);
  }
  if (options.detector.background.min_echo_length_m >= reach_m) {
    add("the minimum echo length (--min-echo-length)", options.detector.background.min_echo_length_m);
  }
  if (options.max_range_m < reach_m) {
    std::snprintf(text, sizeof text,
                  "the maximum range (--max-range) %s is below the log's reach (%s): beams reaching farther clear "
                  "free space up to it and lose their obstacles",
                  metres(options.max_range_m).c_str(), metres(reach_m).c_str());
    lines.emplace_back(text);
  }
  if (options.resolution_m && *options.resolution_m > 0.25 * reach_m) {
    std::snprintf(text, sizeof text,
                  "the resolution (--resolution) %s is coarser than a quarter of the log's reach (%s): each beam "
                  "covers only a few voxels (auto would choose %s)",
                  metres(*options.resolution_m).c_str(), metres(reach_m).c_str(), metres(autoResolution_m(reach_m)).c_str());
    lines.emplace_back(text);
  }
  if (options.smoothing.kind != Smoothing::kNone && options.smoothing.range_m > 0.5 * reach_m) {
    std::snprintf(text, sizeof text,
                  "the smoothing along the beam (--smoothing-range) %s is longer than half the log's reach (%s)",
                  metres(options.smoothing.range_m).c_str(), metres(reach_m).c_str());
    lines.emplace_back(text);
  }
  return lines;
}

void checkWorkBudget(const LogSurvey& survey, const BeamPass& pass, const MapperOptions& options) {
  const bool resolved = options.resolution_m.has_value();
  if (resolved && surelyFits(survey, options)) return;
  const double updates = estimateVoxelUpdates(survey, pass, options);
  if (updates <= options.max_voxel_updates) return;
  // Updates scale with 1 / resolution² (planar) or 1 / resolution³ (volume): the finest that fits.
  const double voxel_m = resolutionOrAuto_m(survey, pass, options);
  MapperOptions automatic = options;
  automatic.resolution_m.reset();
  const double power = options.beam_model == BeamModel::kVolume ? 1.0 / 3.0 : 0.5;
  const double fits_m = voxel_m * std::pow(updates / options.max_voxel_updates, power);
  char text[400];
  std::snprintf(text, sizeof text,
                "mapping this log at %s voxels needs about %.3g voxel updates, more than the budget of %.3g "
                "(max_voxel_updates, --max-voxel-updates): use a resolution of at least %s (auto: %s), or raise "
                "the budget",
                metres(voxel_m).c_str(), updates, options.max_voxel_updates, metres(fits_m).c_str(),
                metres(resolutionOrAuto_m(survey, pass, automatic)).c_str());
  throw ValueError(text);
}

void checkWorkBudget(const SonarLog& log, const MapperOptions& options) {
  const BeamPass pass = passOver(log);
  checkWorkBudget(surveyLog(pass), pass, options);
}

}  // namespace sonarmap
