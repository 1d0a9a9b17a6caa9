/// @file mapping_warnings.cpp
/// What a user needs to hear about a finished mapping (see sonar_mapper.hpp, mappingWarnings).

#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

#include "sonarmap/core/key.hpp"
#include "sonarmap/mapping/local_origin.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"

namespace sonarmap {
namespace {

std::string format(const char* pattern, ...) {
  char text[640];
  va_list arguments;
  va_start(arguments, pattern);
  std::vsnprintf(text, sizeof text, pattern, arguments);
  va_end(arguments);
  return text;
}

/// Why beams found no obstacle, from the diagnostics and the calibration.
std::string likelyCause(const MappingStats& stats) {
  const DetectionDiagnostics& d = stats.detection;
  const MappingStats::Calibration& c = stats.calibration;
  if (c.min_range_m >= d.reach_m) {
    return format("the detector's minimum range (%.3g m; --min-range) is beyond "
                  "the log's reach (%.3g m)",
                  c.min_range_m, d.reach_m);
  }
  if (d.echoes_before_min_range > 0) {
    return format("%zu beams have echoes above the threshold between the self-reflection band's end and the "
                  "detector's minimum range (%.2f .. %.2f m in their sweeps), which hides them: they may be walls "
                  "nearer than it (lower --min-range or --max-near-field, or leave them on auto)",
                  d.echoes_before_min_range, d.hidden_from_m, d.hidden_to_m);
  }
  if (d.echoes_too_short > 0) {
    return format("%zu beams have echoes above the threshold that are shorter than the minimum echo length "
                  "(lower --min-echo-length)",
                  d.echoes_too_short);
  }
  return format("no echo rose %.1f dB above the background (the threshold from --false-alarm, on an intensity "
                "scale of %.1f dB: if the sonar's span differs, set --intensity-span; or raise --false-alarm)",
                c.threshold_db, c.span_db);
}

}  // namespace

std::vector<std::string> mappingWarnings(const MappingStats& stats, const MapperOptions& options, double resolution_m) {
  std::vector<std::string> lines;
  const std::size_t tried = stats.beams_used + stats.out_of_map;
  if (stats.out_of_map > 0 && 2 * stats.out_of_map >= tried) {
    const double needed_m = resolution_m * stats.farthest_m / mapHalfExtent_m(resolution_m);
    lines.push_back(format("%zu of %zu beams reach outside the map: at %g m voxels it spans ±%.3g m, the beams reach "
                           "%.3g m; a resolution of at least %.3g m fits them (--resolution; auto chooses one from the "
                           "log's reach)",
                           stats.out_of_map, tried, resolution_m, mapHalfExtent_m(resolution_m), stats.farthest_m,
                           needed_m));
  }
  const DetectionDiagnostics& d = stats.detection;
  if (d.beams > 0 && d.obstacles == 0) {
    lines.push_back(format("no obstacle in %zu beams: %s", d.beams, likelyCause(stats).c_str()));
  } else if (d.beams > 0 && 4 * d.obstacles < d.echoes_before_min_range + d.echoes_too_short) {
    lines.push_back(format("only %zu obstacles in %zu beams, far fewer than the echoes suggest: %s", d.obstacles, d.beams,
                           likelyCause(stats).c_str()));
  } else if (d.beams > 0 && 4 * d.echoes_before_min_range > d.beams) {
    lines.push_back(format("%zu of %zu beams have echoes above the threshold between the self-reflection band's end "
                           "and the detector's minimum range (%.2f .. %.2f m in their sweeps): obstacles nearer than "
                           "it are missed (lower --min-range or --max-near-field, or leave them on auto)",
                           d.echoes_before_min_range, d.beams, d.hidden_from_m, d.hidden_to_m));
  }
  if (stats.beams_clipped > 0 && 2 * stats.beams_clipped >= stats.beams_used) {
    lines.push_back(format("%zu of %zu beams reach beyond the maximum range (%g m): they clear free space up to it "
                           "and lose their obstacles (--max-range)",
                           stats.beams_clipped, stats.beams_used, options.max_range_m));
  }
  if (stats.beams_uncalibrated > 0) {
    lines.push_back(format("%zu beams were not mapped: their range scale or gain was used for fewer than %d beams in a "
                           "row before any whole sweep of it, too few bearings to calibrate on (the range knob's "
                           "passing stops)",
                           stats.beams_uncalibrated, options.detector.background.min_beams));
  }
  if (stats.beams_without_nav > 0) {
    lines.push_back(format("%zu beams lie outside the navigation's time span and were skipped", stats.beams_without_nav));
  }
  return lines;
}

}  // namespace sonarmap
