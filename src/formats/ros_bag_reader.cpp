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
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/beam_source.hpp"

namespace sonarmap {
namespace {

using detail::RosField;
using detail::RosSchema;
using detail::RosStruct;
using detail::RosValue;

constexpr std::array<std::string_view, 7> kBearingNames{"angle", "bearing", "angle_deg", "bearing_deg",
                                                         "angle_rad", "bearing_rad", "head_angle"};
constexpr std::array<std::string_view, 6> kBinLengthNames{"bin_distance_step", "bin_length", "bin_length_m",
                                                          "bin_size", "range_resolution", "step_dist"};
constexpr std::array<std::string_view, 4> kRangeNames{"range", "range_m", "max_range", "range_max"};
constexpr std::array<std::string_view, 6> kIntensityArrayNames{"intensities", "intensity", "data",
                                                               "bins", "samples", "echo"};
constexpr std::array<std::string_view, 2> kIntensityNames{"intensity", "value"};
// What a head reports with each beam, when the message carries it (dive_recorder.hpp's SonarBeam,
// ping360_sonar's SonarEcho `gain`).
constexpr std::array<std::string_view, 2> kGainNames{"gain_setting", "gain"};
constexpr std::array<std::string_view, 1> kPulseLengthNames{"pulse_length_m"};
constexpr std::array<std::string_view, 1> kIntensitySpanNames{"intensity_span_db"};
constexpr std::array<std::string_view, 1> kBeamWidthNames{"beam_width_rad"};
constexpr std::array<std::string_view, 1> kVerticalApertureNames{"vertical_aperture_rad"};

bool isNumber(const std::string& type) {
  return RosSchema::isBuiltin(type) && type != "string" && type != "time" && type != "duration";
}
bool isByte(const std::string& type) { return type == "uint8" || type == "int8" || type == "byte" || type == "char"; }

template <std::size_t N>
const RosField* fieldNamed(const std::vector<RosField>& fields, const std::array<std::string_view, N>& names,
                           bool (*accepts)(const RosField&)) {
  for (const std::string_view name : names) {
    for (const RosField& field : fields) {
      if (field.name == name && accepts(field)) return &field;
    }
  }
  return nullptr;
}

/// Where a topic's message keeps a beam's parts (see ros_bag_reader.hpp).
struct SonarFields {
  std::string bearing, bin_length, range, intensities, element_intensity;  // field names; empty: absent
  std::string gain, pulse_length, intensity_span;                          // optional; empty: absent
  std::string beam_width, vertical_aperture;                               // the log's beam; optional
  bool bearing_in_degrees = false, bearing_in_radians = false;             // said by the name
  bool header = false;
};

/// The sonar fields of `schema`'s top message, or nothing when it lacks one of them.
std::optional<SonarFields> sonarFields(const RosSchema& schema) {
  const std::vector<RosField>& fields = schema.fields(schema.root());
  auto scalarNumber = [](const RosField& f) { return f.array < 0 && isNumber(f.type); };
  SonarFields found;
  const RosField* bearing = fieldNamed(fields, kBearingNames, scalarNumber);
  const RosField* bin_length = fieldNamed(fields, kBinLengthNames, scalarNumber);
  const RosField* range = fieldNamed(fields, kRangeNames, scalarNumber);
  const RosField* bytes = fieldNamed(fields, kIntensityArrayNames, [](const RosField& f) { return f.array >= 0 && isByte(f.type); });
  const RosField* elements = fieldNamed(fields, kIntensityArrayNames, [](const RosField& f) {
    return f.array >= 0 && !RosSchema::isBuiltin(f.type);
  });
  if (bearing == nullptr || (bin_length == nullptr && range == nullptr)) return std::nullopt;
  if (bytes != nullptr) {
    found.intensities = bytes->name;
  } else if (elements != nullptr) {
    const RosField* intensity = fieldNamed(schema.fields(elements->type), kIntensityNames, scalarNumber);
    if (intensity == nullptr) return std::nullopt;
    found.intensities = elements->name;
    found.element_intensity = intensity->name;
  } else {
    return std::nullopt;
  }
  found.bearing = bearing->name;
  found.bearing_in_degrees = bearing->name.ends_with("_deg");
  found.bearing_in_radians = bearing->name.ends_with("_rad");
  if (bin_length != nullptr) found.bin_length = bin_length->name;
  if (range != nullptr) found.range = range->name;
  auto integer = [](const RosField& f) { return f.array < 0 && isNumber(f.type) && !f.type.starts_with("float"); };
  if (const RosField* gain = fieldNamed(fields, kGainNames, integer)) found.gain = gain->name;
  if (const RosField* pulse = fieldNamed(fields, kPulseLengthNames, scalarNumber)) found.pulse_length = pulse->name;
  if (const RosField* span = fieldNamed(fields, kIntensitySpanNames, scalarNumber)) found.intensity_span = span->name;
  const RosField* width = fieldNamed(fields, kBeamWidthNames, scalarNumber);
  const RosField* aperture = fieldNamed(fields, kVerticalApertureNames, scalarNumber);
  if (width != nullptr && aperture != nullptr) {
    found.beam_width = width->name;
    found.vertical_aperture = aperture->name;
  }
  for (const RosField& field : fields) {
    if (field.name == "header" && field.type == "std_msgs/Header" && field.array < 0) found.header = true;
  }
  return found;
}

/// One beam of a decoded message (bearing as the message gives it; converted afterwards).
struct RawBeam {
  double time_s = 0.0, bearing = 0.0;
  Beam beam;
  std::optional<NominalBeam> nominal_beam;  ///< when the message records its sonar's beam
};

RawBeam beamOf(const RosValue& message, const SonarFields& fields, double record_time_s) {
  RawBeam raw;
  raw.bearing = detail::finiteNumber(message.field(fields.bearing), "bearing");
  const RosValue* intensities = message.field(fields.intensities);
  std::vector<std::uint8_t>& out = raw.beam.intensities;
  const auto byteOf = [](double value) {
    if (!std::isfinite(value)) throw Error("its intensity is not a finite number");
    return static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L));
  };
  if (const auto* bytes = std::get_if<std::vector<std::uint8_t>>(&intensities->value)) {
    out = *bytes;
  } else if (const auto* table = std::get_if<detail::RosTable>(&intensities->value)) {
    const std::size_t column = table->column(fields.element_intensity);
    if (column == table->columns()) throw Error("its intensity is not a finite number");
    out.reserve(table->rows());
    for (std::size_t row = 0; row < table->rows(); ++row) out.push_back(byteOf(table->values[row * table->columns() + column]));
  } else if (const auto* elements = std::get_if<std::vector<RosValue>>(&intensities->value)) {
    for (const RosValue& element : *elements) {
      out.push_back(byteOf(detail::finiteNumber(element.field(fields.element_intensity), "intensity")));
    }
  } else {
    throw Error("its intensities are not an array");
  }
  if (!fields.bin_length.empty()) {
    raw.beam.bin_length_m = detail::finiteNumber(message.field(fields.bin_length), "bin length");
  } else if (!out.empty()) {
    raw.beam.bin_length_m = detail::finiteNumber(message.field(fields.range), "range") / static_cast<double>(out.size());
  }
  if (!(raw.beam.bin_length_m > 0.0)) throw Error("its bin length is not > 0 m");
  if (out.empty()) throw Error("it holds no bins");
  // Optional: a negative gain or a length or span that is not > 0 says the head did not report it.
  const auto number = [&](const std::string& name) {
    const RosValue* value = message.field(name);
    const double* number = value != nullptr ? std::get_if<double>(&value->value) : nullptr;
    return number != nullptr && std::isfinite(*number) ? std::optional<double>(*number) : std::nullopt;
  };
  if (!fields.gain.empty()) {
    if (const std::optional<double> gain = number(fields.gain); gain && *gain >= 0.0) {
      raw.beam.gain_setting = static_cast<int>(*gain);
    }
  }
  if (!fields.pulse_length.empty()) {
    if (const std::optional<double> pulse = number(fields.pulse_length); pulse && *pulse > 0.0) raw.beam.pulse_length_m = *pulse;
  }
  if (!fields.intensity_span.empty()) {
    if (const std::optional<double> span = number(fields.intensity_span); span && *span > 0.0) {
      raw.beam.intensity_span_db = *span;
    }
  }
  if (!fields.beam_width.empty()) {
    const std::optional<double> width = number(fields.beam_width), aperture = number(fields.vertical_aperture);
    if (width && aperture && *width > 0.0 && *width < std::numbers::pi && *aperture > 0.0 && *aperture < std::numbers::pi) {
      raw.nominal_beam = NominalBeam{*width, *aperture};
    }
  }
  raw.time_s = fields.header ? detail::headerTime(message, record_time_s) : record_time_s;
  return raw;
}

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
      const bool first_beam_enough = !decide_unit || options_.bearing_unit != BearingUnit::kAuto ||
                                     fields_->bearing_in_degrees || fields_->bearing_in_radians;
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

  /// Decides the bearings' unit: degrees unless the field's name says radians or every bearing,
  /// at most `largest` in magnitude, fits in a turn of radians; clockwise, as the Tritech head
  /// counts it (ros_bag_reader.hpp); the options override both. Said in the log's notes.
  void decideUnit(double largest) {
    BearingUnit unit = options_.bearing_unit;
    if (unit == BearingUnit::kAuto) {
      const bool degrees = fields_->bearing_in_degrees || (!fields_->bearing_in_radians && beyondRadians(largest));
      unit = degrees ? BearingUnit::kDegrees : BearingUnit::kRadians;
    }
    turn_ = unit == BearingUnit::kDegrees ? 360.0 : unit == BearingUnit::kGradians ? 400.0 : 2.0 * std::numbers::pi;
    clockwise_ = options_.bearing_direction == BearingDirection::kClockwise;
    header_.notes.push_back("bearings of " + topic_ + "'s `" + fields_->bearing + "` read as " +
                            (unit == BearingUnit::kDegrees ? "degrees" : unit == BearingUnit::kGradians ? "gradians" : "radians") +
                            (options_.bearing_unit == BearingUnit::kAuto ? "" : " (as told)") +
                            (clockwise_ ? ", clockwise seen from above (the Tritech head's count)"
                                        : ", counter-clockwise seen from above (as told)"));
  }

  /// Whether a bearing of magnitude `largest` cannot be radians (beyond a turn of them).
  static bool beyondRadians(double largest) { return largest > 2.0 * std::numbers::pi + 1e-6; }

  /// `bearing` in the topic's unit and direction as beam.hpp's clockwise radians in [0, 2π).
  double bearingOf(double bearing) const {
    // Radians are taken as they are (scaling by 2π / 2π could move the last bit).
    const double turned_rad = turn_ == 2.0 * std::numbers::pi ? bearing : bearing * 2.0 * std::numbers::pi / turn_;
    double bearing_rad = std::fmod(clockwise_ ? turned_rad : -turned_rad, 2.0 * std::numbers::pi);
    if (bearing_rad < 0.0) bearing_rad += 2.0 * std::numbers::pi;
    if (!(bearing_rad < 2.0 * std::numbers::pi)) bearing_rad = 0.0;  // −0 and rounding up to a whole turn
    return bearing_rad + 0.0;
  }

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
      fields_ = sonarFields(parsed);
      if (fields_) {
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
        RawBeam raw = beamOf(message, *fields_, time_s);
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
  std::size_t pass_beams_ = 0;  ///< beams given in this pass
  double turn_ = 360.0;         ///< a turn in the topic's bearing unit
  bool clockwise_ = true;
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
