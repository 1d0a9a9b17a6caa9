// libFuzzer harness: beam CSV bytes → readBeamCsv → the whole mapping pipeline (sweeps, polar
// images, self-reflection removal, smoothing, detection, ray casting, octree) with the CLI's
// defaults, and again with the evidence detector. A log that reads must map without crashing or
// hanging, whatever its values.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "fuzz_input.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/formats/beam_csv.hpp"
#include "sonarmap/sonar/log_survey.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sonarmap::fuzz::InputFile file(".csv");
  const std::string& path = file.write(data, size);
  return sonarmap::fuzz::expectReadOrError([&] {
    sonarmap::MapperOptions options;
    options.pipeline_detection = false;  // one thread: libFuzzer's timeout and leak checks see everything
    options.max_range_m = 30.0;  // explore inputs, not ever longer beams (a 300 m beam is legitimate work)
    const sonarmap::SonarLog log = sonarmap::readBeamCsv(path);
    (void)sonarmap::mapSonarLog(log, options);
    sonarmap::selectDetector(options.detector, "evidence");
    (void)sonarmap::mapSonarLog(log, options);
    // beam by beam from the file, as `map` reads it
    const std::unique_ptr<sonarmap::BeamSource> source = sonarmap::openBeamCsv(path);
    const sonarmap::LogSurvey survey = sonarmap::surveyLog(sonarmap::passOver(*source), sonarmap::surveyMinBeams(options));
    (void)sonarmap::mapSonarLog(*source, survey, options);
  });
}
