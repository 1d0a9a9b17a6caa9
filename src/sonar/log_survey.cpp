/// @file log_survey.cpp
/// surveyLog (see log_survey.hpp).

#include "sonarmap/sonar/log_survey.hpp"

#include <algorithm>

#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {

LogSurvey surveyLog(const BeamPass& pass, std::size_t min_beams, const std::optional<std::pair<double, double>>& span) {
  LogSurvey survey;
  SweepSplitter splitter;
  SweepGrouper grouper(min_beams);
  pass([&](const Beam& beam) {
    countRangeScale(survey.scales, beam, survey.beams);
    survey.reach_m = std::max(survey.reach_m, static_cast<double>(beam.intensities.size()) * beam.bin_length_m);
    survey.earliest_s = survey.beams == 0 ? beam.time_s : std::min(survey.earliest_s, beam.time_s);
    survey.latest_s = survey.beams == 0 ? beam.time_s : std::max(survey.latest_s, beam.time_s);
    if (!span || (beam.time_s >= span->first && beam.time_s <= span->second)) ++survey.beams_in_span;
    const bool starts = splitter.startsSweep(beam);
    if (grouper.add(starts, headSettingOf(beam)) > 0) ++survey.sweeps;
    ++survey.beams;
  });
  if (grouper.finish() > 0) ++survey.sweeps;
  return survey;
}

}  // namespace sonarmap
