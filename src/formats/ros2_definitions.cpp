/// @file ros2_definitions.cpp
/// Built-in ros2msg definitions of common types (see ros2_definitions.hpp).

#include "ros2_definitions.hpp"

#include <map>
#include <vector>

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

}  // namespace sonarmap::detail
