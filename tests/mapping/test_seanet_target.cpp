// Obstacles survive: on the shared SeaNet sector log (../shared/data/seanet_sector_target.V4LOG, a
// target moving in to about 1.9 m over 17 passes of a 90° sector), the echoes of the last sweep are
// occupied cells of the final map, although earlier sweeps cleared that water many times.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "sonarmap/eval/last_sweep.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"

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
  std::size_t echoes = 0, occupied = 0;
  for (const LastSweepEcho& echo : lastSweepEchoes(log, mapper)) {
    ++echoes;
    occupied += echo.occupied;
    std::printf("[ seanet ] last sweep: echo at %.1f deg, %.2f m: %s\n", echo.bearing_rad * 180.0 / 3.14159265358979,
                echo.range_m, echo.occupied ? "occupied" : "not occupied");
    EXPECT_NEAR(echo.range_m, 1.9, 0.15);  // the target, nothing else (measured 1.86–1.89 m)
  }
  EXPECT_GE(echoes, 4U);  // measured 5 beams across the target
  EXPECT_EQ(occupied, echoes);
}

}  // namespace
}  // namespace sonarmap
