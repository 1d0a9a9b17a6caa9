/// Tests of mapping a log read beam by beam (mapSonarLog over a BeamSource, sonar_mapper.hpp) and
/// of the survey it is planned with (log_survey.hpp, mapper_options.hpp): the same map as the log
/// held whole, byte for byte, and the same automatic resolution whatever the budget.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"
#include "sonarmap/sonar/log_survey.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {
namespace {

MsisSimulationOptions movingOptions(const std::string& sonar) {
  SimulationArguments args;
  args.sonar = sonar;
  args.turns = 4;
  args.speed_mps = 0.05;
  return toSimulationOptions(args, "harbour");
}

MsisSimulation movingRun(const std::string& sonar) {
  const MsisSimulationOptions options = movingOptions(sonar);
  return simulateMsis(sceneOf("harbour", options.head), options);
}

std::string bytesOf(const OcTree16& map) {
  std::ostringstream out;
  writeBinary(map, out);
  return out.str();
}

TEST(mappingBeamSource, AMovingLogMapsFromASourceAsWhole) {
  const MsisSimulation run = movingRun("micron");
  const Eigen::Isometry3d sonar_to_body = movingOptions("micron").sonar_to_body;
  const MapperOptions options;
  const SonarMapper whole = mapSonarLog(run.log, run.nav, sonar_to_body, options);
  LogBeamSource source(run.log);
  const LogSurvey survey = surveyLog(passOver(source), surveyMinBeams(options));
  std::vector<std::size_t> progress;
  const SonarMapper streamed = mapSonarLog(source, survey, run.nav, sonar_to_body, options,
                                           [&](std::size_t, std::size_t total) { progress.push_back(total); });
  EXPECT_EQ(bytesOf(streamed.map()), bytesOf(whole.map()));
  EXPECT_EQ(streamed.stats().beams_used, whole.stats().beams_used);
  ASSERT_FALSE(progress.empty());
  EXPECT_EQ(progress.back(), groupSweeps(run.log.beams, surveyMinBeams(options)).size());
  const SonarMapper static_whole = mapSonarLog(run.log, options);
  const SonarMapper static_streamed = mapSonarLog(source, survey, options);
  EXPECT_EQ(bytesOf(static_streamed.map()), bytesOf(static_whole.map()));
}

TEST(mappingBeamSource, ALogHeldWholeKeepsEveryHeaderFieldButItsBeams) {
  // `map --slam` holds the log whole and reads its header from a LogBeamSource: the sonar's beam a
  // recording states (SonarLog::nominal_beam) must reach the mapping options as the streamed
  // source's header gives it.
  SonarLog log;
  log.beams.resize(3);
  log.skipped_beams = 2;
  log.skip_reasons = {"a", "b"};
  log.sonar = "Ping360";
  log.notes = {"note"};
  log.clock_utc_s = 1.5e9;
  log.frame_id = "sonar";
  log.nominal_beam = NominalBeam{0.0349, 0.4363};
  const LogBeamSource source(log);
  const SonarLog& header = source.header();
  EXPECT_TRUE(header.beams.empty());
  EXPECT_EQ(header.skipped_beams, 2U);
  EXPECT_EQ(header.skip_reasons, log.skip_reasons);
  EXPECT_EQ(header.sonar, "Ping360");
  EXPECT_EQ(header.notes, log.notes);
  EXPECT_EQ(header.clock_utc_s, log.clock_utc_s);
  EXPECT_EQ(header.frame_id, "sonar");
  ASSERT_TRUE(header.nominal_beam.has_value());
  EXPECT_EQ(header.nominal_beam->width_rad, 0.0349);
  EXPECT_EQ(header.nominal_beam->vertical_aperture_rad, 0.4363);
}

TEST(mappingBeamSource, TheSurveySumsTheLogUp) {
  SonarLog log = movingRun("micron").log;
  log.beams[10].intensities.resize(500);  // a longer beam
  log.beams[20].bin_length_m *= 2.0;      // another range scale
  const LogSurvey survey = surveyLog(passOver(log), 3, std::pair(log.beams[5].time_s, log.beams[9].time_s));
  EXPECT_EQ(survey.beams, log.beams.size());
  const std::vector<RangeScale> scales = rangeScales(log);
  ASSERT_EQ(survey.scales.size(), scales.size());
  for (std::size_t i = 0; i < scales.size(); ++i) {
    EXPECT_EQ(survey.scales[i].bin_length_m, scales[i].bin_length_m);
    EXPECT_EQ(survey.scales[i].reach_m, scales[i].reach_m);
    EXPECT_EQ(survey.scales[i].beams, scales[i].beams);
    EXPECT_EQ(survey.scales[i].first_beam, scales[i].first_beam);
  }
  EXPECT_EQ(survey.reach_m, logReach_m(log, 1e9));
  EXPECT_EQ(survey.sweeps, groupSweeps(log.beams, 3).size());
  EXPECT_EQ(survey.beams_in_span, 5u);
  EXPECT_EQ(survey.earliest_s, log.beams.front().time_s);
  EXPECT_EQ(survey.latest_s, log.beams.back().time_s);
}

}  // namespace
}  // namespace sonarmap
