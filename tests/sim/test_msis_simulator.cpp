// The MSIS simulator: the log's layout and timing, determinism, the CRAS-like structure of the
// simulated tank (wall echoes where the geometry puts them, the surface ring, the self-reflection
// band, multipath behind the walls), poses of a moving vehicle, and option checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

MsisSimulationOptions turns(std::size_t count) {
  MsisSimulationOptions options;
  options.turns = count;
  return options;
}

/// Options without speckle and noise: what is left is the geometry of the echoes.
MsisSimulationOptions noiseless(std::size_t count) {
  MsisSimulationOptions options = turns(count);
  options.echo.speckle_looks = 0;
  options.echo.noise_level_db = -300.0;
  return options;
}

/// Mean intensity of `beam` over ranges [from_m, to_m).
double meanIntensity(const Beam& beam, double from_m, double to_m) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
    const double range_m = (static_cast<double>(i) + 0.5) * beam.bin_length_m;
    if (range_m >= from_m && range_m < to_m) {
      sum += beam.intensities[i];
      ++count;
    }
  }
  return count > 0 ? sum / count : 0.0;
}

/// Highest intensity of `beam` over ranges [from_m, to_m), and the range of its bin.
std::pair<int, double> peak(const Beam& beam, double from_m, double to_m) {
  std::pair<int, double> best{-1, 0.0};
  for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
    const double range_m = (static_cast<double>(i) + 0.5) * beam.bin_length_m;
    if (range_m >= from_m && range_m < to_m && beam.intensities[i] > best.first) best = {beam.intensities[i], range_m};
  }
  return best;
}

/// Range of the first bin of `beam` from `from_m` on with an intensity ≥ `threshold`; −1 if none.
double firstAbove(const Beam& beam, int threshold, double from_m) {
  for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
    const double range_m = (static_cast<double>(i) + 0.5) * beam.bin_length_m;
    if (range_m >= from_m && beam.intensities[i] >= threshold) return range_m;
  }
  return -1.0;
}

/// FNV-1a hash of every beam's time, bearing and bin length (their bits) and intensities.
std::uint64_t checksum(const SonarLog& log) {
  std::uint64_t hash = 14695981039346656037ULL;
  auto add = [&hash](std::uint64_t byte) { hash = (hash ^ byte) * 1099511628211ULL; };
  for (const Beam& beam : log.beams) {
    for (const double value : {beam.time_s, beam.bearing_rad, beam.bin_length_m}) {
      const auto bits = std::bit_cast<std::uint64_t>(value);
      for (int shift = 0; shift < 64; shift += 8) add((bits >> shift) & 0xFFU);
    }
    for (const std::uint8_t intensity : beam.intensities) add(intensity);
  }
  return hash;
}

/// Range of the first surface along the horizontal ray at `bearing_rad` from the map origin.
SceneHit horizontalHit(const Scene& scene, double bearing_rad) {
  // A static head: the sonar frame placed by staticSonarToMap (bearing b at map angle −b).
  const Eigen::Vector3d along = staticSonarToMap().linear() * Eigen::Vector3d(std::cos(bearing_rad), std::sin(bearing_rad), 0.0);
  const auto hit = firstHit(scene, Eigen::Vector3d::Zero(), along, 100.0);
  EXPECT_TRUE(hit);
  return hit.value_or(SceneHit{});
}

