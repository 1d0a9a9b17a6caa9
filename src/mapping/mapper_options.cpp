/// @file mapper_options.cpp
/// MapperOptions validation, the automatic resolution and the work budget per beam (see mapper_options.hpp).

#include "sonarmap/mapping/mapper_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

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

/// The voxel updates of one beam reaching `range_m` (> 0) at `voxel_m` (estimateVoxelUpdatesPerBeam).
double beamUpdates(const MapperOptions& options, double voxel_m, double range_m) {
  const double width_rad = std::max(options.beam_width_rad, voxel_m / range_m);
  if (mapsBeamVolume(options)) {
    // The free cone (its core) in volume, the shell (whole aperture) in area.
    const double free_rad = std::max(freeVerticalAperture_rad(options), voxel_m / range_m);
    const double aperture_rad = std::max(options.vertical_aperture_rad, voxel_m / range_m);
    return width_rad * free_rad * range_m * range_m * range_m / (3.0 * voxel_m * voxel_m * voxel_m) +
           aperture_rad * range_m * range_m / (voxel_m * voxel_m);
  }
  return width_rad * range_m * range_m / (2.0 * voxel_m * voxel_m) + range_m / voxel_m;
}

/// The finest voxel edge, metres, at which a beam reaching `range_m` fits `budget` updates, rounded
/// up to three significant digits (what a user types): the updates fall as the voxel grows, so
/// bisection (in log scale) between a micrometre and the range, where a beam is a voxel or two.
double finestFitting_m(const MapperOptions& options, double range_m, double budget) {
  double fits_m = range_m, too_fine_m = kFinestAutoResolution_m * 1e-3;
  if (beamUpdates(options, too_fine_m, range_m) <= budget) return too_fine_m;
  for (int i = 0; i < 100 && fits_m / too_fine_m > 1.0 + 1e-9; ++i) {
    const double mid_m = std::sqrt(fits_m * too_fine_m);
    (beamUpdates(options, mid_m, range_m) <= budget ? fits_m : too_fine_m) = mid_m;
  }
  const double digit_m = std::pow(10.0, std::floor(std::log10(fits_m)) - 2.0);
  return std::ceil(fits_m / digit_m) * digit_m;
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
  if (name == "inversion") return BeamModel::kInversion;
  throw ValueError("unknown beam model '" + std::string(name) + "', expected planar, volume or inversion");
}

double freeVerticalAperture_rad(const MapperOptions& options) { return 0.5 * options.vertical_aperture_rad; }

bool mapsBeamVolume(const MapperOptions& options) { return options.beam_model != BeamModel::kPlanar; }

bool clearsWithoutObstacle(const MapperOptions& options) { return options.beam_model == BeamModel::kPlanar; }

