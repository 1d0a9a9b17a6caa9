#pragma once
/// @file ros_bag_reader.hpp
/// ROS 1 bags (format 2.0: `.bag`) as sonar logs: the container read by Debian's rosbag_storage
/// (chunks, bz2 and lz4 compression, the index), each message decoded from the definition the bag
/// stores with its connection, so that a driver's own message needs no compiled package
/// (docs/formats.md, "ROS 1 bags").
///
/// The sonar topic is found by its fields' roles, on the message's top level:
///  - a bearing: a number named `angle`, `bearing` (either with `_deg` or `_rad`), or `head_angle`;
///  - a bin length: `bin_distance_step`, `bin_length`, `bin_length_m`, `bin_size`,
///    `range_resolution` or `step_dist` (metres); or a range, `range`, `range_m`, `max_range` or
///    `range_max` (metres), divided by the bins;
///  - the intensities: a uint8/int8/byte array named `intensities`, `intensity`, `data`, `bins`,
///    `samples` or `echo`, or an array of messages holding a number named `intensity` or `value`
///    (micron_driver_ros/ScanLine's `IntensityBin[] bins`); values clamped to 0…255;
///  - when present, what the head reported: an integer `gain_setting` or `gain` (Beam::gain_setting;
///    negative: not reported), `pulse_length_m` and `intensity_span_db` (unset unless > 0); and the
///    sonar's beam, `beam_width_rad` and `vertical_aperture_rad` (SonarLog::nominal_beam, from the
///    first beam; unset unless both are in (0, π)).
/// Each beam's time is its `header.stamp` (seconds since the epoch) when the message has a
/// std_msgs/Header with a stamp, else the time the bag recorded it. Units and direction of the
/// bearing: `_rad` and `_deg` say it; otherwise degrees when any bearing of the topic exceeds 2π,
/// else radians. The bearing grows clockwise seen from above, as the Tritech head counts it (the
/// micron_driver_ros driver publishes the SeaNet head's bearing, 1/16 gradian clockwise, in
/// degrees; docs/formats.md, SeaNet), as beam.hpp's radians count; the message's zero is bearing 0.
/// RosBagOptions::bearing_unit and bearing_direction override both. What was decided is said in
/// SonarLog::notes.

#include <memory>
#include <string>
#include <string_view>

#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/beam_source.hpp"

namespace sonarmap {

/// The unit of a topic's bearings: decided from the field's name and values (kAuto, see the
/// file's comment) or said by the user where a bag cannot tell (a turn is 360°, 2π rad, 400 grad).
enum class BearingUnit { kAuto, kDegrees, kRadians, kGradians };
/// Which way a topic's bearings grow seen from above: clockwise as Tritech heads count (the
/// default), or counter-clockwise as ROS's REP 103 angles do.
enum class BearingDirection { kClockwise, kCounterClockwise };

/// "auto", "deg", "rad" or "grad". @throws ValueError for any other, listing them.
BearingUnit parseBearingUnit(std::string_view name);
/// "cw" or "ccw". @throws ValueError for any other, listing them.
BearingDirection parseBearingDirection(std::string_view name);

/// Options of readRosBag().
struct RosBagOptions {
  /// The sonar topic; empty: the first topic, in the bag's connection order, whose message has a
  /// sonar beam's fields (see the file's comment).
  std::string sonar_topic{};
  BearingUnit bearing_unit = BearingUnit::kAuto;
  BearingDirection bearing_direction = BearingDirection::kClockwise;
  /// A folder of `.msg` files for the types a rosbag2 SQLite log (before ROS 2 Iron) names without
  /// their definitions: `PKG/msg/NAME.msg` (docs/formats.md); empty: the built-in types only.
  std::string msg_path{};
};

/// Reads the sonar beams of a ROS 1 bag (see the file's comment), in the bag's time order.
/// Messages that do not decode (a truncated message, a count beyond its bytes) are skipped and
/// counted in SonarLog::skipped_beams with their reason; the valid ones before and after are kept.
/// SonarLog::sonar names the topic and its type.
/// @throws FileError naming the file when it cannot be opened or is not a readable ROS 1 bag (the
///         container's error: a truncated chunk, an unknown compression, a missing index), when a
///         connection's message definition does not parse, when `options.sonar_topic` is not in the
///         bag or has no sonar fields, when no topic has them (listing the topics and their types),
///         or when no message of the topic decodes.
SonarLog readRosBag(const std::string& path, const RosBagOptions& options = {});

/// readRosBag's beams one at a time (beam_source.hpp), the same beams in the same order with the
/// same header, skips and notes, read from the file as they are asked for: a chunk of the bag at a
/// time, whatever its length. Opening reads the topics and the topic up to its first beam (its
/// frame); without a unit given or named by the bearing's field, on up to the first bearing beyond
/// 2π (degrees), or through (radians). The skips are counted once a pass has reached the end.
/// @throws FileError as readRosBag: on opening for the bag, its topic, or a topic of which no
///         message decodes; from next() for a container's error met later.
std::unique_ptr<BeamSource> openRosBag(const std::string& path, const RosBagOptions& options = {});

}  // namespace sonarmap
