/// @file ros_bag_reader.cpp
/// A ROS 1 bag's sonar topic as a sonar log (see ros_bag_reader.hpp).

#include "sonarmap/formats/ros_bag_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <string_view>
#include <vector>

#include "ros_bag_file.hpp"
#include "ros_frames.hpp"
#include "ros_sonar_fields.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/beam_source.hpp"

namespace sonarmap {
namespace {

using detail::BearingRule;
using detail::RawBeam;
using detail::RosSchema;
using detail::RosValue;
using detail::SonarFields;

}  // namespace

BearingUnit parseBearingUnit(std::string_view name) {
  if (name == "auto") return BearingUnit::kAuto;
  if (name == "deg") return BearingUnit::kDegrees;
  if (name == "rad") return BearingUnit::kRadians;
  if (name == "grad") return BearingUnit::kGradians;
  throw ValueError("unknown bearing unit '" + std::string(name) + "' (auto, deg, rad, grad)");
}

BearingDirection parseBearingDirection(std::string_view name) {
  if (name == "cw") return BearingDirection::kClockwise;
  if (name == "ccw") return BearingDirection::kCounterClockwise;
  throw ValueError("unknown bearing direction '" + std::string(name) + "' (cw, ccw)");
}

namespace {

/// A bag's sonar topic read beam by beam (see ros_bag_reader.hpp): the topic found on opening and,
/// for an automatic bearing unit the field's name does not say, the unit decided on a first pass
/// over its messages (up to the first bearing beyond 2π, or through).
class RosBagBeamSource final : public BeamSource {
 public:
  /// Opens the bag and finds its sonar topic and its first beam; with `decide_unit`, also the
  /// bearings' unit (see the class's comment), else the caller's decideUnit() does.
  RosBagBeamSource(const std::string& path, const RosBagOptions& options, bool decide_unit) : path_(path), options_(options) {
    detail::withBagErrors(path_, [&] {
      open();
      // A first pass up to the first beam that decodes (the log's frame), or, to decide the unit,
      // up to the first bearing beyond a turn of radians (degrees, then, whatever follows) or to
      // the end (radians).
      const bool first_beam_enough = !decide_unit || bearing_->unitKnown();
      double largest = 0.0;
      bool whole_pass = true;
      rewind();
      while (std::optional<RawBeam> raw = nextRaw()) {
        largest = std::max(largest, std::abs(raw->bearing));
        if (first_beam_enough || beyondRadians(largest)) {
          whole_pass = false;
          break;
        }
      }
      if (whole_pass) endPass();  // throws when no message gave a beam
      if (decide_unit) decideUnit(largest);
      rewind();
    });
  }

  std::optional<Beam> next() override {
    return detail::withBagErrors(path_, [&]() -> std::optional<Beam> {
      if (!cursor_) return std::nullopt;
      if (std::optional<RawBeam> raw = nextRaw()) {
        Beam beam = std::move(raw->beam);
        beam.bearing_rad = bearingOf(raw->bearing);
        beam.time_s = raw->time_s;
        return beam;
      }
      endPass();
      return std::nullopt;
    });
  }

  void rewind() override {
    detail::withBagErrors(path_, [&] {
      cursor_.reset();
      cursor_.emplace(bag_->messages(topic_, *schema_));
      pass_beams_ = 0;
    });
  }

  const SonarLog& header() const override { return header_; }

  /// The next message of the topic that gives a beam, its bearing as the message gives it; nullopt
  /// at the end of the pass (then endPass()).
  std::optional<RawBeam> nextRawBeam() {
    return detail::withBagErrors(path_, [&]() -> std::optional<RawBeam> {
      if (!cursor_) return std::nullopt;
      std::optional<RawBeam> raw = nextRaw();
      if (!raw) endPass();
      return raw;
    });
  }

  /// Decides the bearings' unit from the largest bearing (BearingRule::decide), said in the log's notes.
  void decideUnit(double largest) { header_.notes.push_back(bearing_->decide(largest, topic_)); }

  /// Whether a bearing of magnitude `largest` cannot be radians (beyond a turn of them).
  static bool beyondRadians(double largest) { return BearingRule::beyondRadians(largest); }

  /// `bearing` in the topic's unit and direction as beam.hpp's clockwise radians in [0, 2π).
  double bearingOf(double bearing) const { return bearing_->bearingRad(bearing); }

