/// @file node_parameters.cpp
/// The node's ROS parameters (node_parameters.hpp).

#include "node_parameters.hpp"
#include "pose_input.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <ros/console.h>

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

/// A number parameter that `inside` accepts, `accepts` saying which ("a probability in (0, 0.5)").
bool numberIn(const ros::NodeHandle& node, const std::string& name, double& value, bool (*inside)(double),
              const char* accepts) {
  if (!numberParam(node, name, value)) return false;
  if (inside(value)) return true;
  std::ostringstream out;
  out << value;
  throw std::runtime_error("~" + name + ": " + accepts + " is needed, got " + out.str());
}

bool boolParam(const ros::NodeHandle& node, const std::string& name, bool& value) {
  std::string text;
  if (!paramText(node, name, text)) return false;
  if (text != "true" && text != "false") throw std::runtime_error("~" + name + ": true or false is needed, got '" + text + "'");
  value = text == "true";
  return true;
}

void colorParams(const ros::NodeHandle& node, const std::string& prefix, MarkerColor& color) {
  const auto unit = [](double v) { return v >= 0.0 && v <= 1.0; };
  numberIn(node, prefix + "/r", color.r, unit, "a number in [0, 1]");
  numberIn(node, prefix + "/g", color.g, unit, "a number in [0, 1]");
  numberIn(node, prefix + "/b", color.b, unit, "a number in [0, 1]");
  numberIn(node, prefix + "/a", color.a, unit, "a number in [0, 1]");
}

// Why octomap_server's parameters of its input do not apply: it maps a point cloud, a point per
// return; the node maps a sonar's beams, each a cone whose echoes are detected along it.
constexpr char kCloudFilter[] =
    "it crops octomap_server's input point cloud, and a sonar beam is not a point cloud: its echo is detected "
    "along the beam (~min_range, ~max_range) and its whole cone is mapped (~occupancy_min_z/max_z bound the markers)";
constexpr char kGroundFilter[] =
    "it removes the ground plane found by RANSAC in octomap_server's point cloud, and a sonar beam is not a point "
    "cloud (a seabed is mapped where the beam meets it)";
constexpr char kProjection[] =
    "it sizes octomap_server's 2D projection; projected_map here is the map's slice at the vehicle's height, as "
    "large as the map, made whole at each publication";
constexpr char kReconfigure[] =
    "a name of octomap_server's dynamic_reconfigure, which the node does not have; of octomap_server's own names "
    "the node reads sensor_model/miss, min, max and max_range (sensor_model/hit, min_range and ground_filter/* do "
    "not apply)";

}  // namespace

const std::vector<OctomapServerParameter>& octomapServerParameters() {
  // In OctomapServer.cpp's order, then octomap_server_node's map_file and the dynamic_reconfigure names
  // its constructor does not read.
  static const std::vector<OctomapServerParameter> table{
      {"frame_id", nullptr},
      {"base_frame_id", nullptr},  // ~base_frame: the robot's base frame on TF
      {"height_map", "it colours the occupied markers by height; here they have one colour, ~color/*", "false"},
      {"colored_map", "it colours the map by the point cloud's RGB, and a sonar has no colour", "false"},
      {"color_factor", "the scale of height_map's colours; the markers have one colour, ~color/*"},
      {"pointcloud_min_x", kCloudFilter},
      {"pointcloud_max_x", kCloudFilter},
      {"pointcloud_min_y", kCloudFilter},
      {"pointcloud_max_y", kCloudFilter},
      {"pointcloud_min_z", kCloudFilter},
      {"pointcloud_max_z", kCloudFilter},
      {"occupancy_min_z", nullptr},
      {"occupancy_max_z", nullptr},
      {"min_x_size", kProjection},
      {"min_y_size", kProjection},
      {"filter_speckles",
       "it hides occupied voxels without an occupied neighbour from the markers; here they show every occupied leaf "
       "of octomap_binary (a sonar's false echoes are ruled by ~false_alarm and ~detector)",
       "false"},
      {"filter_ground", kGroundFilter, "false"},
      {"ground_filter/distance", kGroundFilter},
      {"ground_filter/angle", kGroundFilter},
      {"ground_filter/plane_distance", kGroundFilter},
      {"sensor_model/max_range", nullptr},  // ~max_range: a beam clears up to it, an echo beyond is dropped
      {"sensor_model/min_range",
       "it drops a point nearer than it with its ray; a sonar beam's nearest echo is ~min_range (map --min-range: "
       "the near field is blanked and the beam looks beyond it)"},
      {"resolution", nullptr},
      {"sensor_model/hit",
       "octomap_server's is the probability of a point of a laser's or a depth camera's cloud (0.7); a sonar's echo "
       "has passed the detector's ~false_alarm threshold and its probability is ~hit_probability (map "
       "--hit-probability, 0.9), at which one echo outweighs the free water that earlier sweeps saw there"},
      {"sensor_model/miss", nullptr},
      {"sensor_model/min", nullptr},
      {"sensor_model/max", nullptr},
      {"compress_map", "the map is always pruned, as `sonarmap map`'s (losslessly)", "true"},
      {"incremental_2D_projection", kProjection, "false"},
      {"color/r", nullptr},
      {"color/g", nullptr},
      {"color/b", nullptr},
      {"color/a", nullptr},
      {"color_free/r", nullptr},
      {"color_free/g", nullptr},
      {"color_free/b", nullptr},
      {"color_free/a", nullptr},
      {"publish_free_space", nullptr},
      {"latch", nullptr},
      {"map_file", "the node starts from an empty map: it maps the sonar and loads no map"},
      {"max_depth",
       "the depth down to which octomap_server's dynamic_reconfigure lets the markers show the tree; they show every "
       "leaf",
       "16"},
      {"sensor_model_max_range", kReconfigure},
      {"sensor_model_min_range", kReconfigure},
      {"sensor_model_hit", kReconfigure},
      {"sensor_model_miss", kReconfigure},
      {"sensor_model_min", kReconfigure},
      {"sensor_model_max", kReconfigure},
      {"ground_filter_distance", kReconfigure},
      {"ground_filter_angle", kReconfigure},
      {"ground_filter_plane_distance", kReconfigure},
  };
  return table;
}

