/// @file slam_mapping.cpp
/// mapSonarLogWithSlam (slam_mapping.hpp).

#include "sonarmap/slam/slam_mapping.hpp"

#include <utility>

#include "sonarmap/mapping/detected_log.hpp"

namespace sonarmap {

SlamMapping mapSonarLogWithSlam(const SonarLog& log, const NavTrack& dead_reckoning,
                                const Eigen::Isometry3d& sonar_to_body, const MapperOptions& options,
                                const SlamOptions& slam, const ProgressCallback& progress) {
  slam.validate();
  const DetectedLog detected = detectSonarLog(log, options);  // once, for the scans and the map
  SlamResult result = localize(detected, dead_reckoning, sonar_to_body, slam);
  SonarMapper mapper = mapDetectedLog(detected, result.trajectory, sonar_to_body, progress);
  return {std::move(mapper), std::move(result)};
}

}  // namespace sonarmap