TEST(simMsis, MicronDefaultsGiveTheCrasLayout) {
  const MsisSimulation run = simulateMsis(builtinScene("tank"), turns(2));
  ASSERT_EQ(run.log.beams.size(), 400U);
  EXPECT_EQ(run.log.skipped_beams, 0U);
  const std::vector<SweepRange> sweeps = splitSweeps(run.log.beams);
  ASSERT_EQ(sweeps.size(), 2U);
  EXPECT_EQ(sweeps[0].size(), 200U);
  EXPECT_EQ(sweeps[1].size(), 200U);
  for (std::size_t i = 0; i < run.log.beams.size(); ++i) {
    const Beam& beam = run.log.beams[i];
    ASSERT_EQ(beam.intensities.size(), 399U);
    EXPECT_DOUBLE_EQ(beam.bin_length_m, 5.0 / 399.0);
    EXPECT_NEAR(beam.time_s, 0.043 * static_cast<double>(i), 1e-9);
    EXPECT_GE(beam.bearing_rad, 0.0);
    EXPECT_LT(beam.bearing_rad, 2.0 * std::numbers::pi);
    // The head turns counter-clockwise seen from above: bearings (clockwise, beam.hpp) decrease.
    EXPECT_NEAR(std::remainder(beam.bearing_rad + 1.8 * kDegree * static_cast<double>(i), 2.0 * std::numbers::pi), 0.0,
                1e-9);
  }
  // The ground truth travels with the log.
  EXPECT_EQ(run.scene.primitives.size(), builtinScene("tank").primitives.size());

  // The progress callback counts the beams; the log is the same with it.
  std::vector<std::size_t> done;
  const MsisSimulation counted = simulateMsis(builtinScene("tank"), turns(2), [&](std::size_t n, std::size_t total) {
    EXPECT_EQ(total, 400U);
    done.push_back(n);
  });
  ASSERT_EQ(done.size(), 400U);
  EXPECT_EQ(done.front(), 1U);
  EXPECT_EQ(done.back(), 400U);
  EXPECT_EQ(counted.log.beams.back().intensities, run.log.beams.back().intensities);
}

TEST(simMsis, DefaultTankAndHarbourLogsAreUnchanged) {
  // Checksums of what the defaults (the Micron, 360° turns, the 5 m scenes) write: they change
  // only on purpose. Bearings count clockwise (beam.hpp) while the simulated head turns
  // counter-clockwise, so a turn's bearings decrease.
  EXPECT_EQ(checksum(simulateMsis(builtinScene("tank"), turns(2)).log), 0xd01dab525ddf3aaULL);
  MsisSimulationOptions moving = turns(1);
  moving.seed = 3;
  moving.trajectory = constantVelocityTrajectory(NavSample{}, Eigen::Vector3d(0.0, 0.3, 0.0));
  EXPECT_EQ(checksum(simulateMsis(builtinScene("harbour"), moving).log), 0xa4b8d6fe5e36c8cbULL);
}

TEST(simMsis, ClockwiseHeadAndOtherRangeScale) {
  MsisSimulationOptions options = turns(1);
  options.head.counter_clockwise = false;
  options.head.start_bearing_rad = 0.5;
  options.head.range_m = 10.0;
  options.head.bins = 200;
  options.head.step_rad = 3.6 * kDegree;
  const MsisSimulation run = simulateMsis(builtinScene("tank"), options);
  ASSERT_EQ(run.log.beams.size(), 100U);
  EXPECT_DOUBLE_EQ(run.log.beams[0].bearing_rad, 0.5);
  EXPECT_NEAR(run.log.beams[1].bearing_rad, 0.5 + 3.6 * kDegree, 1e-12);  // clockwise: bearings increase
  EXPECT_NEAR(run.log.beams[20].bearing_rad, 0.5 + 72.0 * kDegree, 1e-9);
  EXPECT_EQ(run.log.beams[0].intensities.size(), 200U);
  EXPECT_DOUBLE_EQ(run.log.beams[0].bin_length_m, 0.05);
  EXPECT_EQ(splitSweeps(run.log.beams).size(), 1U);
}

/// Bearing difference to − from, wrapped to (−π, π].
double wrappedDifference(double from_rad, double to_rad) { return std::remainder(to_rad - from_rad, 2.0 * std::numbers::pi); }

