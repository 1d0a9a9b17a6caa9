#pragma once
/// @file ros_sonar_message.hpp
/// A live ROS 1 sonar topic's messages as beams, decoded by the definition the topic's publisher
/// sends (topic_tools::ShapeShifter hands a subscriber the type, the definition and the bytes), with
/// the bag readers' rules (ros_bag_reader.hpp: the fields found by their roles, the header's stamp,
/// the bearing's unit and direction), so a driver's message needs no compiled package. And the two
/// ROS frame conversions a live subscriber needs, the bag readers' own: a pose (REP 103 ENU/FLU, or
/// NED/FRD by the frame's name) as a NavSample, and a body → sonar transform as the mapper's
/// sonar_to_body (ros_bag_navigation.hpp, ros_bag_mounting.hpp).

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include <Eigen/Geometry>

#include "sonarmap/formats/ros_bag_reader.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// One decoded sonar message.
struct RosSonarMessage {
  /// The beam: time_s its header's stamp (seconds since the epoch) or the receive time, bin length,
  /// intensities and the head's settings the message carries; bearing_rad is set only when the
  /// decoder's bearing unit is decided (RosSonarDecoder::unitDecided), else 0.
  Beam beam;
  double bearing = 0.0;                     ///< as the message gives it (the topic's unit)
  std::optional<NominalBeam> nominal_beam;  ///< when the message records its sonar's beam
  std::string frame_id;                     ///< its header's frame (tf2's name), or empty
};

/// Decodes a sonar topic's messages (see the file's comment).
class RosSonarDecoder {
 public:
  /// @param type        the message type, "pkg/Name"
  /// @param definition  its full definition as ROS 1 sends it (the connection's message_definition)
  /// @param options     bearing unit and direction as a bag's (RosBagOptions; sonar_topic names the
  ///                    topic in notes and errors)
  /// @throws ValueError when the definition does not parse or its message has no sonar beam's
  ///         fields (a bearing, a bin length or range, and intensities: docs/formats.md).
  RosSonarDecoder(const std::string& type, const std::string& definition, const RosBagOptions& options = {});
  ~RosSonarDecoder();
  RosSonarDecoder(RosSonarDecoder&&) noexcept;
  RosSonarDecoder& operator=(RosSonarDecoder&&) noexcept;

  /// One message's serialized bytes (ROS 1), received at `receive_time_s` (seconds since the epoch).
  /// @throws Error saying what is wrong: bytes that end early or run over, no finite bearing, no
  ///         bins, a bin length not > 0.
  RosSonarMessage decode(std::span<const std::uint8_t> bytes, double receive_time_s) const;

  /// Whether the bearing unit is decided: told by the options, named by the field (`_deg`,
  /// `_rad`), or by decideUnit().
  bool unitDecided() const;
  /// Decides an automatic unit as a bag's topic is (ros_bag_reader.hpp): degrees when `largest`,
  /// the largest bearing magnitude seen, is beyond a turn of radians, else radians; with a unit
  /// told or named, that one. Returns the note saying what was decided.
  std::string decideUnit(double largest);
  /// Whether a bearing of magnitude `largest` settles an automatic unit as degrees.
  static bool beyondRadians(double largest);
  /// `bearing`, in the topic's unit, as beam.hpp's clockwise radians in [0, 2π).
  /// @throws ValueError before the unit is decided.
  double bearingRad(double bearing) const;
  /// The name of the message's bearing field.
  const std::string& bearingField() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A vehicle's pose as ROS gives it (a position in metres and the body's orientation in the world
/// frame `world_frame`) as a NavSample, NED with a forward-right-down body: ENU with a
/// forward-left-up body (REP 103), or NED/FRD when the frame's name says NED (REP 105's "_ned"), as
/// the bag's navigation is read (ros_bag_navigation.hpp).
/// @throws ValueError when the quaternion's norm is not within 1 ± 0.1 or a value is not finite.
NavSample rosPoseFix(double time_s, const Eigen::Vector3d& position_m, const Eigen::Quaterniond& body_to_world,
                     const std::string& world_frame);

/// Whether a ROS frame's name says NED (contains "ned" in any case: REP 105's "odom_ned"), the rule
/// the bag readers read a pose's frame by; any other frame is ENU (REP 103).
bool rosFrameIsNed(const std::string& frame_id);

/// The mounting a ROS transform gives: `sonar_in_body`, the pose of the frame `sonar_frame` in
/// `body_frame` (tf2's lookupTransform(body, sonar)), as the mapper's sonar_to_body (sonar FRD →
/// body FRD), each frame FLU unless its name says FRD or NED, as readRosBagMounting reads a bag's
/// /tf_static (ros_bag_mounting.hpp).
Eigen::Isometry3d rosMountingToBody(const Eigen::Isometry3d& sonar_in_body, const std::string& body_frame,
                                    const std::string& sonar_frame);

}  // namespace sonarmap
