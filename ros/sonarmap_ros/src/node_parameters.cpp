/// @file node_parameters.cpp
/// The node's ROS parameters (node_parameters.hpp).

#include "node_parameters.hpp"
#include "pose_input.hpp"

#include <sstream>
#include <stdexcept>

namespace sonarmap_ros {
namespace {

/// A parameter as the text the mapping option reads ("0.05", "auto", "true", "3"); false when unset.
bool paramText(const ros::NodeHandle& node, const std::string& name, std::string& text) {
  XmlRpc::XmlRpcValue value;
  if (!node.getParam(name, value)) return false;
  std::ostringstream out;
  out.precision(17);
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeString: text = static_cast<std::string>(value); return true;
    case XmlRpc::XmlRpcValue::TypeBoolean: text = static_cast<bool>(value) ? "true" : "false"; return true;
    case XmlRpc::XmlRpcValue::TypeInt: text = std::to_string(static_cast<int>(value)); return true;
    case XmlRpc::XmlRpcValue::TypeDouble: out << static_cast<double>(value); text = out.str(); return true;
    default: throw std::runtime_error("~" + name + ": a number, a word or true/false is needed");
  }
}

bool numberParam(const ros::NodeHandle& node, const std::string& name, double& value) {
  std::string text;
  if (!paramText(node, name, text)) return false;
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    if (used == text.size()) return true;
  } catch (const std::exception&) {
  }
  throw std::runtime_error("~" + name + ": a number is needed, got '" + text + "'");
}

}  // namespace

NodeParameters readNodeParameters(const ros::NodeHandle& node) {
  NodeParameters p;
  CoreParameters& core = p.core;
  node.param<std::string>("sonar_topic", core.sonar_topic, "sonar");
  node.param<std::string>("bearing_unit", core.bearing_unit, core.bearing_unit);
  node.param<std::string>("bearing_direction", core.bearing_direction, core.bearing_direction);
  std::string pose = "tf";
  node.param<std::string>("pose_source", pose, pose);
  if (pose == "none") {
    p.pose_source = PoseSource::kNone;
  } else if (pose == "tf") {
    p.pose_source = PoseSource::kTf;
  } else if (pose == "odometry") {
    p.pose_source = PoseSource::kOdometry;
  } else {
    throw std::runtime_error("~pose_source: unknown source '" + pose + "' (none, tf, odometry)");
  }
  core.navigation = p.pose_source != PoseSource::kNone;
  node.param<std::string>("odom_topic", p.odom_topic, p.odom_topic);
  node.param<std::string>("odom_frame", p.odom_frame, p.odom_frame);
  node.param<std::string>("base_frame", p.base_frame, p.base_frame);
  node.param<bool>("slam", core.slam, core.slam);
  node.param<std::string>("nav_class", core.nav_class, core.nav_class);
  // With slam the map is in the corrected frame, REP 105's map, of which odom is a child (map → odom).
  node.param<std::string>("frame_id", core.frame_id, core.slam ? "map" : p.odom_frame);
  if (core.slam && core.navigation && tfName(core.frame_id) == tfName(p.odom_frame)) {
    throw std::runtime_error("~frame_id: with ~slam the map's frame is the corrected one (map), not ~odom_frame " + p.odom_frame);
  }
  core.base_frame = p.base_frame;
  // every mapping option by its Python keyword (octomap_server's `resolution` among them), then
  // octomap_server's sensor model
  for (const auto& [name, kind] : mappingOptionNames()) {
    std::string text;
    if (paramText(node, name, text)) core.mapping_options.emplace_back(name, text);
  }
  std::string text;
  if (paramText(node, "sensor_model/hit", text)) core.mapping_options.emplace_back("hit_probability", text);
  double number = 0.0;
  if (numberParam(node, "sensor_model/miss", number)) core.prob_miss = number;
  if (numberParam(node, "sensor_model/min", number)) core.clamp_min = number;
  if (numberParam(node, "sensor_model/max", number)) core.clamp_max = number;
  numberParam(node, "occupancy_min_z", core.occupancy_min_z_m);
  numberParam(node, "occupancy_max_z", core.occupancy_max_z_m);
  numberParam(node, "idle_commit_s", p.idle_commit_s);
  numberParam(node, "publish_period_s", p.publish_period_s);
  if (!(p.idle_commit_s > 0.0)) throw std::runtime_error("~idle_commit_s: seconds > 0 are needed");
  if (!(p.publish_period_s >= 0.0)) throw std::runtime_error("~publish_period_s: seconds >= 0 are needed");
  if (numberParam(node, "bearing_decision_beams", number)) {
    if (!(number >= 1.0)) throw std::runtime_error("~bearing_decision_beams: a count >= 1 is needed");
    core.bearing_decision_beams = static_cast<std::size_t>(number);
  }
  node.param<std::string>("save_path", p.save_path, p.save_path);
  return p;
}

}  // namespace sonarmap_ros
