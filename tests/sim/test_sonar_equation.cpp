// The simulated seabed against the sonar equation: a level head over a flat Lambertian seabed
// writes, bin by bin, the echo level the closed form of acoustics/sonar_equation.hpp gives
// (pulse-limited bottom reverberation, Urick 1983 ch. 8), for two heads and two altitudes, and a
// head tilted 25°; the noise's mean power and its counts' distribution (acoustics/speckle.hpp)
// against the simulator's noise alone. The closed form alone: tests/acoustics/test_sonar_equation.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "sonarmap/acoustics/speckle.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/acoustic_parameters.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/sonar_equation.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap {
namespace {

/// The head's echoes of the seabed alone: no speckle, noise, multipath, near-field band or
/// blanking, vertical rays dense enough (W / 60) for the footprints to overlap smoothly, and an
/// A/D mapping wide enough to hold the seabed's level.
MsisSimulationOptions seabedOnly(const SonarPreset& preset) {
  MsisSimulationOptions options;
  options.head = preset.head;
  options.echo = preset.echo;
  options.echo.vertical.rays = std::max(options.echo.vertical.rays, 78);
  options.echo.speckle_looks = 0;
  options.echo.noise_level_db = -300.0;
  options.echo.multipath = false;
  options.echo.self_reflection_end_m = 0.0;
  options.echo.blanking_m = 0.0;
  options.echo.ad_low_db = -90.0;  // a seabed this far lies below the heads' own A/D floors
  options.echo.ad_span_db = 90.0;
  options.turns = 1;
  return options;
}

/// The mean power of the bins around `range_m` (± 2 % of the range) over every beam, from the
/// intensities through the A/D mapping (intensity = 255 (10 log P − ad_low) / span).
double meanPower(const MsisSimulation& run, const EchoModelOptions& echo, double bin_m, double range_m,
                 double max_bearing_rad = 4.0) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const Beam& beam : run.log.beams) {
    if (std::abs(std::remainder(beam.bearing_rad, 2.0 * std::numbers::pi)) > max_bearing_rad) continue;
    for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
      const double r = (static_cast<double>(i) + 0.5) * bin_m;
      if (std::abs(r - range_m) > 0.02 * range_m) continue;
      sum += std::pow(10.0, (echo.ad_low_db + beam.intensities[i] / 255.0 * echo.ad_span_db) / 10.0);
      ++count;
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

TEST(simSonarEquation, SimulatedSeabedFollowsTheClosedForm) {
  for (const char* name : {"micron", "imagenex-881a"}) {
    const SonarPreset preset = sonarPreset(name);
    const MsisSimulationOptions options = seabedOnly(preset);
    const double reach_m = preset.head.range_m;
    // Altitudes that put the seabed in the aperture over most of the range.
    for (const double share : {0.4, 0.6}) {
      const double altitude_m = share * reach_m * std::sin(0.3 * preset.head.vertical_beam_width_rad);
      const Scene seabed{{Plane{{0.0, 0.0, -altitude_m}, Eigen::Vector3d::UnitZ(), 0.5}}};
      const MsisSimulation run = simulateMsis(seabed, options);
      // Where the seabed lies within the flat top of the vertical pattern and the pulse-limited
      // annulus: from just past the aperture's lower edge to the range's end.
      const double first_m = altitude_m / std::sin(0.45 * preset.head.vertical_beam_width_rad);
      int checked = 0;
      for (double range_m = first_m; range_m < 0.95 * reach_m; range_m += 0.1 * reach_m) {
        const double expected = flatSeabedEchoPower(options.head, options.echo, altitude_m, 0.5, range_m);
        const double simulated = meanPower(run, options.echo, options.head.binLength_m(), range_m);
        ASSERT_GT(expected, 0.0) << name << " " << range_m;
        // Within 0.7 dB but at the lowest grazing angles (1.1 dB at 4.8°), where one ray spreads its
        // energy evenly over 0.5 m of range while the closed form falls as r⁻³ across it.
        EXPECT_NEAR(10.0 * std::log10(simulated / expected), 0.0, 1.25)
            << name << ", altitude " << altitude_m << " m, range " << range_m << " m: simulated "
            << 10.0 * std::log10(simulated) << " dB, sonar equation " << 10.0 * std::log10(expected) << " dB";
        ++checked;
      }
      EXPECT_GE(checked, 3) << name;
    }
  }
}

// A head tilted 25° down (the quay3d tilted-loop mission's mounting), the beams that look the way
// it tilts: the seabed crosses the whole vertical aperture.
TEST(simSonarEquation, TiltedHeadSeesTheSeabedAsTheClosedFormSays) {
  const SonarPreset preset = sonarPreset("micron");
  MsisSimulationOptions options = seabedOnly(preset);
  const double tilt_rad = 25.0 * std::numbers::pi / 180.0;
  options.sonar_to_body = defaultSonarToBody() * Eigen::AngleAxisd(-tilt_rad, Eigen::Vector3d::UnitY());  // nose down
  const double altitude_m = 2.0;
  const MsisSimulation run = simulateMsis(Scene{{Plane{{0.0, 0.0, -altitude_m}, Eigen::Vector3d::UnitZ(), 0.5}}}, options);
  int checked = 0;
  for (double range_m = 3.0; range_m < 4.8; range_m += 0.25) {
    const double expected = flatSeabedEchoPower(options.head, options.echo, altitude_m, 0.5, range_m, tilt_rad);
    const double simulated = meanPower(run, options.echo, options.head.binLength_m(), range_m, 2.0 * std::numbers::pi / 180.0);
    ASSERT_GT(expected, 0.0) << range_m;
    EXPECT_NEAR(10.0 * std::log10(simulated / expected), 0.0, 1.25) << "range " << range_m;
    ++checked;
  }
  EXPECT_GE(checked, 7);
}

// Noise alone (open water: nothing within reach), speckled as the head speckles it: its mean
// power after the TVG is what meanNoisePower says.
TEST(simSonarEquation, NoiseAloneHasTheMeanPowerOfTheClosedForm) {
  const SonarPreset preset = sonarPreset("seaking-30");
  MsisSimulationOptions options;
  options.head = preset.head;
  options.echo = preset.echo;
  options.echo.multipath = false;
  options.echo.self_reflection_end_m = 0.0;
  options.echo.blanking_m = 0.0;
  options.echo.ad_low_db = options.echo.noise_level_db - 20.0;  // the noise well inside the A/D span
  options.echo.ad_span_db = 90.0;
  options.turns = 2;
  const MsisSimulation run = simulateMsis(builtinScene("open-water", preset.head.range_m), options);
  for (const double share : {0.2, 0.5, 0.9}) {
    const double range_m = share * preset.head.range_m;
    const double simulated = meanPower(run, options.echo, options.head.binLength_m(), range_m);
    EXPECT_NEAR(10.0 * std::log10(simulated / meanNoisePower(options.echo, range_m)), 0.0, 0.3) << range_m;
  }
  EXPECT_THROW(meanNoisePower(options.echo, 0.0), ValueError);
}

// Noise alone, counted by the A/D: in one bin over many beams the counts follow the quantised
// Gamma speckle of the acoustics layer (speckle.hpp) with the noise's mean power and the head's
// speckle looks: the simulator's moving mean of speckle_looks exponential draws has that marginal.
TEST(simSonarEquation, NoiseCountsFollowTheQuantisedSpeckleDistribution) {
  const SonarPreset preset = sonarPreset("micron");
  MsisSimulationOptions options;
  options.head = preset.head;
  options.echo = preset.echo;
  options.echo.self_reflection_end_m = 0.0;
  options.echo.blanking_m = 0.0;
  options.echo.ad_low_db = options.echo.noise_level_db - 10.0;  // the noise in the A/D span
  options.echo.ad_span_db = 30.0;
  options.echo.multipath = false;  // nothing within reach: one ray a beam is enough
  options.echo.horizontal.rays = 1;
  options.echo.vertical.rays = 1;
  options.turns = 20;  // 4,000 beams
  const MsisSimulation run = simulateMsis(builtinScene("open-water", preset.head.range_m), options);
  for (const std::size_t bin : {40u, 200u, 390u}) {
    const double range_m = (static_cast<double>(bin) + 0.5) * options.head.binLength_m();
    const std::array<double, 256> model = quantisedSpeckleDistribution(
        meanNoisePower(options.echo, range_m), options.echo.speckle_looks, receiverScaleOf(options.echo));
    std::array<double, 256> observed{};
    for (const Beam& beam : run.log.beams) observed[beam.intensities[bin]] += 1.0 / static_cast<double>(run.log.beams.size());
    // Kolmogorov–Smirnov distance of the counts' distribution functions: 0.026 is its 1 % critical
    // value for 4,000 independent draws (1.63 / √4000); the model is within 0.017 in these bins,
    // with its mean 1 dB high 0.15 off, with two looks instead of three 0.08.
    double model_cdf = 0.0, observed_cdf = 0.0, distance = 0.0;
    for (std::size_t counts = 0; counts < 256; ++counts) {
      model_cdf += model[counts];
      observed_cdf += observed[counts];
      distance = std::max(distance, std::abs(model_cdf - observed_cdf));
    }
    EXPECT_LT(distance, 0.026) << "bin " << bin;
  }
}

}  // namespace
}  // namespace sonarmap
