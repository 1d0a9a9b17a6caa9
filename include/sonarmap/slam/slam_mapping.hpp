#pragma once
/// @file slam_mapping.hpp
/// A map that follows the corrected trajectory: the log's sweeps detected once (detectSonarLog,
/// detected_log.hpp), localized from those detections (localizer.hpp), then integrated through the
/// one mapping path (mapDetectedLog) with the corrected navigation, so every beam is placed with the
/// corrected pose at its own time, 2D or 3D alike.

#include <Eigen/Geometry>

#include "sonarmap/core/progress.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/slam/localizer.hpp"

namespace sonarmap {

/// A map and the trajectory it was built with.
struct SlamMapping {
  SonarMapper mapper;
  SlamResult slam;
};

/// Localizes `log` on `dead_reckoning` (localize; an empty track: no navigation, the vehicle
/// believed still and its motion estimated from the scans alone) and maps it with the corrected
/// trajectory (mapDetectedLog: mapSonarLog's map with that track, from the same detections).
/// `progress` counts the mapping's sweeps.
/// @throws ValueError as localize and mapSonarLog.
SlamMapping mapSonarLogWithSlam(const SonarLog& log, const NavTrack& dead_reckoning,
                                const Eigen::Isometry3d& sonar_to_body, const MapperOptions& options,
                                const SlamOptions& slam = {}, const ProgressCallback& progress = {});

}  // namespace sonarmap
