/// @file ros_bag_reader.cpp
/// A ROS 1 bag's sonar topic as a sonar log (see ros_bag_reader.hpp).

#include "sonarmap/formats/ros_bag_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string_view>
#include <vector>

#include "ros_bag_file.hpp"
#include "ros_frames.hpp"
#include "sonarmap/core/errors.hpp"

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
  for (const RosField& field : fields) {
    if (field.name == "header" && field.type == "std_msgs/Header" && field.array < 0) found.header = true;
  }
  return found;
}

/// One beam of a decoded message (bearing as the message gives it; converted afterwards).
struct RawBeam {
  double time_s = 0.0, bearing = 0.0;
  Beam beam;
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

SonarLog readRosBag(const std::string& path, const RosBagOptions& options) {
  SonarLog log;
  std::vector<RawBeam> raw;
  std::string topic;
  std::optional<SonarFields> fields;
  detail::withBagErrors(path, [&] {
    detail::RosBagFile bag(path, options.msg_path);
    std::optional<RosSchema> schema;
    for (const RosBagTopic& candidate : bag.topics()) {
      if (!options.sonar_topic.empty() && candidate.topic != options.sonar_topic) continue;
      const std::string& definition = bag.definition(candidate);
      if (definition.empty()) {
        if (candidate.topic == options.sonar_topic) bag.fail("the connection of " + candidate.topic + " has no message definition");
        continue;
      }
      RosSchema parsed = bag.schema(candidate);
      fields = sonarFields(parsed);
      if (fields) {
        schema = std::move(parsed);
        topic = candidate.topic;
        log.sonar = "ROS topic " + topic + " (" + candidate.type + ")";
        break;
      }
      if (candidate.topic == options.sonar_topic) {
        bag.fail("the topic " + candidate.topic + " (" + candidate.type + ") has no sonar beam's fields "
                 "(a bearing, a bin length or range, and intensities: docs/formats.md)");
      }
    }
    if (!fields) {
      if (!options.sonar_topic.empty()) bag.fail("no topic " + options.sonar_topic + " (topics: " + bag.listing() + ")");
      bag.fail("no topic holds sonar beams (a bearing, a bin length or range, and intensities); topics: " + bag.listing());
    }
    const detail::RosSkipped skipped = bag.forEachMessage(topic, *schema, [&](const RosValue& message, double time_s) {
      raw.push_back(beamOf(message, *fields, time_s));
      if (raw.size() == 1 && fields->header) log.frame_id = detail::headerFrame(message);
    });
    log.skipped_beams = skipped.count;
    log.skip_reasons = skipped.reasons;
    if (raw.empty()) bag.fail("no message of " + topic + " decodes" + (log.skip_reasons.empty() ? "" : ": " + log.skip_reasons.front()));
  });
  // Degrees unless the field's name says radians or every bearing fits in a turn of radians;
  // clockwise, as the Tritech head counts it (ros_bag_reader.hpp); the options override both.
  double largest = 0.0;
  for (const RawBeam& beam : raw) largest = std::max(largest, std::abs(beam.bearing));
  BearingUnit unit = options.bearing_unit;
  if (unit == BearingUnit::kAuto) {
    const bool degrees = fields->bearing_in_degrees || (!fields->bearing_in_radians && largest > 2.0 * std::numbers::pi + 1e-6);
    unit = degrees ? BearingUnit::kDegrees : BearingUnit::kRadians;
  }
  const double turn = unit == BearingUnit::kDegrees ? 360.0 : unit == BearingUnit::kGradians ? 400.0 : 2.0 * std::numbers::pi;
  const bool clockwise = options.bearing_direction == BearingDirection::kClockwise;
  log.notes.push_back("bearings of " + topic + "'s `" + fields->bearing + "` read as " +
                      (unit == BearingUnit::kDegrees ? "degrees" : unit == BearingUnit::kGradians ? "gradians" : "radians") +
                      (options.bearing_unit == BearingUnit::kAuto ? "" : " (as told)") +
                      (clockwise ? ", clockwise seen from above (the Tritech head's count)" : ", counter-clockwise seen from above (as told)"));
  log.beams.reserve(raw.size());
  for (RawBeam& beam : raw) {
    const double turned_rad = beam.bearing * 2.0 * std::numbers::pi / turn;
    double bearing_rad = std::fmod(clockwise ? -turned_rad : turned_rad, 2.0 * std::numbers::pi);
    if (bearing_rad < 0.0) bearing_rad += 2.0 * std::numbers::pi;
    if (!(bearing_rad < 2.0 * std::numbers::pi)) bearing_rad = 0.0;  // −0 and rounding up to a whole turn
    beam.beam.bearing_rad = bearing_rad + 0.0;
    beam.beam.time_s = beam.time_s;
    log.beams.push_back(std::move(beam.beam));
  }
  return log;
}

}  // namespace sonarmap