TEST(simMsis, SectorHeadSweepsBackAndForthBetweenItsLimits) {
  // A 90° sector centred on 350° (it straddles bearing 0), 1.8° steps: 50 steps, 51 beams a pass.
  for (const bool counter_clockwise : {true, false}) {
    SCOPED_TRACE(counter_clockwise ? "counter-clockwise" : "clockwise");
    MsisSimulationOptions options = noiseless(4);
    options.head.sector_width_rad = 90.0 * kDegree;
    options.head.sector_center_rad = 350.0 * kDegree;
    options.head.counter_clockwise = counter_clockwise;
    options.head.start_bearing_rad = 2.0;  // ignored by a sector head
    ASSERT_TRUE(options.head.isSector());
    ASSERT_EQ(options.head.sectorSteps(), 50U);
    ASSERT_EQ(options.head.beamsPerTurn(), 51U);
    const MsisSimulation run = simulateMsis(builtinScene("tank"), options);
    const std::vector<Beam>& beams = run.log.beams;
    ASSERT_EQ(beams.size(), 4U * 51U);  // `turns` counts passes across the sector
    const double first_sign = counter_clockwise ? -1.0 : 1.0;  // counter-clockwise: bearings decrease
    EXPECT_NEAR(wrappedDifference(350.0 * kDegree, beams[0].bearing_rad), -first_sign * 45.0 * kDegree, 1e-9);
    for (std::size_t i = 0; i < beams.size(); ++i) {
      EXPECT_GE(beams[i].bearing_rad, 0.0);
      EXPECT_LT(beams[i].bearing_rad, 2.0 * std::numbers::pi);
      EXPECT_LE(std::abs(wrappedDifference(350.0 * kDegree, beams[i].bearing_rad)), 45.0 * kDegree + 1e-9) << i;
      EXPECT_NEAR(beams[i].time_s, 0.043 * static_cast<double>(i), 1e-9);
      if (i == 0) continue;
      const double step = wrappedDifference(beams[i - 1].bearing_rad, beams[i].bearing_rad);
      if (i % 51 == 0) {
        // The head pings again at the limit it reached, then reverses (as in the SeaNet log).
        EXPECT_NEAR(step, 0.0, 1e-9) << i;
        EXPECT_NEAR(std::abs(wrappedDifference(350.0 * kDegree, beams[i].bearing_rad)), 45.0 * kDegree, 1e-9) << i;
      } else {
        const double pass_sign = (i / 51) % 2 == 0 ? first_sign : -first_sign;
        EXPECT_NEAR(step, pass_sign * 1.8 * kDegree, 1e-9) << i;
      }
    }
    // One sweep per pass; the repeated limit beam (a zero step) closes the sweep it ends.
    const std::vector<SweepRange> sweeps = splitSweeps(beams);
    ASSERT_EQ(sweeps.size(), 4U);
    for (std::size_t k = 1; k < sweeps.size(); ++k) EXPECT_EQ(sweeps[k].first, 51U * k + 1U);
    EXPECT_EQ(sweeps.back().last_exclusive, beams.size());
  }
}

TEST(simMsis, FullWidthSectorIsAContinuousTurn) {
  MsisSimulationOptions options = turns(1);
  options.head.sector_width_rad = 360.0 * kDegree;
  options.head.sector_center_rad = 1.0;  // ignored by a 360° head
  EXPECT_FALSE(options.head.isSector());
  EXPECT_EQ(checksum(simulateMsis(builtinScene("tank"), options).log),
            checksum(simulateMsis(builtinScene("tank"), turns(1)).log));
}

TEST(simMsis, SameSeedSameLogOtherSeedOtherLog) {
  MsisSimulationOptions options = turns(1);
  options.seed = 7;
  const MsisSimulation a = simulateMsis(builtinScene("tank"), options);
  const MsisSimulation b = simulateMsis(builtinScene("tank"), options);
  options.seed = 8;
  const MsisSimulation c = simulateMsis(builtinScene("tank"), options);
  std::size_t differing_beams = 0;
  for (std::size_t i = 0; i < a.log.beams.size(); ++i) {
    EXPECT_EQ(a.log.beams[i].intensities, b.log.beams[i].intensities) << "beam " << i;
    differing_beams += a.log.beams[i].intensities != c.log.beams[i].intensities ? 1 : 0;
  }
  EXPECT_EQ(differing_beams, a.log.beams.size());
}

