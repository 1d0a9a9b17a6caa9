// Loud level returns: an obstacle whose loud echo lasts longer than any vertical face in
// its cone could echo, or that starts where the known water surface enters a cone pointing up, is
// a level surface met at the cone's edge and traced as one (isLevelReturn, sweep_fan.hpp), unless
// the seabed the sweep's weak returns measure lies well below it (SonarMapper::checkLoudTraces).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "polar_fixtures.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "sonarmap/sonar/polar.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
const BeamShape kMicron{3.0 * kDegree, 35.0 * kDegree};

using testing::makeFullTurnSweep;
using testing::tiltedPose;

/// The beam-volume model at 5 cm.
MapperOptions volume() {
  MapperOptions options;
  options.beam_model = BeamModel::kVolume;
  options.resolution_m = 0.05;
  return options;
}

// An obstacle whose echo goes on past the farthest range a vertical face in the cone could echo
// from is a level surface entering the cone: a head tilted 25° with the Micron's 35° aperture (its
// steepest ray 42.5° down) calls a return from 3 m to 3 / cos 42.5° ≈ 4.07 m or less a face.
TEST(mappingLoudReturns, ALongReturnOfADownwardConeIsLevelAndAShortOneAFace) {
  const Eigen::Isometry3d down = tiltedPose(Eigen::Vector3d::Zero(), 0.0, 25.0 * kDegree, 0.0);
  const PlannedBeam ahead{down, 0.0, 2.9, 3.0, true};
  const double face_end_m = 3.0 / std::cos(42.5 * kDegree);
  EXPECT_FALSE(isLevelReturn(ahead, kMicron, 3.0, 3.1, 0.02));
  EXPECT_FALSE(isLevelReturn(ahead, kMicron, 3.0, face_end_m, 0.02));
  EXPECT_TRUE(isLevelReturn(ahead, kMicron, 3.0, face_end_m + 0.03, 0.02));
  // Sideways the tilted cone points both up and down, as a level head's: never level.
  const PlannedBeam sideways{down, 0.5 * std::numbers::pi, 2.9, 3.0, true};
  EXPECT_FALSE(isLevelReturn(sideways, kMicron, 3.0, 10.0, 0.02));
  const PlannedBeam level{Eigen::Isometry3d::Identity(), 0.0, 2.9, 3.0, true};
  EXPECT_FALSE(isLevelReturn(level, kMicron, 3.0, 10.0, 0.02));
}

// A face's loud echo can go on into a weak seabed at its foot, a lit run longer than any face's.
// Whether the obstacle is a level surface is decided on its loud echo alone, up to where it falls
// back (BeamDetection::echo_end_m): a head tilted 25° (steepest ray 42.5° down) with an echo from
// 2.2 m that falls back at 2.8 m (a face reaches 2.2 / cos 42.5° ≈ 2.98 m) keeps its obstacle,
// whatever the lit run behind it; one whose loud echo lasts to 3.6 m is traced as level. Without a
// lit run (a seabed loud over most of the sweep lifts the background the run detector compares
// with) the loud echo alone decides, when the whole echo was searched.
TEST(mappingLoudReturns, AFacesLoudEchoIntoTheSeabedAtItsFootStaysAFace) {
  PolarImage polar = makeFullTurnSweep(1, 200, 0.025);
  const Eigen::Isometry3d down = tiltedPose(Eigen::Vector3d::Zero(), 0.0, 25.0 * kDegree, 0.0);
  BeamDetection echo{88, 200, 2.2};
  echo.water_range_m = 2.2;
  echo.echo_onset_m = 2.2;
  echo.extended_onset_m = 2.2;
  echo.extended_end_m = 3.6;  // the lit run: the face, then the seabed at its foot
  auto mapped = [&](double loud_end_m) {
    echo.echo_end_m = loud_end_m;
    SonarMapper mapper(volume());
    mapper.integrateSweep(polar, {echo}, down);
    return mapper.stats();
  };
  const MappingStats face = mapped(2.8);
  EXPECT_EQ(face.obstacles, 1U);
  EXPECT_EQ(face.extended_returns, 0U);
  const MappingStats level = mapped(3.6);
  EXPECT_EQ(level.obstacles, 0U);
  EXPECT_EQ(level.extended_returns, 1U);
  // Without a measured fall (a detection made by hand) the lit run decides, as before.
  EXPECT_EQ(mapped(std::numeric_limits<double>::quiet_NaN()).extended_returns, 1U);
  echo.extended_onset_m = echo.extended_end_m = std::numeric_limits<double>::quiet_NaN();  // no lit run
  EXPECT_EQ(mapped(2.8).obstacles, 1U);
  const MappingStats loud_only = mapped(3.6);
  EXPECT_EQ(loud_only.obstacles, 0U);
  EXPECT_EQ(loud_only.extended_returns, 1U);
}

