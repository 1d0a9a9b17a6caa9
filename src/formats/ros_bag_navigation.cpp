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

using detail::RosSchema;
using detail::RosValue;

/// The fields of a fix given in NED and Euler angles (dive_recorder.hpp's NavFix, and any message
/// laid out so): north_m, east_m, down_m, roll_rad, pitch_rad, yaw_rad on its top level.
constexpr std::initializer_list<const char*> kNedFixFields{"north_m", "east_m", "down_m", "roll_rad", "pitch_rad", "yaw_rad"};

/// The fields leading from the message to its pose (a message with `position` x, y, z and
/// `orientation` x, y, z, w), {"."} for a message holding kNedFixFields itself, or empty when it
/// has neither, or no std_msgs/Header.
std::vector<std::string> posePath(const RosSchema& schema) {
  if (schema.typeAt({"header"}) != "std_msgs/Header") return {};
  if (schema.holdsNumbers({}, kNedFixFields)) return {"."};
  for (std::vector<std::string> path : {std::vector<std::string>{"pose"}, std::vector<std::string>{"pose", "pose"}}) {
    std::vector<std::string> position = path, orientation = path;
    position.emplace_back("position");
    orientation.emplace_back("orientation");
    if (schema.holdsNumbers(position, {"x", "y", "z"}) && schema.holdsNumbers(orientation, {"x", "y", "z", "w"})) return path;
  }
  return {};
}

/// One message's fix, NED and FRD; `ned` says which frame its header named.
NavSample fixOf(const RosValue& message, const std::vector<std::string>& path, double record_time_s, bool& ned) {
  using detail::finiteNumber;
  if (path.size() == 1 && path.front() == ".") {  // NED and Euler angles, taken as they are
    ned = true;
    NavSample fix;
    fix.time_s = detail::headerTime(message, record_time_s);
    fix.position_ned_m = {finiteNumber(message.field("north_m"), "north_m"), finiteNumber(message.field("east_m"), "east_m"),
                          finiteNumber(message.field("down_m"), "down_m")};
    fix.roll_rad = finiteNumber(message.field("roll_rad"), "roll_rad");
    fix.pitch_rad = finiteNumber(message.field("pitch_rad"), "pitch_rad");
    fix.yaw_rad = finiteNumber(message.field("yaw_rad"), "yaw_rad");
    return fix;
  }
  ned = detail::headerNamesNed(message);
  const RosValue& pose = detail::valueAt(message, path);
  const RosValue* position = pose.field("position");
  const RosValue* orientation = pose.field("orientation");
  const Eigen::Vector3d p(finiteNumber(position->field("x"), "position x"), finiteNumber(position->field("y"), "position y"),
                          finiteNumber(position->field("z"), "position z"));
  const Eigen::Quaterniond q(finiteNumber(orientation->field("w"), "orientation w"), finiteNumber(orientation->field("x"), "orientation x"),
                             finiteNumber(orientation->field("y"), "orientation y"), finiteNumber(orientation->field("z"), "orientation z"));
  return detail::rosPoseToNed(detail::headerTime(message, record_time_s), p, q, ned);
}

/// The fixes of the bag's NavSatFix topic (the one with most messages), into `nav`.
void readGeodeticFixes(detail::RosBagFile& bag, RosBagNavigation& nav) {
  const RosBagTopic* chosen = nullptr;
  for (const RosBagTopic& topic : bag.topics()) {
    if (bag.definition(topic).empty()) continue;
    const RosSchema schema = bag.schema(topic);
    if (schema.typeAt({"header"}) != "std_msgs/Header" || !schema.holdsNumbers({}, {"latitude", "longitude", "altitude"}) ||
        !schema.holdsNumbers({"status"}, {"status"})) {
      continue;
    }
    if (chosen == nullptr || topic.messages > chosen->messages) chosen = &topic;
  }
  if (chosen == nullptr) return;
  nav.geodetic_topic = chosen->topic;
  const RosSchema schema = bag.schema(*chosen);
  const detail::RosSkipped skipped = bag.forEachMessage(chosen->topic, schema, [&](const RosValue& message, double time_s) {
    using detail::finiteNumber;
    if (finiteNumber(message.field("status")->field("status"), "status.status") < 0.0) return;  // STATUS_NO_FIX
    GeodeticFix fix;
    fix.time_s = detail::headerTime(message, time_s);
    fix.point = {finiteNumber(message.field("latitude"), "latitude"), finiteNumber(message.field("longitude"), "longitude"),
                 finiteNumber(message.field("altitude"), "altitude")};
    requireGeodetic(fix.point, "NavSatFix at " + std::to_string(fix.time_s) + " s");
    if (!nav.geodetic_fixes.empty() && !(fix.time_s > nav.geodetic_fixes.back().time_s)) {
      throw Error("its time " + std::to_string(fix.time_s) + " s is not after the previous fix's");
    }
    nav.geodetic_fixes.push_back(fix);
  });
  nav.geodetic_skipped = skipped.count;
  for (const std::string& reason : skipped.reasons) nav.skip_reasons.push_back(reason);
}

}  // namespace

std::vector<RosBagTopic> listRosBagTopics(const std::string& path, const std::string& msg_path) {
  return detail::withBagErrors(path, [&] { return detail::RosBagFile(path, msg_path).topics(); });
}

std::optional<RosBagNavigation> readRosBagNavigation(const std::string& path, const RosBagNavOptions& options) {
  return detail::withBagErrors(path, [&]() -> std::optional<RosBagNavigation> {
    detail::RosBagFile bag(path, options.msg_path);
    // The candidates: every topic with a pose, nav_msgs/Odometry first, then by message count. A
    // topic without a message is no navigation unless named (a recording made without one still
    // declares its channel).
    struct Candidate {
      const RosBagTopic* topic;
      std::vector<std::string> path;
    };
    std::vector<Candidate> candidates;
    bool named = false;
    for (const RosBagTopic& topic : bag.topics()) {
      if (!options.nav_topic.empty() && topic.topic != options.nav_topic) continue;
      named = true;
      if (options.nav_topic.empty() && topic.messages == 0) continue;
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
    if (candidates.empty()) {
      std::optional<RosBagNavigation> inertial = detail::inertialNavigation(bag, options);
      if (inertial) readGeodeticFixes(bag, *inertial);
      return inertial;
    }
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
      if (nav.track.empty()) {
        const RosValue* child = message.field("child_frame_id");
        const std::string* name = child != nullptr ? std::get_if<std::string>(&child->value) : nullptr;
        nav.body_frame = name != nullptr && !name->empty() ? detail::tfFrame(*name)
                                                           : (ned ? "base_link_frd" : "base_link");
      }
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
    readGeodeticFixes(bag, nav);
    return nav;
  });
}

}  // namespace sonarmap