TEST(simMsis, SelfReflectionBandThenSilenceUntilTheRing) {
  const MsisSimulation run = simulateMsis(builtinScene("tank"), turns(1));
  std::vector<double> band, gap;
  for (const Beam& beam : run.log.beams) {
    EXPECT_EQ(beam.intensities[0], 0) << "transmit blanking";
    band.push_back(meanIntensity(beam, 0.05, 0.3));
    gap.push_back(meanIntensity(beam, 0.4, 1.0));
  }
  std::sort(band.begin(), band.end());
  std::sort(gap.begin(), gap.end());
  EXPECT_GT(band[band.size() / 10], 70.0);   // the band is bright in (nearly) every beam: ≈ 100
  EXPECT_LT(gap[gap.size() * 9 / 10], 3.0);  // and nothing follows it until the ring
}

TEST(simMsis, SelfReflectionBandTapersOverItsTaperLength) {
  // Open water (no echo), no speckle and noise: what is left is the band. A 0.5 m taper after a
  // plateau to 0.3 m: half the plateau's power (−3 dB) at 0.55 m, nothing from 0.8 m on.
  MsisSimulationOptions options = noiseless(1);
  options.head.step_rad = 90.0 * kDegree;
  options.echo.self_reflection_taper_m = 0.5;
  const Scene empty{{Plane{{0.0, 0.0, -100.0}, Eigen::Vector3d::UnitZ(), 0.5}}};
  const MsisSimulation run = simulateMsis(empty, options);
  const double per_db = 255.0 / options.echo.ad_span_db;
  for (const Beam& beam : run.log.beams) {
    EXPECT_NEAR(meanIntensity(beam, 0.1, 0.3), 100.0, 0.5);
    EXPECT_NEAR(meanIntensity(beam, 0.54, 0.56), 100.0 - 10.0 * std::log10(2.0) * per_db, 2.0);
    EXPECT_GT(meanIntensity(beam, 0.7, 0.75), 0.0);
    EXPECT_EQ(peak(beam, 0.8, 5.0).first, 0);
  }
}

TEST(simMsis, WallEchoesAtTheRangesOfTheGeometry) {
  const Scene tank = builtinScene("tank");
  const MsisSimulation run = simulateMsis(tank, turns(1));
  std::size_t walls = 0, found = 0;
  for (const Beam& beam : run.log.beams) {
    const SceneHit wall = horizontalHit(tank, beam.bearing_rad);
    if (std::abs(beam.bearing_rad - 265.0 * kDegree) < 20.0 * kDegree) continue;  // the floater (map 95°) is in front
    ++walls;
    // A strong echo starts within a few centimetres of the wall's range (the leading edge).
    const auto [intensity, range_m] = peak(beam, wall.surface.range_m - 0.03, wall.surface.range_m + 0.1);
    found += intensity >= 100 ? 1 : 0;
    // Nothing as strong between the ring and the wall (the 3° beam meets an oblique wall up to
    // ≈ 0.2 m before its axis does).
    EXPECT_LT(peak(beam, 1.0, wall.surface.range_m - 0.25).first, 90) << "bearing " << beam.bearing_rad / kDegree;
  }
  EXPECT_GT(walls, 170U);  // all but the ±20° behind the floater
  EXPECT_GE(static_cast<double>(found), 0.95 * static_cast<double>(walls));
}

