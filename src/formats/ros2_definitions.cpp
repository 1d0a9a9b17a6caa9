/// @file ros2_definitions.cpp
/// Built-in ros2msg definitions of common types (see ros2_definitions.hpp).

#include "ros2_definitions.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

/// Each type's own fields (ROS 2 Humble's .msg files without comments), and the types it uses.
struct Type {
  const char* fields;
  std::vector<const char*> uses;
};

const std::map<std::string, Type>& types() {
  static const std::map<std::string, Type> table = {
      {"builtin_interfaces/Time", {"int32 sec\nuint32 nanosec\n", {}}},
      {"std_msgs/Header", {"builtin_interfaces/Time stamp\nstring frame_id\n", {"builtin_interfaces/Time"}}},
      {"geometry_msgs/Point", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/Vector3", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/Quaternion", {"float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n", {}}},
      {"geometry_msgs/Pose",
       {"geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n", {"geometry_msgs/Point", "geometry_msgs/Quaternion"}}},
      {"geometry_msgs/PoseWithCovariance", {"geometry_msgs/Pose pose\nfloat64[36] covariance\n", {"geometry_msgs/Pose"}}},
      {"geometry_msgs/Twist", {"geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n", {"geometry_msgs/Vector3"}}},
      {"geometry_msgs/TwistWithCovariance", {"geometry_msgs/Twist twist\nfloat64[36] covariance\n", {"geometry_msgs/Twist"}}},
      {"geometry_msgs/PoseStamped", {"std_msgs/Header header\ngeometry_msgs/Pose pose\n", {"std_msgs/Header", "geometry_msgs/Pose"}}},
      {"geometry_msgs/PoseWithCovarianceStamped",
       {"std_msgs/Header header\ngeometry_msgs/PoseWithCovariance pose\n", {"std_msgs/Header", "geometry_msgs/PoseWithCovariance"}}},
      {"geometry_msgs/TwistStamped", {"std_msgs/Header header\ngeometry_msgs/Twist twist\n", {"std_msgs/Header", "geometry_msgs/Twist"}}},
      {"geometry_msgs/TwistWithCovarianceStamped",
       {"std_msgs/Header header\ngeometry_msgs/TwistWithCovariance twist\n", {"std_msgs/Header", "geometry_msgs/TwistWithCovariance"}}},
      {"nav_msgs/Odometry",
       {"std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
        "geometry_msgs/TwistWithCovariance twist\n",
        {"std_msgs/Header", "geometry_msgs/PoseWithCovariance", "geometry_msgs/TwistWithCovariance"}}},
      {"sensor_msgs/Imu",
       {"std_msgs/Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n"
        "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n"
        "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n",
        {"std_msgs/Header", "geometry_msgs/Quaternion", "geometry_msgs/Vector3"}}},
      {"sensor_msgs/FluidPressure", {"std_msgs/Header header\nfloat64 fluid_pressure\nfloat64 variance\n", {"std_msgs/Header"}}},
      {"ping360_sonar_msgs/SonarEcho",
       {"std_msgs/Header header\nfloat32 angle\nuint8 gain\nuint16 number_of_samples\nuint16 transmit_frequency\n"
        "uint16 speed_of_sound\nuint8 range\nuint8[] intensities\n",
        {"std_msgs/Header"}}},
  };
  return table;
}

/// Every type `name` uses, nested ones too, each once, in first-use order.
void collect(const std::string& name, std::vector<std::string>& out) {
  for (const char* used : types().at(name).uses) {
    bool seen = false;
    for (const std::string& known : out) seen = seen || known == used;
    if (seen) continue;
    out.emplace_back(used);
    collect(used, out);
  }
}

}  // namespace

std::string builtinRos2Definition(const std::string& type) {
  std::string name = type;
  if (const auto msg = name.find("/msg/"); msg != std::string::npos) name.erase(msg, 4);
  const auto found = types().find(name);
  if (found == types().end()) return {};
  std::string definition = found->second.fields;
  std::vector<std::string> used;
  collect(name, used);
  for (const std::string& u : used) {
    definition += std::string(80, '=') + "\nMSG: " + u + "\n" + types().at(u).fields;
  }
  return definition;
}

namespace {

/// "pkg/msg/Name" or "pkg/Name" as ("pkg", "Name"); a name without a package keeps `package`.
std::pair<std::string, std::string> splitType(const std::string& type, const std::string& package) {
  const auto first = type.find('/');
  if (first == std::string::npos) return {type == "Header" ? "std_msgs" : package, type};
  return {type.substr(0, first), type.substr(type.rfind('/') + 1)};
}

bool isPrimitive(const std::string& base) {
  static const std::vector<std::string> primitives{"bool",  "byte",  "char",   "float32", "float64", "int8",
                                                   "uint8", "int16", "uint16", "int32",   "uint32",  "int64",
                                                   "uint64", "string", "wstring"};
  return std::find(primitives.begin(), primitives.end(), base) != primitives.end() ||
         base.rfind("builtin_interfaces/", 0) == 0;
}

/// The `.msg` file of pkg/Name under `dir`, or empty.
std::filesystem::path msgFile(const std::string& dir, const std::string& package, const std::string& name) {
  namespace fs = std::filesystem;
  for (const fs::path& candidate : {fs::path(dir) / package / "msg" / (name + ".msg"), fs::path(dir) / package / (name + ".msg"),
                                    fs::path(dir) / (name + ".msg")}) {
    std::error_code error;
    if (fs::is_regular_file(candidate, error)) return candidate;
  }
  return {};
}

/// The types a .msg text uses (not primitives), as "pkg/Name".
std::vector<std::string> usedTypes(const std::string& text, const std::string& package) {
  std::vector<std::string> used;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string type, name;
    if (!(words >> type >> name) || name.find('=') != std::string::npos) continue;  // blank, or a constant
    std::string base = type.substr(0, type.find('['));
    base = base.substr(0, base.find("<="));
    if (isPrimitive(base)) continue;
    const auto [pkg, message] = splitType(base, package);
    used.push_back(pkg + "/" + message);
  }
  return used;
}

}  // namespace

std::string msgPathDefinition(const std::string& type, const std::string& msg_path) {
  if (msg_path.empty()) return {};
  const auto [package, name] = splitType(type, "");
  const std::filesystem::path root = msgFile(msg_path, package, name);
  if (root.empty()) return {};
  const auto textOf = [](const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  };
  std::string definition = textOf(root);
  std::vector<std::string> pending = usedTypes(definition, package), done{package + "/" + name};
  while (!pending.empty()) {
    const std::string next = pending.front();
    pending.erase(pending.begin());
    if (std::find(done.begin(), done.end(), next) != done.end()) continue;
    done.push_back(next);
    const auto [pkg, message] = splitType(next, "");
    std::string fields;
    if (const std::filesystem::path file = msgFile(msg_path, pkg, message); !file.empty()) {
      fields = textOf(file);
    } else if (const auto builtin = types().find(next); builtin != types().end()) {
      fields = builtin->second.fields;
    } else {
      throw Error("the message " + type + " uses " + next + ", found neither under " + msg_path + " (" + pkg + "/msg/" +
                  message + ".msg) nor among the built-in types");
    }
    const std::vector<std::string> more = usedTypes(fields, pkg);
    pending.insert(pending.end(), more.begin(), more.end());
    definition += "\n" + std::string(80, '=') + "\nMSG: " + next + "\n" + fields;
  }
  return definition;
}

}  // namespace sonarmap::detail