 private:
  void open() {
    const RosBagOptions& options = options_;
    bag_ = std::make_unique<detail::RosBagFile>(path_, options.msg_path);
    detail::RosBagFile& bag = *bag_;
    header_.notes = bag.notes();
    for (const RosBagTopic& candidate : bag.topics()) {
      if (!options.sonar_topic.empty() && candidate.topic != options.sonar_topic) continue;
      const std::string& definition = bag.definition(candidate);
      if (definition.empty()) {
        if (candidate.topic == options.sonar_topic) bag.fail("the connection of " + candidate.topic + " has no message definition");
        continue;
      }
      RosSchema parsed = bag.schema(candidate);
      fields_ = detail::sonarFields(parsed);
      if (fields_) {
        bearing_.emplace(*fields_, options_);
        schema_ = std::make_unique<RosSchema>(std::move(parsed));
        topic_ = candidate.topic;
        header_.sonar = "ROS topic " + topic_ + " (" + candidate.type + ")";
        break;
      }
      if (candidate.topic == options.sonar_topic) {
        bag.fail("the topic " + candidate.topic + " (" + candidate.type + ") has no sonar beam's fields "
                 "(a bearing, a bin length or range, and intensities: docs/formats.md)");
      }
    }
    if (!fields_) {
      if (!options.sonar_topic.empty()) bag.fail("no topic " + options.sonar_topic + " (topics: " + bag.listing() + ")");
      bag.fail("no topic holds sonar beams (a bearing, a bin length or range, and intensities); topics: " + bag.listing());
    }
  }

  /// The next message of the topic that gives a beam (bearing as the message gives it); nullopt at
  /// the end of the pass. Sets the log's frame at the first beam of a pass.
  std::optional<RawBeam> nextRaw() {
    RosValue message;
    double time_s = 0.0;
    while (cursor_->next(message, time_s)) {
      try {
        RawBeam raw = detail::beamOf(message, *fields_, time_s);
        if (++pass_beams_ == 1) {
          if (fields_->header) header_.frame_id = detail::headerFrame(message);
          header_.nominal_beam = raw.nominal_beam;
        }
        return raw;
      } catch (const Error& error) {
        cursor_->reject(error.what());
      }
    }
    return std::nullopt;
  }

  /// The end of a pass: its skips are the log's; without a beam, the bag is refused.
  void endPass() {
    if (!cursor_) return;
    header_.skipped_beams = cursor_->skipped().count;
    header_.skip_reasons = cursor_->skipped().reasons;
    const std::size_t beams = pass_beams_;
    pass_beams_ = 0;
    cursor_.reset();
    if (beams == 0) {
      bag_->fail("no message of " + topic_ + " decodes" + (header_.skip_reasons.empty() ? "" : ": " + header_.skip_reasons.front()));
    }
  }

  std::string path_;
  RosBagOptions options_;
  std::unique_ptr<detail::RosBagFile> bag_;
  std::string topic_;
  std::unique_ptr<RosSchema> schema_;  ///< the decoded messages point into it: kept in place
  std::optional<SonarFields> fields_;
  std::optional<detail::RosBagFile::MessageCursor> cursor_;  ///< unset between passes
  std::optional<BearingRule> bearing_;  ///< set with fields_
  std::size_t pass_beams_ = 0;  ///< beams given in this pass
  SonarLog header_;
};

}  // namespace

std::unique_ptr<BeamSource> openRosBag(const std::string& path, const RosBagOptions& options) {
  return std::make_unique<RosBagBeamSource>(path, options, true);
}

SonarLog readRosBag(const std::string& path, const RosBagOptions& options) {
  // One pass: the beams are held anyway, so the unit is decided on them afterwards.
  RosBagBeamSource source(path, options, false);
  std::vector<RawBeam> raw;
  while (std::optional<RawBeam> beam = source.nextRawBeam()) raw.push_back(std::move(*beam));
  double largest = 0.0;
  for (const RawBeam& beam : raw) largest = std::max(largest, std::abs(beam.bearing));
  source.decideUnit(largest);
  SonarLog log = source.header();
  log.beams.reserve(raw.size());
  for (RawBeam& beam : raw) {
    beam.beam.bearing_rad = source.bearingOf(beam.bearing);
    beam.beam.time_s = beam.time_s;
    log.beams.push_back(std::move(beam.beam));
  }
  return log;
}

}  // namespace sonarmap
