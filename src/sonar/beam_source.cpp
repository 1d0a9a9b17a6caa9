/// @file beam_source.cpp
/// LogBeamSource (see beam_source.hpp).

#include "sonarmap/sonar/beam_source.hpp"

namespace sonarmap {

LogBeamSource::LogBeamSource(const SonarLog& log) : log_(log) {
  header_.skipped_beams = log.skipped_beams;
  header_.skip_reasons = log.skip_reasons;
  header_.sonar = log.sonar;
  header_.notes = log.notes;
  header_.clock_utc_s = log.clock_utc_s;
  header_.frame_id = log.frame_id;
  header_.nominal_beam = log.nominal_beam;
}

std::optional<Beam> LogBeamSource::next() {
  if (next_ >= log_.beams.size()) return std::nullopt;
  return log_.beams[next_++];
}

BeamPass passOver(const SonarLog& log) {
  return [&log](const std::function<void(const Beam&)>& visit) {
    for (const Beam& beam : log.beams) visit(beam);
  };
}

BeamPass passOver(BeamSource& source) {
  return [&source](const std::function<void(const Beam&)>& visit) {
    source.rewind();
    while (const std::optional<Beam> beam = source.next()) visit(*beam);
  };
}

}  // namespace sonarmap
