#pragma once
/// @file last_sweep.hpp
/// Do obstacles survive? The echoes of a log's last sweep, detected as the mapper detected them,
/// and whether each is an occupied cell of the final map: a target seen in the last
/// sweeps must be occupied, however often earlier sweeps cleared that water.

#include <vector>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"

namespace sonarmap {

/// One echo of the last sweep.
struct LastSweepEcho {
  double bearing_rad = 0.0;  ///< sonar frame, [0, 2π)
  double range_m = 0.0;      ///< the echo's leading edge, metres
  bool occupied = false;     ///< the map's cell there (sonar plane, static sonar at the origin) is occupied
};

/// The last sweep of `log` (split and merged as mapSonarLog does), detected with `mapper`'s
/// options (SonarMapper::detect), each echo looked up in `mapper`'s map at
/// (range cos bearing, range sin bearing, 0): a static sonar at the map's origin, as
/// mapSonarLog(log) places it. Empty when the log has no sweep.
/// @throws ValueError as SonarMapper::detect.
std::vector<LastSweepEcho> lastSweepEchoes(const SonarLog& log, const SonarMapper& mapper);

}  // namespace sonarmap
