/// @file ros_sonar_fields.cpp
/// A sonar message's fields by their roles, its beam, and its bearings' unit (ros_sonar_fields.hpp).

#include "ros_sonar_fields.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string_view>
#include <vector>

#include "ros_frames.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

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

}  // namespace

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

RawBeam beamOf(const RosValue& message, const SonarFields& fields, double record_time_s) {
  RawBeam raw;
  raw.bearing = finiteNumber(message.field(fields.bearing), "bearing");
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
      out.push_back(byteOf(finiteNumber(element.field(fields.element_intensity), "intensity")));
    }
  } else {
    throw Error("its intensities are not an array");
  }
  if (!fields.bin_length.empty()) {
    raw.beam.bin_length_m = finiteNumber(message.field(fields.bin_length), "bin length");
  } else if (!out.empty()) {
    raw.beam.bin_length_m = finiteNumber(message.field(fields.range), "range") / static_cast<double>(out.size());
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
  raw.time_s = fields.header ? headerTime(message, record_time_s) : record_time_s;
  return raw;
}


bool BearingRule::beyondRadians(double largest) { return largest > 2.0 * std::numbers::pi + 1e-6; }

std::string BearingRule::decide(double largest, const std::string& topic) {
  BearingUnit unit = options_.bearing_unit;
  if (unit == BearingUnit::kAuto) {
    const bool degrees = fields_.bearing_in_degrees || (!fields_.bearing_in_radians && beyondRadians(largest));
    unit = degrees ? BearingUnit::kDegrees : BearingUnit::kRadians;
  }
  turn_ = unit == BearingUnit::kDegrees ? 360.0 : unit == BearingUnit::kGradians ? 400.0 : 2.0 * std::numbers::pi;
  clockwise_ = options_.bearing_direction == BearingDirection::kClockwise;
  return "bearings of " + topic + "'s `" + fields_.bearing + "` read as " +
         (unit == BearingUnit::kDegrees ? "degrees" : unit == BearingUnit::kGradians ? "gradians" : "radians") +
         (options_.bearing_unit == BearingUnit::kAuto ? "" : " (as told)") +
         (clockwise_ ? ", clockwise seen from above (the Tritech head's count)" : ", counter-clockwise seen from above (as told)");
}

double BearingRule::bearingRad(double bearing) const {
  // Radians are taken as they are (scaling by 2π / 2π could move the last bit).
  const double turned_rad = turn_ == 2.0 * std::numbers::pi ? bearing : bearing * 2.0 * std::numbers::pi / turn_;
  double bearing_rad = std::fmod(clockwise_ ? turned_rad : -turned_rad, 2.0 * std::numbers::pi);
  if (bearing_rad < 0.0) bearing_rad += 2.0 * std::numbers::pi;
  if (!(bearing_rad < 2.0 * std::numbers::pi)) bearing_rad = 0.0;  // −0 and rounding up to a whole turn
  return bearing_rad + 0.0;
}

}  // namespace sonarmap::detail