NodeParameters readNodeParameters(const ros::NodeHandle& node) {
  NodeParameters p;
  CoreParameters& core = p.core;
  // octomap_server's parameters that do not apply, each named with why (the others are read below)
  for (const OctomapServerParameter& parameter : octomapServerParameters()) {
    if (parameter.ignored == nullptr || !node.hasParam(parameter.name)) continue;
    std::string text;
    try {
      paramText(node, parameter.name, text);
    } catch (const std::runtime_error&) {
      // a list or a dictionary: not a switch's value
    }
    if (parameter.agrees != nullptr && text == parameter.agrees) continue;
    ROS_WARN("sonarmap: ~%s: octomap_server's parameter, not applied: %s", parameter.name, parameter.ignored);
  }
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
  std::string base_frame_id;  // octomap_server's name of the robot's base frame on TF
  if (node.getParam("base_frame_id", base_frame_id)) {
    if (node.hasParam("base_frame") && base_frame_id != p.base_frame) {
      throw std::runtime_error("~base_frame_id: octomap_server's name of ~base_frame, which says " + p.base_frame +
                               ": give one of them");
    }
    p.base_frame = base_frame_id;
  }
  node.param<bool>("slam", core.slam, core.slam);
  node.param<std::string>("nav_class", core.nav_class, core.nav_class);
  // With slam the map is in the corrected frame, REP 105's map, of which odom is a child (map → odom).
  node.param<std::string>("frame_id", core.frame_id, core.slam ? "map" : p.odom_frame);
  if (core.slam && core.navigation && tfName(core.frame_id) == tfName(p.odom_frame)) {
    throw std::runtime_error("~frame_id: with ~slam the map's frame is the corrected one (map), not ~odom_frame " + p.odom_frame);
  }
  core.base_frame = p.base_frame;
  // every mapping option by its Python keyword (octomap_server's `resolution` among them), then
  // octomap_server's sensor model where it means the same: the miss (a cell the beam crossed before
  // its echo, as a ray before its point), the clamping bounds and max_range (a beam clears up to it,
  // an echo beyond is dropped; <= 0 is octomap_server's no limit, `map`'s 300 m)
  for (const auto& [name, kind] : mappingOptionNames()) {
    std::string text;
    if (paramText(node, name, text)) core.mapping_options.emplace_back(name, text);
  }
  double number = 0.0;
  if (numberIn(node, "sensor_model/max_range", number, [](double v) { return std::isfinite(v); }, "metres")) {
    if (node.hasParam("max_range")) {
      throw std::runtime_error("~sensor_model/max_range: octomap_server's name of ~max_range, which is given too: give one of them");
    }
    std::string text;
    paramText(node, "sensor_model/max_range", text);
    if (number > 0.0) core.mapping_options.emplace_back("max_range", text);
  }
  if (numberIn(node, "sensor_model/miss", number, [](double v) { return v > 0.0 && v < 0.5; }, "a probability in (0, 0.5)")) {
    core.prob_miss = number;
  }
  if (numberIn(node, "sensor_model/min", number, [](double v) { return v > 0.0 && v <= 0.5; }, "a probability in (0, 0.5]")) {
    core.clamp_min = number;
  }
  if (numberIn(node, "sensor_model/max", number, [](double v) { return v >= 0.5 && v < 1.0; }, "a probability in [0.5, 1)")) {
    core.clamp_max = number;
  }
  numberParam(node, "occupancy_min_z", core.occupancy_min_z_m);
  numberParam(node, "occupancy_max_z", core.occupancy_max_z_m);
  boolParam(node, "latch", p.latch);
  boolParam(node, "publish_free_space", p.publish_free_space);
  core.free_cells = p.publish_free_space;
  colorParams(node, "color", p.color);
  colorParams(node, "color_free", p.color_free);
  numberParam(node, "idle_commit_s", p.idle_commit_s);
  numberParam(node, "publish_period_s", p.publish_period_s);
  if (!(p.idle_commit_s > 0.0)) throw std::runtime_error("~idle_commit_s: seconds > 0 are needed");
  if (!(p.publish_period_s >= 0.0)) throw std::runtime_error("~publish_period_s: seconds >= 0 are needed");
  numberParam(node, "jump_back_s", core.jump_back_s);
  numberParam(node, "mounting_wait_s", core.mounting_wait_s);
  if (!(core.jump_back_s > 0.0)) throw std::runtime_error("~jump_back_s: seconds > 0 are needed");
  if (!(core.mounting_wait_s >= 0.0)) throw std::runtime_error("~mounting_wait_s: seconds >= 0 are needed");
  if (numberParam(node, "bearing_decision_beams", number)) {
    if (!(number >= 1.0)) throw std::runtime_error("~bearing_decision_beams: a count >= 1 is needed");
    core.bearing_decision_beams = static_cast<std::size_t>(number);
  }
  node.param<std::string>("save_path", p.save_path, p.save_path);
  return p;
}

}  // namespace sonarmap_ros
