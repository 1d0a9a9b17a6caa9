/// @file missions.cpp
/// The named missions in the built-in scenes (see missions.hpp for their geometry).

#include "sonarmap/sim/missions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {
namespace {

constexpr double kEast_rad = 0.5 * std::numbers::pi;
constexpr double kTurnRate_radps = 0.5;
constexpr double kTiltDown_deg = 25.0;  ///< the tilted loop's sonar, below the vehicle's horizontal plane

void requirePositive(const char* field, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw ValueError(std::string("mission: ") + field + " must be a finite number > 0, got " + std::to_string(value));
  }
}

/// Sum of the distances between consecutive waypoints, metres.
double pathLength_m(const std::vector<NavSample>& waypoints) {
  double length_m = 0.0;
  for (std::size_t k = 1; k < waypoints.size(); ++k) {
    length_m += (waypoints[k].position_ned_m - waypoints[k - 1].position_ned_m).norm();
  }
  return length_m;
}

/// A rectangle of `length` (along `heading_rad`) × `width` centred at (north, east), laps times.
std::vector<NavSample> rectangle(double north_m, double east_m, double heading_rad, double length_m, double width_m,
                                 bool clockwise, double speed_mps, std::size_t laps) {
  LoopPattern loop;
  loop.shape = LoopShape::kRectangle;
  loop.center_ne_m = Eigen::Vector2d(north_m, east_m);
  loop.heading_rad = heading_rad;
  loop.length_m = length_m;
  loop.width_m = width_m;
  loop.clockwise = clockwise;
  loop.depths_m.assign(laps, 0.0);  // a lap at the same depth: no vertical transit between laps
  loop.speed_mps = speed_mps;
  loop.turn_rate_radps = kTurnRate_radps;
  return loopWaypoints(loop);
}

/// Legs along east, the first at north `first_north_m` from east_from_m, spaced 1 s to the south.
std::vector<NavSample> eastwardLegs(std::size_t legs, double first_north_m, double east_from_m, double leg_length_m,
                                    double spacing_m, double speed_mps, std::size_t laps) {
  LawnmowerPattern pattern;
  const double legs_across_m = static_cast<double>(legs - 1) * spacing_m;
  pattern.center_ne_m = Eigen::Vector2d(first_north_m - 0.5 * legs_across_m, east_from_m + 0.5 * leg_length_m);
  pattern.heading_rad = kEast_rad;
  pattern.legs = legs;
  pattern.leg_length_m = leg_length_m;
  pattern.leg_spacing_m = spacing_m;  // to starboard of east: south
  pattern.depths_m.assign(laps, 0.0);  // each lap flies the path back (lawnmowerWaypoints)
  pattern.speed_mps = speed_mps;
  pattern.turn_rate_radps = kTurnRate_radps;
  return lawnmowerWaypoints(pattern);
}

/// The missions over quay3d (3D), whose depths and mountings differ from the planar ones'.
bool isMission3d(const std::string& name) { return name == "lawnmower-3d" || name == "tilted-loop"; }

/// "unknown mission 'x', expected one of: ...".
ValueError unknownMission(const std::string& name) {
  std::string known;
  for (const std::string& candidate : missionNames()) known += (known.empty() ? "" : ", ") + candidate;
  return ValueError("unknown mission '" + name + "', expected one of: " + known);
}

}  // namespace

std::vector<std::string> missionNames() {
  return {"harbour-loop", "harbour-lawnmower", "harbour-featureless", "hull-loop", "lawnmower-3d", "tilted-loop"};
}

double defaultMissionSpeed_mps(const std::string& name, double range_m) {
  requirePositive("range_m", range_m);
  const std::vector<std::string> names = missionNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) throw unknownMission(name);
  if (isMission3d(name)) return 0.2 * (range_m / kBuiltinSceneReach_m);
  return std::min(range_m / 20.0, 0.5);
}

MissionPlan missionPlan(const std::string& name, double range_m, double speed_mps, std::size_t laps) {
  requirePositive("range_m", range_m);
  requirePositive("speed_mps", speed_mps);
  if (laps == 0) throw ValueError("mission: laps must be at least 1");
  const double s = range_m / kBuiltinSceneReach_m;
  MissionPlan plan;
  plan.name = name;
  if (name == "harbour-loop") {
    plan.scene = "harbour";
    plan.waypoints = rectangle(-0.5 * s, 0.0, kEast_rad, 16.0 * s, 1.0 * s, true, speed_mps, laps);
  } else if (name == "harbour-lawnmower") {
    plan.scene = "harbour";
    plan.waypoints = eastwardLegs(3, 0.0, -8.0 * s, 16.0 * s, 0.5 * s, speed_mps, laps);
  } else if (name == "harbour-featureless") {
    plan.scene = "harbour";
    plan.waypoints = eastwardLegs(1, 0.0, 0.0, 40.0 * s, 1.0 * s, speed_mps, laps);
  } else if (name == "hull-loop") {
    plan.scene = "hull";
    plan.waypoints = rectangle(0.0, -3.25 * s, 0.0, 9.0 * s, 6.5 * s, false, speed_mps, laps);
  } else if (name == "lawnmower-3d") {
    plan.scene = "quay3d";
    LawnmowerPattern pattern;
    pattern.legs = 3;
    pattern.leg_length_m = 4.0 * s;
    pattern.leg_spacing_m = 1.5 * s;
    pattern.depths_m.clear();
    for (std::size_t lap = 0; lap < laps; ++lap) pattern.depths_m.insert(pattern.depths_m.end(), {3.0 * s, 3.5 * s});
    pattern.speed_mps = speed_mps;
    pattern.turn_rate_radps = kTurnRate_radps;
    plan.waypoints = lawnmowerWaypoints(pattern);
  } else if (name == "tilted-loop") {
    plan.scene = "quay3d";
    LoopPattern pattern;
    pattern.length_m = 4.0 * s;
    pattern.width_m = 3.0 * s;
    pattern.depths_m.assign(laps, 3.0 * s);
    pattern.speed_mps = speed_mps;
    pattern.turn_rate_radps = kTurnRate_radps;
    plan.waypoints = loopWaypoints(pattern);
    plan.mounting = {0.0, 0.0, 0.0, 0.0, -kTiltDown_deg, 0.0};  // pitched down: negative pitch (FRD)
  } else {
    throw unknownMission(name);
  }
  plan.length_m = pathLength_m(plan.waypoints);
  plan.duration_s = plan.waypoints.back().time_s;
  return plan;
}

}  // namespace sonarmap
