/// @file last_sweep.cpp
/// The last sweep's echoes in the final map (see last_sweep.hpp).

#include "sonarmap/eval/last_sweep.hpp"

#include <cmath>

#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {

std::vector<LastSweepEcho> lastSweepEchoes(const SonarLog& log, const SonarMapper& mapper) {
  std::vector<LastSweepEcho> echoes;
  const auto min_beams = static_cast<std::size_t>(std::max(1, mapper.options().detector.background.min_beams));
  const std::vector<SweepRange> sweeps = groupSweeps(log.beams, min_beams);
  if (sweeps.empty()) return echoes;
  PolarImage last = makePolarImage(log.beams, sweeps.back().first, sweeps.back().last_exclusive);
  const std::vector<BeamDetection> detections = mapper.detect(last);
  const Eigen::Isometry3d static_to_map = staticSonarToMap();  // a log without navigation
  for (int r = 0; r < last.rows(); ++r) {
    const BeamDetection& detection = detections[static_cast<std::size_t>(r)];
    if (!detection.hasObstacle()) continue;
    LastSweepEcho echo{last.bearing_rad[static_cast<std::size_t>(r)], detection.range_m, false};
    const Eigen::Vector3d point =
        static_to_map * Eigen::Vector3d(echo.range_m * std::cos(echo.bearing_rad), echo.range_m * std::sin(echo.bearing_rad), 0.0);
    echo.occupied = mapper.map().occupancyAt(point) == Occupancy::kOccupied;
    echoes.push_back(echo);
  }
  return echoes;
}

}  // namespace sonarmap
