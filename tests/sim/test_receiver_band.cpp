// The simulated receiver's self-reflection band (msis_simulator.hpp, step 5): its level spread
// from ping to ping (EchoModelOptions::self_reflection_spread_db) moves a dB ring-down's end with it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {
namespace {

TEST(simReceiverBand, SpreadRingDownEndsFartherOnLouderPings) {
  // No speckle and noise: a 100-count plateau to 0.3 m falling linearly in dB to 0 counts at 0.8 m;
  // each ping's level shifted by a normal draw of 3 dB: its plateau by 3 dB × 255 / 45 counts and
  // its end by 0.5 m × 3 dB / (100 counts × 45 dB / 255 counts) = 8.5 cm (σ), the same shift.
  MsisSimulationOptions options;
  options.turns = 1;
  options.echo.speckle_looks = 0;
  options.echo.noise_level_db = -300.0;
  options.echo.self_reflection_taper_m = 0.5;
  options.echo.self_reflection_taper_db = true;
  const Scene empty{{Plane{{0.0, 0.0, -100.0}, Eigen::Vector3d::UnitZ(), 0.5}}};
  const double per_db = 255.0 / options.echo.ad_span_db;
  for (const double spread_db : {0.0, 3.0}) {
    options.echo.self_reflection_spread_db = spread_db;
    const MsisSimulation run = simulateMsis(empty, options);
    double sum = 0.0, squares = 0.0;
    for (const Beam& beam : run.log.beams) {
      const auto plateau_bin = static_cast<std::size_t>(0.2 / beam.bin_length_m);
      const double plateau_db = (beam.intensities[plateau_bin] - 100.0) / per_db;
      int last = 0;  // the band's last lit bin
      for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
        if (beam.intensities[i] > 0) last = static_cast<int>(i);
      }
      // The end lies within the bin after the last lit one's centre: ±0.44 dB, and a count's rounding.
      const double end_db = ((last + 1.0) * beam.bin_length_m - 0.8) / 0.5 * 100.0 / per_db;
      EXPECT_NEAR(end_db, plateau_db, 0.7) << "the band's end moves with its level";
      sum += plateau_db;
      squares += plateau_db * plateau_db;
    }
    const auto n = static_cast<double>(run.log.beams.size());
    const double mean_db = sum / n;
    EXPECT_NEAR(mean_db, 0.0, 0.5) << spread_db;
    EXPECT_NEAR(std::sqrt(squares / n - mean_db * mean_db), spread_db, 0.3 * spread_db + 0.05) << spread_db;
  }
  options.echo.self_reflection_spread_db = -1.0;
  EXPECT_THROW(simulateMsis(empty, options), ValueError);
}

}  // namespace
}  // namespace sonarmap
