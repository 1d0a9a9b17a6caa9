/// @file map_sonar_log.cpp
/// mapSonarLog (sonar_mapper.hpp): a log's beams through an OnlineMapper, the one mapping path.

#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/online_mapper.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {

namespace {
/// mapSonarLog's body: every beam of the log through `online` (an OnlineMapper), in order.
SonarMapper mapThroughOnline(const SonarLog& log, OnlineMapper& online) {
  for (const Beam& beam : log.beams) online.addBeam(beam);
  online.finish();
  SonarMapper mapper = std::move(online).release();
  mapper.stats().beams_skipped = log.skipped_beams;
  const MappingStats& stats = mapper.stats();
  if (stats.beams_used == 0 && stats.out_of_map > 0) {  // an empty map is no answer
    throw ValueError("no beam could be mapped: " +
                     mappingWarnings(stats, mapper.options(), mapper.map().resolution_m()).front());
  }
  return mapper;
}

/// Reports progress as (sweeps done, sweeps the log holds), when asked.
OnlineMapper::SweepCallback progressOf(const SonarLog& log, const MapperOptions& options, const ProgressCallback& progress) {
  if (!progress) return {};
  const auto min_beams = static_cast<std::size_t>(std::max(1, options.detector.background.min_beams));
  const std::size_t total = groupSweeps(log.beams, min_beams).size();
  return [progress, total](std::size_t done) { progress(done, total); };
}
}  // namespace

SonarMapper mapSonarLog(const SonarLog& log, const MapperOptions& options, const ProgressCallback& progress) {
  const MapperOptions resolved = resolveForLog(options, log);
  checkWorkBudget(log, resolved);
  OnlineMapper online(resolved, OnlineIntegration::kSweep, progressOf(log, options, progress));
  return mapThroughOnline(log, online);
}

SonarMapper mapSonarLog(const SonarLog& log, const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body,
                        const MapperOptions& options, const ProgressCallback& progress) {
  const NavInterpolator checked(nav);  // checks the track once: throws ValueError when it is invalid
  const MapperOptions resolved = resolveForLog(options, log);
  checkWorkBudget(log, resolved);
  OnlineMapper online(resolved, sonar_to_body, OnlineIntegration::kSweep, progressOf(log, options, progress));
  for (const NavSample& fix : nav) online.addNavFix(fix);
  return mapThroughOnline(log, online);
}

}  // namespace sonarmap
