/// @file ros_inertial_navigation.cpp
/// Dead reckoning from a bag's IMU, pressure sensor and DVL (see ros_inertial_navigation.hpp).

#include "ros_inertial_navigation.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include "ros_frames.hpp"

namespace sonarmap::detail {
namespace {

/// Standard gravity, m/s² (the CGPM's conventional value).
constexpr double kGravity_m_s2 = 9.80665;

/// The first of `paths` that holds the number fields `names`, or empty; empty too for a message
/// without a std_msgs/Header.
std::vector<std::string> firstPath(const RosSchema& schema, std::initializer_list<std::vector<std::string>> paths,
                                   std::initializer_list<const char*> names) {
  if (schema.typeAt({"header"}) != "std_msgs/Header") return {};
  for (const std::vector<std::string>& path : paths) {
    if (schema.holdsNumbers(path, names)) return path;
  }
  return {};
}

Eigen::Vector3d vectorOf(const RosValue& value, const std::string& what) {
  return {finiteNumber(value.field("x"), what + " x"), finiteNumber(value.field("y"), what + " y"),
          finiteNumber(value.field("z"), what + " z")};
}

/// A topic chosen for a role: the first, in the bag's order, whose message holds it.
struct Role {
  const RosBagTopic* topic = nullptr;
  std::vector<std::string> path;
  std::optional<RosSchema> schema;
};

template <class Matches>
Role findRole(RosBagFile& bag, Matches&& matches) {
  for (const RosBagTopic& topic : bag.topics()) {
    const std::string& definition = bag.definition(topic);
    if (definition.empty()) continue;
    RosSchema schema = bag.schema(topic);
    std::vector<std::string> path = matches(schema);
    if (!path.empty()) return Role{&topic, std::move(path), std::move(schema)};
  }
  return {};
}

template <class T>
struct Timed {
  double time_s;
  T value;
};

/// Keeps the samples in strictly increasing time (a recorder may write two at one stamp).
template <class T>
void keepIncreasing(std::vector<Timed<T>>& samples) {
  std::stable_sort(samples.begin(), samples.end(), [](const Timed<T>& a, const Timed<T>& b) { return a.time_s < b.time_s; });
  samples.erase(std::unique(samples.begin(), samples.end(), [](const Timed<T>& a, const Timed<T>& b) { return a.time_s == b.time_s; }),
                samples.end());
}

/// `samples` (sorted) linearly interpolated at `time_s`, held at the ends.
template <class T>
T interpolated(const std::vector<Timed<T>>& samples, double time_s) {
  const auto after = std::lower_bound(samples.begin(), samples.end(), time_s,
                                      [](const Timed<T>& s, double t) { return s.time_s < t; });
  if (after == samples.begin()) return samples.front().value;
  if (after == samples.end()) return samples.back().value;
  const Timed<T>& before = *(after - 1);
  const double w = (time_s - before.time_s) / (after->time_s - before.time_s);
  return before.value + w * (after->value - before.value);
}

}  // namespace

std::optional<RosBagNavigation> inertialNavigation(RosBagFile& bag, const RosBagNavOptions& options) {
  const Role attitude = findRole(bag, [](const RosSchema& s) {
    return firstPath(s, {{"orientation"}}, {"x", "y", "z", "w"});
  });
  if (attitude.topic == nullptr) return std::nullopt;
  const Role pressure = findRole(bag, [](const RosSchema& s) {
    const bool pressure = s.typeAt({"header"}) == "std_msgs/Header" && s.holdsNumbers({}, {"fluid_pressure"});
    return pressure ? std::vector<std::string>{"fluid_pressure"} : std::vector<std::string>{};
  });
  const Role velocity = findRole(bag, [](const RosSchema& s) {
    return firstPath(s, {{"twist", "linear"}, {"twist", "twist", "linear"}, {"velocity"}}, {"x", "y", "z"});
  });

  RosBagNavigation nav;
  nav.topic = attitude.topic->topic;
  nav.type = attitude.topic->type;
  std::vector<Timed<NavSample>> attitudes;
  bool any_ned = false, any_enu = false;
  std::string attitude_frame;  // the IMU's frame: its orientation is that frame's
  RosSkipped skipped = bag.forEachMessage(attitude.topic->topic, *attitude.schema, [&](const RosValue& message, double record_s) {
    if (const RosValue* covariance = message.field("orientation_covariance")) {
      const auto* values = std::get_if<std::vector<RosValue>>(&covariance->value);
      if (values != nullptr && !values->empty() && finiteNumber(&values->front(), "orientation covariance") == -1.0) {
        throw Error("its orientation_covariance[0] is -1: it has no orientation");
      }
    }
    const RosValue& q = valueAt(message, attitude.path);
    const bool ned = headerNamesNed(message);
    (ned ? any_ned : any_enu) = true;
    if (attitude_frame.empty()) attitude_frame = headerFrame(message);
    const double time_s = headerTime(message, record_s);
    attitudes.push_back({time_s, rosPoseToNed(time_s, Eigen::Vector3d::Zero(),
                                              Eigen::Quaterniond(finiteNumber(q.field("w"), "orientation w"), finiteNumber(q.field("x"), "orientation x"),
                                                                 finiteNumber(q.field("y"), "orientation y"), finiteNumber(q.field("z"), "orientation z")),
                                              ned)});
  });
  keepIncreasing(attitudes);
  if (attitudes.empty()) bag.fail("no message of " + nav.topic + " gives an attitude" + (skipped.reasons.empty() ? "" : ": " + skipped.reasons.front()));
  auto attitudeAt = [&](double time_s) -> const NavSample& {
    const auto after = std::lower_bound(attitudes.begin(), attitudes.end(), time_s,
                                        [](const Timed<NavSample>& s, double t) { return s.time_s < t; });
    if (after == attitudes.begin()) return after->value;
    if (after == attitudes.end() || time_s - (after - 1)->time_s < after->time_s - time_s) return (after - 1)->value;
    return after->value;
  };

  std::vector<Timed<double>> depths;
  if (pressure.topic != nullptr) {
    const double pascals_per_metre = options.water_density_kg_m3 * kGravity_m_s2;
    const RosSkipped more = bag.forEachMessage(pressure.topic->topic, *pressure.schema, [&](const RosValue& message, double record_s) {
      depths.push_back({headerTime(message, record_s),
                        (finiteNumber(message.field("fluid_pressure"), "fluid pressure") - options.surface_pressure_pa) / pascals_per_metre});
    });
    skipped.count += more.count;
    skipped.reasons.insert(skipped.reasons.end(), more.reasons.begin(), more.reasons.end());
    keepIncreasing(depths);
  }

  // Positions integrated from the velocities: each held until the next (a DVL's ping to ping).
  std::vector<Timed<Eigen::Vector3d>> positions;
  std::optional<std::string> dvl_mounting;
  if (velocity.topic != nullptr) {
    std::vector<Timed<Eigen::Vector3d>> velocities;
    // A DVL mounted turned on the vehicle (a Water Linked A50 at 45 degrees, say): its velocity is
    // turned into the IMU's frame by the rotation /tf_static records between the two (its lever
    // arm, the rotation's own contribution, is not added).
    std::vector<bool> flu;  // per velocity: FLU (to be turned into the IMU's frame, then FRD), else FRD
    std::string dvl_frame;
    const RosSkipped more = bag.forEachMessage(velocity.topic->topic, *velocity.schema, [&](const RosValue& message, double record_s) {
      velocities.push_back({headerTime(message, record_s), vectorOf(valueAt(message, velocity.path), "velocity")});
      flu.push_back(!headerNamesNed(message));
      if (dvl_frame.empty() && flu.back()) dvl_frame = headerFrame(message);
    });
    const std::optional<StaticTransform> dvl_in_imu =
        dvl_frame != attitude_frame ? staticTransform(bag, attitude_frame, dvl_frame) : std::nullopt;
    for (std::size_t k = 0; k < velocities.size(); ++k) {
      if (!flu[k]) continue;
      const Eigen::Vector3d v = dvl_in_imu ? Eigen::Vector3d(dvl_in_imu->pose.linear() * velocities[k].value) : velocities[k].value;
      velocities[k].value = Eigen::Vector3d(v.x(), -v.y(), -v.z());  // FLU → FRD
    }
    skipped.count += more.count;
    skipped.reasons.insert(skipped.reasons.end(), more.reasons.begin(), more.reasons.end());
    keepIncreasing(velocities);
    if (dvl_in_imu) dvl_mounting = dvl_in_imu->chain;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < velocities.size(); ++k) {
      positions.push_back({velocities[k].time_s, position});
      if (k + 1 == velocities.size()) break;
      const double dt_s = velocities[k + 1].time_s - velocities[k].time_s;
      position += bodyToNed(attitudeAt(velocities[k].time_s)).linear() * velocities[k].value * dt_s;
    }
  }

  for (const Timed<NavSample>& sample : attitudes) {
    NavSample fix = sample.value;
    fix.time_s = sample.time_s;
    if (!positions.empty()) fix.position_ned_m = interpolated(positions, sample.time_s);
    if (!depths.empty()) fix.position_ned_m.z() = interpolated(depths, sample.time_s);
    nav.track.push_back(fix);
  }
  nav.skipped = skipped.count;
  nav.skip_reasons = std::move(skipped.reasons);
  std::string frame = any_ned && any_enu ? "NED and ENU (REP 103)" : any_ned ? "NED" : "ENU (REP 103) turned into NED";
  frame += std::string(", dead reckoning: attitude of ") + nav.topic;
  frame += velocity.topic != nullptr ? ", velocity of " + velocity.topic->topic : std::string(", no velocity (north, east 0)");
  if (dvl_mounting) frame += " turned by /tf_static (" + *dvl_mounting + ")";
  frame += pressure.topic != nullptr ? ", depth of " + pressure.topic->topic : std::string(", no pressure");
  nav.frame = frame;
  return nav;
}

}  // namespace sonarmap::detail
