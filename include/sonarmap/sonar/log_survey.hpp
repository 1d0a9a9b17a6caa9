#pragma once
/// @file log_survey.hpp
/// What mapping needs to know of a whole log before its first beam (the automatic resolution, the
/// work budget, the options' warnings, the progress bar, the clock's overlap with a navigation),
/// gathered in one pass over its beams without holding them: a log of hours is mapped from a
/// BeamSource in the memory of its map, then a second pass maps it.

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "sonarmap/sonar/beam_source.hpp"
#include "sonarmap/sonar/range_scales.hpp"

namespace sonarmap {

/// A log's beams summed up (surveyLog).
struct LogSurvey {
  std::size_t beams = 0;
  std::vector<RangeScale> scales;  ///< rangeScales of the log
  double reach_m = 0.0;            ///< its longest beam, bins × bin length, metres
  /// The earliest and latest beam time, seconds (0 without beams).
  double earliest_s = 0.0, latest_s = 0.0;
  std::size_t sweeps = 0;  ///< groupSweeps(beams, min_beams).size()
  /// Beams whose time lies within the span asked for (surveyLog's `span`); all of them without one.
  std::size_t beams_in_span = 0;
};

/// Surveys the log `pass` goes over (one pass).
/// @param min_beams  the detector's smallest sweep (BackgroundOptions::min_beams), for `sweeps`.
/// @param span       [first, last] seconds: counts the beams within it (a navigation's span).
LogSurvey surveyLog(const BeamPass& pass, std::size_t min_beams = 1,
                    const std::optional<std::pair<double, double>>& span = std::nullopt);

}  // namespace sonarmap
