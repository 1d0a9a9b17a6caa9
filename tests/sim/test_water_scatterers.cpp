// The simulator's water scatterers (fish, bubbles, suspended matter): strong discrete echoes in open
// water at the density asked for, and their options checked.
#include <gtest/gtest.h>

#include <cstddef>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {
namespace {

MsisSimulationOptions turns(std::size_t count) {
  MsisSimulationOptions options;
  options.turns = count;
  return options;
}

/// Bins of `log` in [from_m, to_m) at least `level` counts.
std::size_t binsAtLeast(const SonarLog& log, double from_m, double to_m, int level) {
  std::size_t count = 0;
  for (const Beam& beam : log.beams) {
    for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
      const double range_m = (static_cast<double>(i) + 0.5) * beam.bin_length_m;
      count += range_m >= from_m && range_m < to_m && beam.intensities[i] >= level ? 1 : 0;
    }
  }
  return count;
}

TEST(simMsis, WaterScatterersAddStrongDiscreteEchoesInOpenWaterAtTheirDensity) {
  const Scene open = builtinScene("open-water");
  MsisSimulationOptions options = turns(2);
  const SonarLog quiet = simulateMsis(open, options).log;
  options.echo.water_scatterers_per_m = 0.0;  // explicitly none: the same draws, the same log
  EXPECT_EQ(simulateMsis(open, options).log.beams[7].intensities, quiet.beams[7].intensities);
  options.echo.water_scatterers_per_m = 2.0;
  options.echo.water_scatterer_level_db = 12.0;
  const SonarLog cluttered = simulateMsis(open, options).log;
  // Quiet open water never reaches 150 counts past the band; with 2 scatterers per metre over
  // 1–4.5 m (7 per beam) of mean 12 dB above the noise, many bins of many beams do.
  EXPECT_EQ(binsAtLeast(quiet, 1.0, 4.5, 150), 0U);
  const std::size_t strong = binsAtLeast(cluttered, 1.0, 4.5, 150);
  EXPECT_GT(strong, quiet.beams.size());
  options.echo.water_scatterers_per_m = 0.5;
  const std::size_t sparse = binsAtLeast(simulateMsis(open, options).log, 1.0, 4.5, 150);
  EXPECT_LT(sparse, strong / 2);  // a quarter of the density: about a quarter of the bins
  EXPECT_GT(sparse, 0U);
  options.echo.water_scatterers_per_m = -1.0;
  EXPECT_THROW(simulateMsis(open, options), ValueError);
  options.echo.water_scatterers_per_m = 1.0;
  options.echo.water_scatterer_level_db = 0.0;
  EXPECT_THROW(simulateMsis(open, options), ValueError);
}

}  // namespace
}  // namespace sonarmap
