/// @file ros_bag_mounting.cpp
/// readRosBagMounting: a sonar's mounting from a ROS log's /tf_static (see ros_bag_mounting.hpp).

#include "sonarmap/formats/ros_bag_mounting.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <queue>
#include <vector>

#include "ros_bag_file.hpp"
#include "ros_frames.hpp"
#include "sonarmap/formats/ros_sonar_message.hpp"

namespace sonarmap {
namespace {

using detail::RosSchema;
using detail::RosValue;
using detail::headerFrame;

const std::string* textOf(const RosValue* value) { return value != nullptr ? std::get_if<std::string>(&value->value) : nullptr; }

/// A body frame named forward-right-down (or NED-fixed, as MAVROS's "base_link_frd").
bool namesFrd(const std::string& frame) {
  std::string lower = frame;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("frd") != std::string::npos || detail::namesNedFrame(frame);
}

/// One transform: the pose of `child` in `parent`.
struct Edge {
  std::string to;
  Eigen::Isometry3d transform;  ///< maps `to`'s coordinates into the frame the edge leaves from
};

Eigen::Isometry3d transformOf(const RosValue& transform) {
  using detail::finiteNumber;
  const RosValue* t = transform.field("translation");
  const RosValue* r = transform.field("rotation");
  if (t == nullptr || r == nullptr) throw Error("its transform has no translation and rotation");
  const Eigen::Quaterniond q(finiteNumber(r->field("w"), "rotation w"), finiteNumber(r->field("x"), "rotation x"),
                             finiteNumber(r->field("y"), "rotation y"), finiteNumber(r->field("z"), "rotation z"));
  if (!(std::abs(q.norm() - 1.0) <= 0.1)) throw Error("its rotation is no unit quaternion");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(finiteNumber(t->field("x"), "translation x"), finiteNumber(t->field("y"), "translation y"),
                                       finiteNumber(t->field("z"), "translation z"));
  return pose;
}

}  // namespace

namespace detail {

std::optional<StaticTransform> staticTransform(RosBagFile& bag, const std::string& from_frame, const std::string& to_frame) {
  const std::string from = detail::tfFrame(from_frame), to = detail::tfFrame(to_frame);
  if (from.empty() || to.empty()) return std::nullopt;
  std::map<std::pair<std::string, std::string>, Eigen::Isometry3d> transforms;  // (parent, child) → pose of child
  for (const RosBagTopic& topic : bag.topics()) {
    if ((topic.topic != "/tf_static" && topic.topic != "tf_static") || bag.definition(topic).empty()) continue;
    const RosSchema schema = bag.schema(topic);
    bag.forEachMessage(topic.topic, schema, [&](const RosValue& message, double) {
      const RosValue* list = message.field("transforms");
      const auto* items = list != nullptr ? std::get_if<std::vector<RosValue>>(&list->value) : nullptr;
      if (items == nullptr) throw Error("it holds no transforms[]");
      for (const RosValue& item : *items) {
        const std::string* child = textOf(item.field("child_frame_id"));
        const RosValue* transform = item.field("transform");
        if (child == nullptr || transform == nullptr) throw Error("a transform has no child_frame_id or transform");
        transforms[{headerFrame(item), detail::tfFrame(*child)}] = transformOf(*transform);
      }
    });
  }
  // Breadth-first from `from` over the transforms, both ways.
  std::map<std::string, std::vector<Edge>> edges;
  for (const auto& [frames, pose] : transforms) {
    edges[frames.first].push_back({frames.second, pose});
    edges[frames.second].push_back({frames.first, pose.inverse()});
  }
  std::map<std::string, std::pair<std::string, Eigen::Isometry3d>> reached;  // frame → (previous, pose in `from`)
  reached[from] = {"", Eigen::Isometry3d::Identity()};
  std::queue<std::string> next;
  next.push(from);
  while (!next.empty() && reached.find(to) == reached.end()) {
    const std::string frame = next.front();
    next.pop();
    for (const Edge& edge : edges[frame]) {
      if (reached.count(edge.to) != 0) continue;
      reached[edge.to] = {frame, reached[frame].second * edge.transform};
      next.push(edge.to);
    }
  }
  const auto found = reached.find(to);
  if (found == reached.end()) return std::nullopt;
  StaticTransform result;
  result.pose = found->second.second;
  for (std::string frame = to; !frame.empty(); frame = reached[frame].first) {
    result.chain = result.chain.empty() ? frame : frame + " -> " + result.chain;
  }
  return result;
}

}  // namespace detail

Eigen::Isometry3d rosMountingToBody(const Eigen::Isometry3d& sonar_in_body, const std::string& body_frame,
                                    const std::string& sonar_frame) {
  Eigen::Isometry3d to_frd = Eigen::Isometry3d::Identity();
  if (!namesFrd(detail::tfFrame(body_frame))) to_frd.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();  // FLU → FRD
  Eigen::Isometry3d sonar_from_frd = Eigen::Isometry3d::Identity();  // our sonar frame (FRD) in the tf frame
  if (!namesFrd(detail::tfFrame(sonar_frame))) sonar_from_frd.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  return to_frd * sonar_in_body * sonar_from_frd;
}

std::optional<RosBagMounting> readRosBagMounting(const std::string& path, const std::string& sonar_frame,
                                                 const std::string& body_frame) {
  return detail::withBagErrors(path, [&]() -> std::optional<RosBagMounting> {
    detail::RosBagFile bag(path);
    const std::optional<detail::StaticTransform> found = detail::staticTransform(bag, body_frame, sonar_frame);
    if (!found) return std::nullopt;
    RosBagMounting mounting;
    mounting.sonar_to_body = rosMountingToBody(found->pose, body_frame, sonar_frame);
    mounting.chain = found->chain;
    return mounting;
  });
}

}  // namespace sonarmap
