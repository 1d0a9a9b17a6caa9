#pragma once
/// @file ros_sonar_fields.hpp
/// Private to formats: where a sonar message keeps a beam's parts, found by the fields' roles, one
/// decoded message as a beam, and the bearing's unit and direction (the rules of
/// ros_bag_reader.hpp's comment). The one implementation behind the bag readers (ros_bag_reader.cpp)
/// and the message decoder of a live topic (ros_sonar_message.hpp).

#include <optional>
#include <string>

#include "ros_message.hpp"
#include "sonarmap/formats/ros_bag_reader.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap::detail {

/// Where a topic's message keeps a beam's parts (see ros_bag_reader.hpp).
struct SonarFields {
  std::string bearing, bin_length, range, intensities, element_intensity;  // field names; empty: absent
  std::string gain, pulse_length, intensity_span;                          // optional; empty: absent
  std::string beam_width, vertical_aperture;                               // the log's beam; optional
  bool bearing_in_degrees = false, bearing_in_radians = false;             // said by the name
  bool header = false;
};

/// The sonar fields of `schema`'s top message, or nothing when it lacks one of them.
std::optional<SonarFields> sonarFields(const RosSchema& schema);

/// One beam of a decoded message (bearing as the message gives it; converted afterwards).
struct RawBeam {
  double time_s = 0.0, bearing = 0.0;
  Beam beam;
  std::optional<NominalBeam> nominal_beam;  ///< when the message records its sonar's beam
};

/// The beam of one decoded message; its time is the header's stamp, else `record_time_s`.
/// @throws Error saying what is wrong (no finite bearing, no bins, a bin length not > 0).
RawBeam beamOf(const RosValue& message, const SonarFields& fields, double record_time_s);

/// A topic's bearings in beam.hpp's clockwise radians: the unit and direction told, named by the
/// field, or decided from the largest bearing (ros_bag_reader.hpp's rules).
class BearingRule {
 public:
  BearingRule(const SonarFields& fields, const RosBagOptions& options) : fields_(fields), options_(options) {}
  /// Whether the unit is known without seeing the bearings (told, or named by the field).
  bool unitKnown() const {
    return options_.bearing_unit != BearingUnit::kAuto || fields_.bearing_in_degrees || fields_.bearing_in_radians;
  }
  /// Whether a bearing of magnitude `largest` cannot be radians (beyond a turn of them).
  static bool beyondRadians(double largest);
  /// Decides the unit: degrees unless the field's name says radians or every bearing, at most
  /// `largest` in magnitude, fits in a turn of radians; the options override. Returns the note
  /// saying it, naming `topic`.
  std::string decide(double largest, const std::string& topic);
  /// `bearing` in the topic's unit and direction as clockwise radians in [0, 2π).
  double bearingRad(double bearing) const;

 private:
  SonarFields fields_;
  RosBagOptions options_;
  double turn_ = 360.0;  ///< a turn in the topic's bearing unit
  bool clockwise_ = true;
};

}  // namespace sonarmap::detail