TEST(simMsis, SurfaceRingAtAConstantRangeInEveryDirection) {
  // The surface is 0.47 m above the head: the ±17.5° aperture meets it from 1.56 m on. Without
  // noise, the ring is what returns between the band and the nearest wall (1.8 m).
  const MsisSimulation run = simulateMsis(builtinScene("tank"), noiseless(1));
  std::vector<double> onset_m;
  for (const Beam& beam : run.log.beams) {
    // Ring onset: the first bin from 1 m on with intensity ≥ 10.
    for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
      const double range_m = (static_cast<double>(i) + 0.5) * beam.bin_length_m;
      if (range_m >= 1.0 && beam.intensities[i] >= 10) {
        onset_m.push_back(range_m);
        break;
      }
    }
  }
  ASSERT_EQ(onset_m.size(), run.log.beams.size());
  const auto [lowest, highest] = std::minmax_element(onset_m.begin(), onset_m.end());
  EXPECT_GT(*lowest, 1.2);
  EXPECT_LT(*highest, 1.7);
  EXPECT_LT(*highest - *lowest, 0.05);  // the same range at every bearing
  // Without the surface there is no ring: the first echo is the wall.
  Scene no_surface = builtinScene("tank");
  no_surface.primitives.erase(no_surface.primitives.begin());
  const MsisSimulation dry = simulateMsis(no_surface, noiseless(1));
  for (const Beam& beam : dry.log.beams) EXPECT_LT(peak(beam, 1.0, 1.7).first, 10);
}

TEST(simMsis, MultipathLandsBehindTheWallsStrongestNearCorners) {
  const Scene tank = builtinScene("tank");
  MsisSimulationOptions without = noiseless(1);
  without.echo.multipath = false;
  const MsisSimulation direct = simulateMsis(tank, without);
  const MsisSimulation with = simulateMsis(tank, noiseless(1));
  double corner_excess = 0.0, wall_excess = 0.0;
  int corner_beams = 0, wall_beams = 0;
  for (std::size_t i = 0; i < direct.log.beams.size(); ++i) {
    const Beam& beam = with.log.beams[i];
    const Beam& direct_beam = direct.log.beams[i];
    const double wall_m = horizontalHit(tank, beam.bearing_rad).surface.range_m;
    // In front of the walls a double bounce never arrives (its path is longer than the way to the
    // wall and back), except around the floater (floater–surface–wall paths).
    if (std::abs(beam.bearing_rad - 265.0 * kDegree) > 20.0 * kDegree) {  // away from the floater (map 95°)
      EXPECT_LT(std::abs(meanIntensity(beam, 1.0, wall_m - 0.05) - meanIntensity(direct_beam, 1.0, wall_m - 0.05)), 0.5)
          << "bearing " << beam.bearing_rad / kDegree;
    }
    // What multipath adds just behind the wall.
    const double excess =
        meanIntensity(beam, wall_m + 0.15, wall_m + 0.8) - meanIntensity(direct_beam, wall_m + 0.15, wall_m + 0.8);
    EXPECT_GE(excess, 0.0);
    // Angle to the nearest corner of the tank (x = ±2.1 m, y = −1.8 / 2.6 m) seen from the head.
    double to_corner_rad = std::numbers::pi;
    for (const double x_m : {-2.1, 2.1}) {
      for (const double y_m : {-1.8, 2.6}) {
        to_corner_rad = std::min(
            to_corner_rad, std::abs(std::remainder(beam.bearing_rad - std::atan2(y_m, x_m), 2.0 * std::numbers::pi)));
      }
    }
    if (to_corner_rad < 10.0 * kDegree) {
      corner_excess += excess;
      ++corner_beams;
    } else if (to_corner_rad > 25.0 * kDegree) {
      wall_excess += excess;
      ++wall_beams;
    }
  }
  ASSERT_GT(corner_beams, 0);
  ASSERT_GT(wall_beams, 0);
  EXPECT_GT(corner_excess / corner_beams, 2.0);
  EXPECT_GT(corner_excess / corner_beams, 5.0 * wall_excess / wall_beams);
  // Opposite walls: the echo heard through the back lobe at the tank's width (4.2 m along x).
  const Beam& north = with.log.beams[0];
  EXPECT_GT(peak(north, 4.1, 4.4).first, peak(direct.log.beams[0], 4.1, 4.4).first + 20);
}

