#pragma once
/// @file beam_source.hpp
/// A sonar log read beam by beam (pull-based), so that mapping a log holds one beam at a time
/// instead of the whole log: what the mapper needs of a log of hours (tens of GB of ROS bag) on a
/// vehicle computer of 1–4 GB. The formats' streaming readers implement it (log_reader.hpp's
/// openBeamSource); LogBeamSource serves a log already in memory.

#include <cstddef>
#include <functional>
#include <optional>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// The beams of one log in recording order, one at a time, as often as asked (rewind()).
class BeamSource {
 public:
  virtual ~BeamSource() = default;
  /// The next beam in recording order; nullopt at the end of the log (and again after it until
  /// rewind()).
  /// @throws FileError for what the format's whole-log reader rejects (a malformed row, a broken
  ///         container), when reading reaches it; after that, read again only after rewind().
  virtual std::optional<Beam> next() = 0;
  /// Starts again at the first beam. @throws FileError when the file can no longer be read.
  virtual void rewind() = 0;
  /// What the log says besides its beams (SonarLog with `beams` empty): sonar, notes, clock_utc_s,
  /// frame_id from the opening; skipped_beams and skip_reasons complete once a pass has reached the
  /// end (the same on every pass).
  virtual const SonarLog& header() const = 0;
};

/// A log held in memory as a BeamSource (formats read whole, simulated logs, tests): next() gives a
/// copy of each beam. The log must outlive the source.
class LogBeamSource final : public BeamSource {
 public:
  explicit LogBeamSource(const SonarLog& log);
  std::optional<Beam> next() override;
  void rewind() override { next_ = 0; }
  const SonarLog& header() const override { return header_; }

 private:
  const SonarLog& log_;
  SonarLog header_;  ///< log_ without its beams
  std::size_t next_ = 0;
};

/// One pass over a log's beams: calls its argument with each beam in recording order. What the
/// estimates over a whole log (mapper_options.hpp) take, so that one code serves a log in memory
/// and a source read from its file.
using BeamPass = std::function<void(const std::function<void(const Beam&)>&)>;

/// A pass over `log`'s beams (no copies). The log must outlive it.
BeamPass passOver(const SonarLog& log);
/// A pass over `source`'s beams from its first (rewind()). The source must outlive it.
/// @throws what the source throws.
BeamPass passOver(BeamSource& source);

}  // namespace sonarmap
