/// @file map_sonar_log.cpp
/// mapSonarLog (sonar_mapper.hpp), detectSonarLog and mapDetectedLog (detected_log.hpp): a log's
/// beams through an OnlineMapper, the one mapping path.

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/detected_log.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/beam_source.hpp"
#include "sonarmap/sonar/log_survey.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {

namespace {
/// The finished mapper of `online`, the reader's `skipped_beams` counted.
/// @throws ValueError when no beam could be mapped because every one reaches outside the map.
SonarMapper releaseMapped(OnlineMapper& online, std::size_t skipped_beams) {
  online.finish();
  SonarMapper mapper = std::move(online).release();
  mapper.stats().beams_skipped = skipped_beams;
  const MappingStats& stats = mapper.stats();
  if (stats.beams_used == 0 && stats.out_of_map > 0) {  // an empty map is no answer
    throw ValueError("no beam could be mapped: " +
                     mappingWarnings(stats, mapper.options(), mapper.map().resolution_m()).front());
  }
  return mapper;
}

/// mapSonarLog's body: every beam of `source` through `online` (an OnlineMapper), in order.
SonarMapper mapThroughOnline(BeamSource& source, OnlineMapper& online) {
  // A log is read faster than its sweeps are detected: keep every core detecting.
  online.setDetectionsAhead(std::max(1U, std::thread::hardware_concurrency()));
  source.rewind();
  while (std::optional<Beam> beam = source.next()) online.addBeam(std::move(*beam));
  return releaseMapped(online, source.header().skipped_beams);
}

/// Reports progress as (sweeps done, sweeps the log holds), when asked.
OnlineMapper::SweepCallback progressOf(const LogSurvey& survey, const ProgressCallback& progress) {
  if (!progress) return {};
  return [progress, total = survey.sweeps](std::size_t done) { progress(done, total); };
}
}  // namespace

std::size_t surveyMinBeams(const MapperOptions& options) {
  return static_cast<std::size_t>(std::max(1, options.detector.background.min_beams));
}

SonarMapper mapSonarLog(BeamSource& source, const LogSurvey& survey, const MapperOptions& options,
                        const ProgressCallback& progress) {
  const MapperOptions resolved = mappingOptionsForLog(options, survey);
  OnlineMapper online(resolved, OnlineIntegration::kSweep, progressOf(survey, progress));
  return mapThroughOnline(source, online);
}

SonarMapper mapSonarLog(BeamSource& source, const LogSurvey& survey, const NavTrack& nav,
                        const Eigen::Isometry3d& sonar_to_body, const MapperOptions& options,
                        const ProgressCallback& progress) {
  const NavInterpolator checked(nav);  // checks the track once: throws ValueError when it is invalid
  const MapperOptions resolved = mappingOptionsForLog(options, survey);
  OnlineMapper online(resolved, sonar_to_body, OnlineIntegration::kSweep, progressOf(survey, progress));
  for (const NavSample& fix : nav) online.addNavFix(fix);
  return mapThroughOnline(source, online);
}

SonarMapper mapSonarLog(const SonarLog& log, const MapperOptions& options, const ProgressCallback& progress) {
  LogBeamSource source(log);
  return mapSonarLog(source, surveyLog(passOver(log), surveyMinBeams(options)), options, progress);
}

SonarMapper mapSonarLog(const SonarLog& log, const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body,
                        const MapperOptions& options, const ProgressCallback& progress) {
  LogBeamSource source(log);
  return mapSonarLog(source, surveyLog(passOver(log), surveyMinBeams(options)), nav, sonar_to_body, options, progress);
}

DetectedLog detectSonarLog(const SonarLog& log, const MapperOptions& options) {
  DetectedLog detected;
  detected.options = mappingOptionsForLog(options, log);
  detected.beams_skipped = log.skipped_beams;
  OnlineMapper online(detected.options, OnlineIntegration::kSweep);
  online.detectOnly([&detected](DetectedSweep&& sweep) {
    sweep.detection.calibration.water_evidence = {};  // for rows detected later; integration needs none
    sweep.detection.calibration.water_level = {};
    detected.sweeps.push_back(std::move(sweep));
  });
  for (const Beam& beam : log.beams) online.addBeam(beam);
  online.finish();
  detected.beams_uncalibrated = online.mapper().stats().beams_uncalibrated;
  return detected;
}

SonarMapper mapDetectedLog(const DetectedLog& detected, const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body,
                           const ProgressCallback& progress) {
  const NavInterpolator checked(nav);  // checks the track once: throws ValueError when it is invalid
  OnlineMapper::SweepCallback on_sweep;
  if (progress) {
    on_sweep = [progress, total = detected.sweeps.size()](std::size_t done) { progress(done, total); };
  }
  OnlineMapper online(detected.options, sonar_to_body, OnlineIntegration::kSweep, std::move(on_sweep));
  for (const NavSample& fix : nav) online.addNavFix(fix);
  for (const DetectedSweep& sweep : detected.sweeps) online.addDetectedSweep(sweep);
  online.mapper().stats().beams_uncalibrated += detected.beams_uncalibrated;
  return releaseMapped(online, detected.beams_skipped);
}

}  // namespace sonarmap
