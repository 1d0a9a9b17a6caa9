/// @file slam_mapping.cpp
/// mapSonarLogWithSlam (slam_mapping.hpp).

#include "sonarmap/slam/slam_mapping.hpp"

#include <utility>

namespace sonarmap {

SlamMapping mapSonarLogWithSlam(const SonarLog& log, const NavTrack& dead_reckoning,
                                const Eigen::Isometry3d& sonar_to_body, const MapperOptions& options,
                                const SlamOptions& slam, const ProgressCallback& progress) {
  SlamResult result = localize(log, dead_reckoning, sonar_to_body, options, slam);
  SonarMapper mapper = mapSonarLog(log, result.trajectory, sonar_to_body, options, progress);
  return {std::move(mapper), std::move(result)};
}

}  // namespace sonarmap