TEST(simMsis, MovingVehicleCarriesItsPoseAndTime) {
  // Harbour, heading north at 5 cm/s: the pile straight ahead (2 m north, radius 0.2 m) comes
  // closer by 5 cm/s × 8.6 s between the two turns' first beams.
  MsisSimulationOptions options = turns(2);
  options.trajectory = constantVelocityTrajectory(NavSample{}, Eigen::Vector3d(0.05, 0.0, 0.0));
  const MsisSimulation run = simulateMsis(builtinScene("harbour"), options);
  for (std::size_t i = 1; i < run.log.beams.size(); ++i)
    EXPECT_GT(run.log.beams[i].time_s, run.log.beams[i - 1].time_s);
  for (const std::size_t i : {std::size_t{0}, std::size_t{200}}) {
    const Beam& beam = run.log.beams[i];
    ASSERT_NEAR(std::remainder(beam.bearing_rad, 2.0 * std::numbers::pi), 0.0, 1e-9);  // ahead, a turn apart
    const double expected_m = 1.8 - 0.05 * beam.time_s;
    EXPECT_NEAR(firstAbove(beam, 100, 1.0), expected_m, 0.05) << "at " << beam.time_s << " s";
  }
  // The navigation track: 10 Hz from the first beam to at least the last, on the trajectory.
  ASSERT_FALSE(run.nav.empty());
  EXPECT_DOUBLE_EQ(run.nav.front().time_s, run.log.beams.front().time_s);
  EXPECT_GE(run.nav.back().time_s, run.log.beams.back().time_s);
  EXPECT_LT(run.nav.back().time_s - 0.1, run.log.beams.back().time_s);
  for (std::size_t k = 1; k < run.nav.size(); ++k) {
    EXPECT_NEAR(run.nav[k].time_s - run.nav[k - 1].time_s, 0.1, 1e-9);
    EXPECT_NEAR(run.nav[k].position_ned_m.x(), 0.05 * run.nav[k].time_s, 1e-12);
  }
}

TEST(simMsis, HeadingTurnsTheBeamsInTheMap) {
  // Heading east (yaw 90°): the sonar's +x looks east (map −y, open water) and its port side
  // (bearing 270°, where the counter-clockwise head is 50 beams later) looks north, at the pile
  // 1.8 m away.
  NavSample east;
  east.yaw_rad = 90.0 * kDegree;
  MsisSimulationOptions options = noiseless(1);
  options.trajectory = staticTrajectory(east);
  const MsisSimulation run = simulateMsis(builtinScene("harbour"), options);
  const Beam& ahead = run.log.beams[0];  // bearing 0°
  const Beam& left = run.log.beams[50];  // bearing 270°: port
  ASSERT_NEAR(left.bearing_rad, 270.0 * kDegree, 1e-9);
  EXPECT_LT(peak(ahead, 1.0, 5.0).first, 10);
  EXPECT_NEAR(firstAbove(left, 100, 1.0), 1.8, 0.05);
}

