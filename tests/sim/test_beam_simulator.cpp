// One beam at a time (MsisBeamSimulator): the beams of simulateMsis for the same times, bearings
// and seed; new settings between beams; the checks on its inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/beam_simulator.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap {
namespace {

TEST(simBeamSimulator, BeamByBeamIsTheRunsLog) {
  MsisSimulationOptions options;
  options.turns = 2;
  options.seed = 7;
  const MsisSimulation run = simulateMsis(builtinScene("tank"), options);
  MsisBeamSimulator simulator(builtinScene("tank"), options.head, options.echo, options.trajectory, options.sonar_to_body, 7);
  ASSERT_EQ(run.log.beams.size(), 400U);
  for (std::size_t i = 0; i < run.log.beams.size(); ++i) {
    const Beam& expected = run.log.beams[i];
    const Beam beam = simulator.simulate(expected.time_s, options.head.bearingOf(i));
    ASSERT_EQ(beam.intensities, expected.intensities) << "beam " << i;
    ASSERT_EQ(beam.bearing_rad, expected.bearing_rad);
    ASSERT_EQ(beam.bin_length_m, expected.bin_length_m);
  }
}

TEST(simBeamSimulator, NewSettingsApplyToTheNextBeam) {
  MsisHeadOptions head;
  MsisBeamSimulator simulator(builtinScene("tank"), head, EchoModelOptions{}, staticTrajectory(), defaultSonarToBody(), 1);
  EXPECT_EQ(simulator.simulate(0.0, 0.0).intensities.size(), 399U);
  head.range_m = 10.0;
  head.bins = 200;
  head.logs_pulse_length = true;
  simulator.setHead(head, EchoModelOptions{});
  const Beam beam = simulator.simulate(0.1, -0.5 * std::numbers::pi);
  EXPECT_EQ(beam.intensities.size(), 200U);
  EXPECT_DOUBLE_EQ(beam.bin_length_m, 0.05);
  EXPECT_NEAR(beam.bearing_rad, 1.5 * std::numbers::pi, 1e-12);  // wrapped to [0, 2π)
  ASSERT_TRUE(beam.pulse_length_m.has_value());
  head.bins = 0;
  EXPECT_THROW(simulator.setHead(head, EchoModelOptions{}), ValueError);
  EXPECT_EQ(simulator.head().bins, 200);  // refused settings change nothing
  EXPECT_THROW(simulator.simulate(std::nan(""), 0.0), ValueError);
}

TEST(simBeamSimulator, RefusesAnEmptyTrajectoryAndABentMounting) {
  EXPECT_THROW(MsisBeamSimulator(builtinScene("tank"), {}, {}, Trajectory{}, defaultSonarToBody(), 1), ValueError);
  Eigen::Isometry3d bent = defaultSonarToBody();
  bent.linear() *= 2.0;
  EXPECT_THROW(MsisBeamSimulator(builtinScene("tank"), {}, {}, staticTrajectory(), bent, 1), ValueError);
}

}  // namespace
}  // namespace sonarmap
