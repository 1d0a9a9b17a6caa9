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

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <ros/serialization.h>

#include "ros_bag_check.hpp"
#include "ros_message.hpp"
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

double numberOf(const RosValue* value, const char* what) {
  const double* number = value != nullptr ? std::get_if<double>(&value->value) : nullptr;
  if (number == nullptr || !std::isfinite(*number)) throw Error(std::string("its ") + what + " is not a finite number");
  return *number;
}

/// One beam of a decoded message (bearing as the message gives it; converted afterwards).
struct RawBeam {
  double time_s = 0.0, bearing = 0.0;
  Beam beam;
};

RawBeam beamOf(const RosValue& message, const SonarFields& fields, double record_time_s) {
  RawBeam raw;
  raw.bearing = numberOf(message.field(fields.bearing), "bearing");
  const RosValue* intensities = message.field(fields.intensities);
  std::vector<std::uint8_t>& out = raw.beam.intensities;
  if (const auto* bytes = std::get_if<std::vector<std::uint8_t>>(&intensities->value)) {
    out = *bytes;
  } else {
    for (const RosValue& element : std::get<std::vector<RosValue>>(intensities->value)) {
      const double value = numberOf(element.field(fields.element_intensity), "intensity");
      out.push_back(static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L)));
    }
  }
  if (!fields.bin_length.empty()) {
    raw.beam.bin_length_m = numberOf(message.field(fields.bin_length), "bin length");
  } else if (!out.empty()) {
    raw.beam.bin_length_m = numberOf(message.field(fields.range), "range") / static_cast<double>(out.size());
  }
  if (!(raw.beam.bin_length_m > 0.0)) throw Error("its bin length is not > 0 m");
  if (out.empty()) throw Error("it holds no bins");
  raw.time_s = record_time_s;
  if (fields.header) {
    const RosValue* header = message.field("header");
    const double stamp = numberOf(header->field("stamp"), "header stamp");
    if (stamp > 0.0) raw.time_s = stamp;
  }
  return raw;
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw FileError("'" + path + "': ROS bag: " + what);
}

}  // namespace

SonarLog readRosBag(const std::string& path, const RosBagOptions& options) {
  SonarLog log;
  std::vector<RawBeam> raw;
  std::string topic;
  std::optional<SonarFields> fields;
  try {
    detail::checkBagRecords(path);
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    rosbag::View everything(bag);
    std::optional<RosSchema> schema;
    std::string listing;
    for (const rosbag::ConnectionInfo* connection : everything.getConnections()) {
      listing += (listing.empty() ? "" : ", ") + connection->topic + " (" + connection->datatype +
                 (connection->msg_def.empty() ? ", no message definition)" : ")");
      if (fields || (!options.sonar_topic.empty() && connection->topic != options.sonar_topic)) continue;
      if (connection->msg_def.empty()) {
        if (connection->topic == options.sonar_topic) fail(path, "the connection of " + connection->topic + " has no message definition");
        continue;
      }
      RosSchema candidate(connection->datatype, connection->msg_def);
      fields = sonarFields(candidate);
      if (fields) {
        schema = std::move(candidate);
        topic = connection->topic;
        log.sonar = "ROS topic " + topic + " (" + connection->datatype + ")";
      } else if (connection->topic == options.sonar_topic) {
        fail(path, "the topic " + connection->topic + " (" + connection->datatype + ") has no sonar beam's fields "
                   "(a bearing, a bin length or range, and intensities: docs/formats.md)");
      }
    }
    if (!fields) {
      if (!options.sonar_topic.empty()) fail(path, "no topic " + options.sonar_topic + " (topics: " + listing + ")");
      fail(path, "no topic holds sonar beams (a bearing, a bin length or range, and intensities); topics: " +
                     (listing.empty() ? std::string("none") : listing));
    }
    rosbag::View view(bag, rosbag::TopicQuery(topic));
    std::vector<std::uint8_t> bytes;
    std::size_t index = 0;
    for (const rosbag::MessageInstance& message : view) {
      ++index;
      try {
        bytes.resize(message.size());
        ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
        message.write(stream);
        raw.push_back(beamOf(detail::decodeRosMessage(*schema, bytes), *fields, message.getTime().toSec()));
      } catch (const Error& error) {
        ++log.skipped_beams;
        log.skip_reasons.push_back("message " + std::to_string(index) + " of " + topic + ": " + error.what());
      }
    }
  } catch (const Error& error) {
    if (dynamic_cast<const FileError*>(&error) != nullptr) throw;
    fail(path, error.what());
  } catch (const std::exception& error) {  // rosbag's BagException and its kin, boost's
    fail(path, error.what());
  }
  if (raw.empty()) fail(path, "no message of " + topic + " decodes" + (log.skip_reasons.empty() ? "" : ": " + log.skip_reasons.front()));
  // Degrees unless the field's name says radians or every bearing fits in a turn of radians;
  // clockwise, as the Tritech head counts it (ros_bag_reader.hpp).
  double largest = 0.0;
  for (const RawBeam& beam : raw) largest = std::max(largest, std::abs(beam.bearing));
  const bool degrees = fields->bearing_in_degrees || (!fields->bearing_in_radians && largest > 2.0 * std::numbers::pi + 1e-6);
  log.notes.push_back("bearings of " + topic + "'s `" + fields->bearing + "` read as " +
                      (degrees ? "degrees" : "radians") + ", clockwise seen from above (the Tritech head's count)");
  log.beams.reserve(raw.size());
  for (RawBeam& beam : raw) {
    const double clockwise_rad = degrees ? beam.bearing * std::numbers::pi / 180.0 : beam.bearing;
    double bearing_rad = std::fmod(-clockwise_rad, 2.0 * std::numbers::pi);
    if (bearing_rad < 0.0) bearing_rad += 2.0 * std::numbers::pi;
    if (!(bearing_rad < 2.0 * std::numbers::pi)) bearing_rad = 0.0;  // −0 and rounding up to a whole turn
    beam.beam.bearing_rad = bearing_rad + 0.0;
    beam.beam.time_s = beam.time_s;
    log.beams.push_back(std::move(beam.beam));
  }
  return log;
}

}  // namespace sonarmap