TEST(simMsis, DefaultMountingMapsTheSonarOntoTheVehicle) {
  const Eigen::Isometry3d at_origin = sonarToMap(NavSample{}, defaultSonarToBody());
  EXPECT_TRUE(at_origin.isApprox(staticSonarToMap(), 1e-12));  // a log without navigation
  EXPECT_TRUE((at_origin.linear() * Eigen::Vector3d::UnitY()).isApprox(-Eigen::Vector3d::UnitY(), 1e-12));  // starboard: east
  NavSample moved;
  moved.position_ned_m = Eigen::Vector3d(1.0, 2.0, 3.0);  // north, east, down
  moved.yaw_rad = 90.0 * kDegree;
  const Eigen::Isometry3d pose = sonarToMap(moved, defaultSonarToBody());
  EXPECT_TRUE(pose.translation().isApprox(Eigen::Vector3d(1.0, -2.0, -3.0), 1e-12));  // NWU
  // Heading east: the sonar's +x (forward) is the map's −y (east), its +z (down) the map's −z.
  EXPECT_TRUE((pose.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_TRUE((pose.linear() * Eigen::Vector3d::UnitZ()).isApprox(-Eigen::Vector3d::UnitZ(), 1e-12));
}

TEST(simMsis, InvalidOptionsAndScenesAreRejected) {
  const Scene tank = builtinScene("tank");
  auto rejects = [&](const MsisSimulationOptions& options) { EXPECT_THROW(simulateMsis(tank, options), ValueError); };
  MsisSimulationOptions options = turns(1);
  options.head.bins = 0;
  rejects(options);
  options = turns(1);
  options.head.step_rad = 0.0;
  rejects(options);
  options = turns(1);
  options.echo.vertical.rays = 0;
  rejects(options);
  for (const double width_rad : {0.0, -1.0, 2.0 * std::numbers::pi + 1e-6, 1.0 * kDegree, std::nan("")}) {
    options = turns(1);
    options.head.sector_width_rad = width_rad;  // 1°: less than the 1.8° step
    rejects(options);
  }
  options = turns(1);
  options.head.sector_width_rad = 90.0 * kDegree;
  options.head.sector_center_rad = std::numeric_limits<double>::infinity();
  rejects(options);
  options = turns(1);
  options.echo.ad_span_db = 0.0;
  rejects(options);
  options = turns(1);
  options.echo.self_reflection_taper_m = 0.0;
  rejects(options);
  options = turns(1);
  options.trajectory = nullptr;
  rejects(options);
  options = turns(1);
  options.sonar_to_body.linear() *= 2.0;
  rejects(options);
  options = turns(1);
  options.nav_rate_hz = -1.0;
  rejects(options);
  Scene broken = tank;
  broken.primitives.push_back(Cylinder{0.0, 0.0, -1.0, 0.0, 1.0, 0.5});
  EXPECT_THROW(simulateMsis(broken, turns(1)), ValueError);
  broken = tank;
  broken.reverberation_db = std::numeric_limits<double>::infinity();
  EXPECT_THROW(simulateMsis(broken, turns(1)), ValueError);
}

TEST(simMsis, ReverberationFillsOnlyWhatLiesBehindTheFirstSurfaceOnTheAxis) {
  // One wall 2 m ahead (x = 2), nothing behind the head: a basin's reverberation rises behind the
  // wall in the beams that meet it, changes nothing before it, and nothing in the beams that miss.
  Scene open;
  open.primitives.push_back(Box{{3.0, 0.0, 0.0}, {2.0, 3.0, 4.0}, 0.0, 0.9});
  Scene basin = open;
  basin.reverberation_db = -20.0;  // 13 dB over the A/D floor
  const MsisSimulation quiet = simulateMsis(open, turns(1));
  const MsisSimulation loud = simulateMsis(basin, turns(1));
  ASSERT_EQ(quiet.log.beams.size(), loud.log.beams.size());
  int facing = 0, away = 0;
  for (std::size_t i = 0; i < quiet.log.beams.size(); ++i) {
    const Beam& a = quiet.log.beams[i];
    const Beam& b = loud.log.beams[i];
    const double bearing_rad = std::remainder(a.bearing_rad, 2.0 * std::numbers::pi);
    const int wall_bin = static_cast<int>(1.95 / a.bin_length_m);
    if (std::abs(bearing_rad) < 20.0 * kDegree) {  // the axis meets the wall at 2 m / cos β < 2.13 m
      ++facing;
      EXPECT_TRUE(std::equal(a.intensities.begin(), a.intensities.begin() + wall_bin, b.intensities.begin())) << i;
      EXPECT_GT(meanIntensity(b, 3.5, 5.0), meanIntensity(a, 3.5, 5.0) + 30.0) << i;
    } else if (std::abs(bearing_rad) > 120.0 * kDegree) {
      ++away;
      EXPECT_EQ(a.intensities, b.intensities) << i;
    }
  }
  EXPECT_GT(facing, 10);
  EXPECT_GT(away, 50);
}

TEST(simMsis, NoNavigationTrackWhenTheRateIsZero) {
  MsisSimulationOptions options = turns(1);
  options.nav_rate_hz = 0.0;
  EXPECT_TRUE(simulateMsis(builtinScene("tank"), options).nav.empty());
}

}  // namespace
}  // namespace sonarmap