void MapperOptions::validate() const {
  checkOptionalLength(resolution_m, "resolution", false);
  checkOptionalLength(self_reflection_range_m, "self-reflection range", true);
  checkOptionalLength(range_tolerance_m, "range tolerance", true);
  if (!(max_range_m > 0.0)) throw ValueError("max range must be > 0 m, got " + std::to_string(max_range_m));
  if (!(beam_width_rad >= 0.0 && beam_width_rad < std::numbers::pi)) {
    throw ValueError("beam width must be within [0, pi) rad, got " + std::to_string(beam_width_rad));
  }
  if (mapsBeamVolume(*this) && !(vertical_aperture_rad > 0.0 && vertical_aperture_rad < std::numbers::pi)) {
    throw ValueError("vertical aperture must be within (0, pi) rad, got " + std::to_string(vertical_aperture_rad));
  }
  if (!(max_voxel_updates_per_beam > 0.0)) {
    throw ValueError("the voxel-update budget per beam must be > 0, got " + std::to_string(max_voxel_updates_per_beam));
  }
  if (std::isinf(water_surface_depth_m)) throw ValueError("the water surface's depth must be finite or NaN (unknown)");
  if (threads == 0) throw ValueError("the mapper needs at least one thread");
  smoothing.validate();
  detector.validate();
  extended.validate();
  inversion.validate();
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

AutoResolution autoResolutionForLog(const LogSurvey& survey, const MapperOptions& options) {
  options.validate();
  const RangeScale* most_used = mostUsedRangeScale(survey.scales);
  if (most_used == nullptr || !(most_used->reach_m > 0.0)) {
    throw ValueError("automatic resolution: the log has no beam with bins");
  }
  AutoResolution chosen{0.0, *most_used, survey.scales.size(), survey.beams, false};
  chosen.scale.reach_m = std::min(chosen.scale.reach_m, options.max_range_m);
  chosen.resolution_m = autoResolution_m(chosen.scale.reach_m);
  const double reach_m = logReach_m(survey, options.max_range_m);
  const double coarsest_m = autoResolution_m(reach_m);
  while (chosen.resolution_m < coarsest_m &&
         beamUpdates(options, chosen.resolution_m, reach_m) > options.max_voxel_updates_per_beam) {
    // The next of 1, 2, 5 × 10^k: ×2 from a 1 or a 5, ×2.5 from a 2.
    const double mantissa = chosen.resolution_m / std::pow(10.0, std::floor(std::log10(chosen.resolution_m) + 1e-9));
    chosen.resolution_m *= std::abs(mantissa - 2.0) < 0.01 ? 2.5 : 2.0;
    chosen.coarsened = true;
  }
  return chosen;
}

AutoResolution autoResolutionForLog(const SonarLog& log, const MapperOptions& options) {
  return autoResolutionForLog(surveyLog(passOver(log)), options);
}

MapperOptions resolveForLog(const MapperOptions& options, const LogSurvey& survey) {
  options.validate();
  MapperOptions resolved = options;
  if (!resolved.resolution_m) resolved.resolution_m = autoResolutionForLog(survey, options).resolution_m;
  return resolved;
}

MapperOptions resolveForLog(const MapperOptions& options, const SonarLog& log) {
  return resolveForLog(options, surveyLog(passOver(log)));
}

double estimateVoxelUpdatesPerBeam(const MapperOptions& options, double range_m) {
  options.validate();
  if (!options.resolution_m) throw ValueError("voxel updates per beam: the resolution must be set");
  if (!(std::isfinite(range_m) && range_m > 0.0)) {
    throw ValueError("voxel updates per beam: the range must be a finite number of metres > 0, got " +
                     std::to_string(range_m));
  }
  return beamUpdates(options, *options.resolution_m, std::min(range_m, options.max_range_m));
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
  // --min-range sets both the detector's minimum range and the bins zeroed before detection.
  const double near_m = std::max(options.detector.min_range_m.value_or(0.0), options.self_reflection_range_m.value_or(0.0));
  if (near_m >= reach_m) add("the minimum range (--min-range)", near_m);
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

void checkWorkBudget(const LogSurvey& survey, const MapperOptions& options) {
  const double reach_m = logReach_m(survey, options.max_range_m);
  if (!(reach_m > 0.0)) return;
  MapperOptions automatic = options;
  automatic.resolution_m.reset();
  const double auto_m = autoResolutionForLog(survey, automatic).resolution_m;
  const double voxel_m = options.resolution_m.value_or(auto_m);
  const double updates = beamUpdates(options, voxel_m, reach_m);
  if (updates <= options.max_voxel_updates_per_beam) return;
  char text[480];
  std::snprintf(text, sizeof text,
                "mapping this log at %s voxels needs about %.3g voxel updates for its longest beam (%s), more than "
                "the budget of %.3g per beam (max_voxel_updates_per_beam, --max-voxel-updates-per-beam): use a "
                "resolution of at least %s (auto: %s), or raise the budget",
                metres(voxel_m).c_str(), updates, metres(reach_m).c_str(), options.max_voxel_updates_per_beam,
                metres(finestFitting_m(options, reach_m, options.max_voxel_updates_per_beam)).c_str(),
                metres(auto_m).c_str());
  throw ValueError(text);
}

void checkWorkBudget(const SonarLog& log, const MapperOptions& options) {
  checkWorkBudget(surveyLog(passOver(log)), options);
}

MapperOptions mappingOptionsForLog(const MapperOptions& options, const LogSurvey& survey) {
  MapperOptions resolved = resolveForLog(options, survey);
  checkWorkBudget(survey, resolved);
  return resolved;
}

MapperOptions mappingOptionsForLog(const MapperOptions& options, const SonarLog& log) {
  return mappingOptionsForLog(options, surveyLog(passOver(log)));
}

}  // namespace sonarmap
