/// @file ros_sonar_message.cpp
/// A live sonar topic's messages decoded by their definition (see ros_sonar_message.hpp).

#include "sonarmap/formats/ros_sonar_message.hpp"

#include <cmath>

#include "ros_frames.hpp"
#include "ros_message.hpp"
#include "ros_sonar_fields.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {

struct RosSonarDecoder::Impl {
  std::string topic;
  std::unique_ptr<detail::RosSchema> schema;  ///< decoded messages point into it: kept in place
  detail::SonarFields fields;
  std::optional<detail::BearingRule> bearing;
  bool decided = false;
};

RosSonarDecoder::RosSonarDecoder(const std::string& type, const std::string& definition, const RosBagOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->topic = options.sonar_topic.empty() ? type : options.sonar_topic;
  try {
    impl_->schema = std::make_unique<detail::RosSchema>(type, definition);
  } catch (const Error& error) {
    throw ValueError(impl_->topic + " (" + type + "): its message definition does not parse: " + error.what());
  }
  std::optional<detail::SonarFields> fields = detail::sonarFields(*impl_->schema);
  if (!fields) {
    throw ValueError(impl_->topic + " (" + type + ") has no sonar beam's fields (a bearing, a bin length or range, and "
                     "intensities: docs/formats.md)");
  }
  impl_->fields = *fields;
  impl_->bearing.emplace(impl_->fields, options);
  if (impl_->bearing->unitKnown()) decideUnit(0.0);
}

RosSonarDecoder::~RosSonarDecoder() = default;
RosSonarDecoder::RosSonarDecoder(RosSonarDecoder&&) noexcept = default;
RosSonarDecoder& RosSonarDecoder::operator=(RosSonarDecoder&&) noexcept = default;

RosSonarMessage RosSonarDecoder::decode(std::span<const std::uint8_t> bytes, double receive_time_s) const {
  const detail::RosValue message = detail::decodeRosMessage(*impl_->schema, bytes);
  detail::RawBeam raw = detail::beamOf(message, impl_->fields, receive_time_s);
  RosSonarMessage out;
  out.beam = std::move(raw.beam);
  out.beam.time_s = raw.time_s;
  out.bearing = raw.bearing;
  if (impl_->decided) out.beam.bearing_rad = impl_->bearing->bearingRad(raw.bearing);
  out.nominal_beam = raw.nominal_beam;
  if (impl_->fields.header) out.frame_id = detail::headerFrame(message);
  return out;
}

bool RosSonarDecoder::unitDecided() const { return impl_->decided; }

std::string RosSonarDecoder::decideUnit(double largest) {
  impl_->decided = true;
  return impl_->bearing->decide(largest, impl_->topic);
}

bool RosSonarDecoder::beyondRadians(double largest) { return detail::BearingRule::beyondRadians(largest); }

double RosSonarDecoder::bearingRad(double bearing) const {
  if (!impl_->decided) throw ValueError(impl_->topic + ": the bearings' unit is not decided yet");
  return impl_->bearing->bearingRad(bearing);
}

const std::string& RosSonarDecoder::bearingField() const { return impl_->fields.bearing; }

bool rosFrameIsNed(const std::string& frame_id) { return detail::namesNedFrame(frame_id); }

NavSample rosPoseFix(double time_s, const Eigen::Vector3d& position_m, const Eigen::Quaterniond& body_to_world,
                     const std::string& world_frame) {
  if (!std::isfinite(time_s) || !position_m.allFinite() || !body_to_world.coeffs().allFinite()) {
    throw ValueError("ROS pose in " + world_frame + ": a value is not finite");
  }
  try {
    return detail::rosPoseToNed(time_s, position_m, body_to_world, detail::namesNedFrame(world_frame));
  } catch (const ValueError&) {
    throw;
  } catch (const Error& error) {
    throw ValueError("ROS pose in " + world_frame + ": " + error.what());
  }
}

}  // namespace sonarmap
