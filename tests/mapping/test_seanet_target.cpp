// Obstacles survive: on the shared SeaNet sector log (../shared/data/seanet_sector_target.V4LOG, a
// target moving in to about 1.9 m over 17 passes of a 90° sector), the echoes of the last sweep are
// occupied cells of the final map, although earlier sweeps cleared that water many times.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/polar.hpp"

namespace sonarmap {
namespace {

TEST(mappingSeaNetTarget, TheTargetsLastPositionIsOccupied) {
  const std::string path = std::string(SONARMAP_SHARED_DATA) + "/seanet_sector_target.V4LOG";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
  const SonarLog log = readSonarLog(path);
  const SonarMapper mapper = mapSonarLog(log);
  EXPECT_EQ(mapper.stats().sweeps, 17U);
  EXPECT_DOUBLE_EQ(mapper.map().resolution_m(), 0.05);  // automatic: 10.2 m of reach
  // The last sweep, detected as the mapper detected it.
  const std::vector<SweepRange> sweeps = mergeShortSweeps(splitSweeps(log.beams), 20);
  PolarImage last = makePolarImage(log.beams, sweeps.back().first, sweeps.back().last_exclusive);
  const std::vector<BeamDetection> detections = mapper.detect(last);
  std::size_t echoes = 0, occupied = 0;
  for (int r = 0; r < last.rows(); ++r) {
    const BeamDetection& d = detections[static_cast<std::size_t>(r)];
    if (!d.hasObstacle()) continue;
    ++echoes;
    const double bearing = last.bearing_rad[static_cast<std::size_t>(r)];
    const Eigen::Vector3d point(d.range_m * std::cos(bearing), d.range_m * std::sin(bearing), 0.0);
    const bool is_occupied = mapper.map().occupancyAt(point) == Occupancy::kOccupied;
    occupied += is_occupied;
    std::printf("[ seanet ] last sweep: echo at %.1f deg, %.2f m: %s\n", bearing * 180.0 / 3.14159265358979,
                d.range_m, is_occupied ? "occupied" : "not occupied");
    EXPECT_NEAR(d.range_m, 1.9, 0.15);  // the target, nothing else (measured 1.86–1.89 m)
  }
  EXPECT_GE(echoes, 4U);  // measured 5 beams across the target
  EXPECT_EQ(occupied, echoes);
}

}  // namespace
}  // namespace sonarmap