// A loud face can outlast the nominal cone's face bound too (it is heard beyond the −3 dB edge),
// and is then called level. The seabed that the sweep's weak returns measure tells it apart: a
// head tilted 25°, 2.4 m over a flat seabed; 39 beams within ±20° of its tilt hear the seabed
// weakly from where it enters the lower edge; one hears it loud from there (traced: its onset lies
// on the seabed) and one hears a face from 2.2 m whose loud echo lasts to 3.6 m, longer than the
// face bound 2.2 / cos 42.5° ≈ 2.98 m, but whose onset on the edge lies 0.9 m over the seabed:
// it stays an obstacle. Without the weak seabed returns (no onsets to fit) both loud beams are traced.
TEST(mappingLoudReturns, ALoudTraceAboveTheMeasuredSeabedStaysAnObstacle) {
  const Eigen::Isometry3d down = tiltedPose(Eigen::Vector3d::Zero(), 0.0, 25.0 * kDegree, 0.0);
  PolarImage polar = makeFullTurnSweep(41, 200, 0.025);
  std::vector<BeamDetection> detections(41);
  for (int i = 0; i < 41; ++i) {
    polar.bearing_rad[i] = std::remainder((i - 20) * kDegree, 2.0 * std::numbers::pi);
    if (polar.bearing_rad[i] < 0.0) polar.bearing_rad[i] += 2.0 * std::numbers::pi;
    const Eigen::Vector3d edge = down.linear() * Eigen::Vector3d(std::cos(17.5 * kDegree) * std::cos(polar.bearing_rad[i]),
                                                                  std::cos(17.5 * kDegree) * std::sin(polar.bearing_rad[i]),
                                                                  -std::sin(17.5 * kDegree));
    const double onset_m = 2.4 / -edge.z();  // where the seabed enters the lower edge
    BeamDetection& beam = detections[static_cast<std::size_t>(i)];
    beam.water_range_m = 5.0;
    beam.echo_onset_m = beam.extended_onset_m = onset_m;
    beam.extended_end_m = 4.9;
    if (i == 10) {  // the seabed heard loud
      beam = BeamDetection{static_cast<int>(onset_m / 0.025), 200, onset_m};
      beam.water_range_m = beam.echo_onset_m = beam.extended_onset_m = onset_m;
      beam.echo_end_m = beam.extended_end_m = 4.9;
    }
    if (i == 20) {  // the face
      beam = BeamDetection{88, 200, 2.2};
      beam.water_range_m = beam.echo_onset_m = beam.extended_onset_m = 2.2;
      beam.echo_end_m = beam.extended_end_m = 3.6;
    }
  }
  SonarMapper measured(volume());
  measured.integrateSweep(polar, detections, down);
  EXPECT_EQ(measured.stats().obstacles, 1U);
  EXPECT_EQ(measured.stats().extended_returns, 40U);
  for (int i = 0; i < 41; ++i) {
    if (i == 10 || i == 20) continue;
    BeamDetection& beam = detections[static_cast<std::size_t>(i)];
    beam.echo_onset_m = beam.extended_onset_m = beam.extended_end_m = std::numeric_limits<double>::quiet_NaN();
  }
  SonarMapper unmeasured(volume());
  unmeasured.integrateSweep(polar, detections, down);
  EXPECT_EQ(unmeasured.stats().obstacles, 0U);
  EXPECT_EQ(unmeasured.stats().extended_returns, 2U);
}

// A cone that points up under a known water surface meets it first on its top ray: a head tilted
// 25° looking back, 3 m under the surface, at 3 / sin 42.5° ≈ 4.44 m. A return that starts there
// is the surface even where the beam's 5 m range ends it before a face's bound (4.44 / cos 42.5°
// ≈ 6.0 m); one that starts 0.3 m nearer or farther is a face; an unknown surface decides nothing,
// and a cone that points down never meets the surface first.
TEST(mappingLoudReturns, AnUpwardConesReturnWhereTheKnownSurfaceEntersIsLevel) {
  const Eigen::Isometry3d down = tiltedPose(Eigen::Vector3d::Zero(), 0.0, 25.0 * kDegree, 0.0);
  const double surface_m = 3.0 / std::sin(42.5 * kDegree);
  PlannedBeam back{down, std::numbers::pi, 4.3, surface_m, true};
  back.surface_z_m = 3.0;
  EXPECT_TRUE(isLevelReturn(back, kMicron, surface_m, 5.0, 0.02));
  EXPECT_TRUE(isLevelReturn(back, kMicron, surface_m - 0.015, surface_m + 0.1, 0.02));
  EXPECT_FALSE(isLevelReturn(back, kMicron, surface_m - 0.3, 5.0, 0.02));
  EXPECT_FALSE(isLevelReturn(back, kMicron, surface_m + 0.3, 5.0, 0.02));
  back.surface_z_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(isLevelReturn(back, kMicron, surface_m, 5.0, 0.02));
  PlannedBeam ahead{down, 0.0, 2.9, 3.0, true};
  ahead.surface_z_m = 3.0;
  EXPECT_FALSE(isLevelReturn(ahead, kMicron, 3.0, 3.1, 0.02));
}

}  // namespace
}  // namespace sonarmap
