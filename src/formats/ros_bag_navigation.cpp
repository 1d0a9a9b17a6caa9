/// @file ros_bag_navigation.cpp
/// A ROS 1 bag's topics and navigation (see ros_bag_navigation.hpp).

#include "sonarmap/formats/ros_bag_navigation.hpp"

#include <algorithm>
#include <cmath>

#include "ros_bag_file.hpp"
#include "ros_frames.hpp"
#include "ros_inertial_navigation.hpp"

namespace sonarmap {
namespace {

using detail::RosField;
using detail::RosSchema;
using detail::RosValue;

bool hasFields(const RosSchema& schema, const std::string& type, std::initializer_list<const char*> names) {
  if (RosSchema::isBuiltin(type)) return false;
  const std::vector<RosField>& fields = schema.fields(type);
  return std::all_of(names.begin(), names.end(), [&](const char* name) {
    return std::any_of(fields.begin(), fields.end(), [&](const RosField& f) { return f.name == name && f.array < 0; });
  });
}

const RosField* fieldNamed(const RosSchema& schema, const std::string& type, const char* name) {
  if (RosSchema::isBuiltin(type)) return nullptr;
  for (const RosField& field : schema.fields(type)) {
    if (field.name == name && field.array < 0) return &field;
  }
  return nullptr;
}

/// The fields leading from the message to its pose (a message with `position` x, y, z and
/// `orientation` x, y, z, w), or empty when it has none, or no std_msgs/Header.
std::vector<std::string> posePath(const RosSchema& schema) {
  const RosField* header = fieldNamed(schema, schema.root(), "header");
  if (header == nullptr || header->type != "std_msgs/Header") return {};
  auto isPose = [&](const std::string& type) {
    const RosField* position = fieldNamed(schema, type, "position");
    const RosField* orientation = fieldNamed(schema, type, "orientation");
    return position != nullptr && orientation != nullptr && hasFields(schema, position->type, {"x", "y", "z"}) &&
           hasFields(schema, orientation->type, {"x", "y", "z", "w"});
  };
  const RosField* pose = fieldNamed(schema, schema.root(), "pose");
  if (pose == nullptr) return {};
  if (isPose(pose->type)) return {"pose"};
  const RosField* inner = fieldNamed(schema, pose->type, "pose");
  if (inner != nullptr && isPose(inner->type)) return {"pose", "pose"};
  return {};
}

double number(const RosValue* value, const char* what) {
  const double* out = value != nullptr ? std::get_if<double>(&value->value) : nullptr;
  if (out == nullptr || !std::isfinite(*out)) throw Error(std::string("its ") + what + " is not a finite number");
  return *out;
}

/// One message's fix, NED and FRD.
NavSample fixOf(const RosValue& message, const std::vector<std::string>& path, double record_time_s, bool& ned) {
  const RosValue* header = message.field("header");
  const RosValue* frame = header->field("frame_id");
  const std::string* frame_id = frame != nullptr ? std::get_if<std::string>(&frame->value) : nullptr;
  ned = frame_id != nullptr && detail::namesNedFrame(*frame_id);
  const RosValue* pose = &message;
  for (const std::string& name : path) pose = pose->field(name);
  const RosValue* position = pose->field("position");
  const RosValue* orientation = pose->field("orientation");
  const Eigen::Vector3d p(number(position->field("x"), "position x"), number(position->field("y"), "position y"),
                          number(position->field("z"), "position z"));
  const Eigen::Quaterniond q(number(orientation->field("w"), "orientation w"), number(orientation->field("x"), "orientation x"),
                             number(orientation->field("y"), "orientation y"), number(orientation->field("z"), "orientation z"));
  const double stamp = number(header->field("stamp"), "header stamp");
  return detail::rosPoseToNed(stamp > 0.0 ? stamp : record_time_s, p, q, ned);
}

}  // namespace

std::vector<RosBagTopic> listRosBagTopics(const std::string& path) {
  return detail::withBagErrors(path, [&] { return detail::RosBagFile(path).topics(); });
}

std::optional<RosBagNavigation> readRosBagNavigation(const std::string& path, const RosBagNavOptions& options) {
  return detail::withBagErrors(path, [&]() -> std::optional<RosBagNavigation> {
    detail::RosBagFile bag(path);
    // The candidates: every topic with a pose, nav_msgs/Odometry first, then by message count.
    struct Candidate {
      const RosBagTopic* topic;
      std::vector<std::string> path;
    };
    std::vector<Candidate> candidates;
    bool named = false;
    for (const RosBagTopic& topic : bag.topics()) {
      if (!options.nav_topic.empty() && topic.topic != options.nav_topic) continue;
      named = true;
      const std::string& definition = bag.definition(topic);
      if (definition.empty()) continue;
      const RosSchema schema = bag.schema(topic);
      std::vector<std::string> found = posePath(schema);
      if (!found.empty()) candidates.push_back({&topic, std::move(found)});
    }
    if (!options.nav_topic.empty()) {
      if (!named) bag.fail("no topic " + options.nav_topic + " (topics: " + bag.listing() + ")");
      if (candidates.empty()) {
        bag.fail("the topic " + options.nav_topic + " holds no pose (a std_msgs/Header and pose.position and "
                 "pose.orientation, or pose.pose.*: docs/formats.md)");
      }
    }
    if (candidates.empty()) return detail::inertialNavigation(bag, options);
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
      auto odometry = [](const RosBagTopic* t) { return t->type == "nav_msgs/Odometry" || t->type == "nav_msgs/msg/Odometry"; };
      const bool a_odometry = odometry(a.topic), b_odometry = odometry(b.topic);
      if (a_odometry != b_odometry) return a_odometry;
      return a.topic->messages > b.topic->messages;
    });
    const Candidate& chosen = candidates.front();
    RosBagNavigation nav;
    nav.topic = chosen.topic->topic;
    nav.type = chosen.topic->type;
    const RosSchema schema = bag.schema(*chosen.topic);
    bool any_ned = false, any_enu = false;
    const detail::RosSkipped skipped = bag.forEachMessage(nav.topic, schema, [&](const RosValue& message, double time_s) {
      bool ned = false;
      const NavSample fix = fixOf(message, chosen.path, time_s, ned);
      if (!nav.track.empty() && !(fix.time_s > nav.track.back().time_s)) {
        throw Error("its time " + std::to_string(fix.time_s) + " s is not after the previous fix's");
      }
      (ned ? any_ned : any_enu) = true;
      nav.track.push_back(fix);
    });
    nav.skipped = skipped.count;
    nav.skip_reasons = skipped.reasons;
    if (nav.track.empty()) {
      bag.fail("no message of " + nav.topic + " gives a fix" + (skipped.reasons.empty() ? "" : ": " + skipped.reasons.front()));
    }
    nav.frame = any_ned && any_enu ? "NED and ENU (REP 103) by each message's frame_id, turned into NED"
                : any_ned          ? "NED"
                                   : "ENU (REP 103), turned into NED";
    return nav;
  });
}

}  // namespace sonarmap
