#pragma once
/// @file detected_log.hpp
/// A log's sweeps detected once (the pipeline is detect, then model, then integrate): the
/// detection stage of mapSonarLog (sonar_mapper.hpp) kept for whatever needs the same detections
/// before the map is made. Localization (`map --slam`) forms its scans from them and the map is
/// then integrated from them with the corrected trajectory: every sweep is detected once.

#include <cstddef>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/core/progress.hpp"
#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/polar_image.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {

class SonarMapper;

/// One sweep as the mapper detected it (OnlineMapper: its grouping of beams into sweeps, its
/// calibration per head setting).
struct DetectedSweep {
  /// The sweep's polar image (rows: beams in recording order; columns: bins) as the detector saw
  /// it: self-reflection removed and smoothed in place (SonarMapper::detectSweep).
  PolarImage polar;
  SweepDetection detection;   ///< one BeamDetection per row of `polar`, and the sweep's calibration
  HeadSetting setting;        ///< of its beams (range scale and gain)
  std::size_t first_beam = 0; ///< index of its first beam in the log (SonarLog::beams)
};

/// Every sweep of a log, detected.
struct DetectedLog {
  MapperOptions options;              ///< the options detected with, resolved for the log (resolveForLog)
  std::vector<DetectedSweep> sweeps;  ///< in recording order
  /// Beams of a head setting used too briefly to calibrate on, before any whole sweep of it: not
  /// detected (MappingStats::beams_uncalibrated).
  std::size_t beams_uncalibrated = 0;
  std::size_t beams_skipped = 0;  ///< malformed beams the reader dropped (SonarLog::skipped_beams)
};

/// Detects every sweep of `log` exactly as mapSonarLog does (the same sweeps, calibrations and
/// detections), without integrating them. Memory: the log's polar images (one byte per bin).
/// @throws ValueError for invalid options, a sweep that mixes bin lengths, or a log whose longest
///         beam needs more voxel updates than options.max_voxel_updates_per_beam (checkWorkBudget).
DetectedLog detectSonarLog(const SonarLog& log, const MapperOptions& options = {});

/// Integrates a detected log from a moving vehicle: each beam placed with the sonar's pose at its
/// time, nedToMap() · bodyToNed(t) · sonar_to_body, bodyToNed(t) interpolated from `nav`
/// (navigation.hpp). The map is mapSonarLog(log, nav, sonar_to_body, detected.options)'s, byte for
/// byte. `progress` counts sweeps.
/// @throws ValueError for a navigation track that is empty, non-finite or not strictly increasing
///         in time, or when no beam could be mapped because every one reaches outside the map.
SonarMapper mapDetectedLog(const DetectedLog& detected, const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body,
                           const ProgressCallback& progress = {});

}  // namespace sonarmap
