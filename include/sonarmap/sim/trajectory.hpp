#pragma once
/// @file trajectory.hpp
/// The simulated vehicle's motion: its navigation fix (pose in NED, navigation.hpp) as a function
/// of time. The simulator asks it for the pose at every beam's time and samples it into the run's
/// NavTrack.

#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// Pose of the vehicle at `time_s` (seconds, the log's clock): position in NED (metres) and
/// roll/pitch/yaw (radians, navigation.hpp). The returned time_s is ignored (the caller sets it).
using Trajectory = std::function<NavSample(double time_s)>;

/// A vehicle that does not move: `pose` at every time (default: NED origin, zero attitude, where
/// an upright aligned sonar has the identity pose in the map).
Trajectory staticTrajectory(const NavSample& pose = {});

/// Straight, level-attitude motion: position start.position_ned_m + velocity_ned_mps · (t − start.time_s),
/// roll and pitch of `start`, yaw start.yaw_rad + yaw_rate_radps · (t − start.time_s).
/// @param velocity_ned_mps  velocity in NED, metres per second.
/// @param yaw_rate_radps    turn rate, radians per second (positive turns clockwise seen from above).
/// @throws ValueError when a value is not finite.
Trajectory constantVelocityTrajectory(const NavSample& start, const Eigen::Vector3d& velocity_ned_mps,
                                      double yaw_rate_radps = 0.0);

/// A vehicle that follows `waypoints` (fixes in NED, times in seconds, strictly increasing):
/// piecewise-linear interpolation in time between the two waypoints around t. With
/// f = (t − t_i) / (t_{i+1} − t_i): position and roll, pitch linear in f; yaw
/// yaw_i + f · Δ, where Δ is yaw_{i+1} − yaw_i wrapped into [−π, π) (the shortest arc: 170° to
/// −170° passes through 180°; an exact half turn goes counter-clockwise seen from above, Δ = −π).
/// The interpolated yaw is not wrapped itself. Every waypoint is reproduced exactly at its own
/// time. Before the first waypoint's time (and for a NaN time) the pose is the first waypoint's,
/// after the last one's the last waypoint's. The returned sample's time_s is the time asked.
/// Cost: O(log waypoints) per call.
/// @throws ValueError when `waypoints` is empty, holds a non-finite value, or its times are not
///         strictly increasing (naming the waypoint's index).
Trajectory waypointTrajectory(std::vector<NavSample> waypoints);

/// A lawnmower (boustrophedon) survey in NED, repeated at several depths; see lawnmowerWaypoints().
struct LawnmowerPattern {
  /// Centre of the surveyed rectangle, NED north and east, metres.
  Eigen::Vector2d center_ne_m = Eigen::Vector2d::Zero();
  /// Direction of the first leg: heading clockwise from north seen from above, radians.
  double heading_rad = 0.0;
  std::size_t legs = 4;         ///< parallel legs per depth, ≥ 1
  double leg_length_m = 6.0;    ///< length of each leg, metres, > 0
  /// Distance between adjacent legs, metres, ≠ 0: positive steps to starboard of the first leg's
  /// direction (to the east for heading 0), negative to port.
  double leg_spacing_m = 1.0;
  /// Depths of the vehicle origin (NED z, metres, positive down), one full pattern at each, in order.
  std::vector<double> depths_m{0.0, 1.0};
  double speed_mps = 0.25;       ///< along every straight path, vertical transits included, > 0
  double turn_rate_radps = 0.5;  ///< of the turns in place at the ends of the legs, rad/s, > 0
};

/// Waypoints (times from 0 s) of a lawnmower at each of `pattern.depths_m`, for
/// waypointTrajectory(). At the first depth the legs run from the first one, which starts at
/// center − leg_length/2 · forward − (legs − 1) · leg_spacing/2 · starboard (forward and
/// starboard: the horizontal unit vectors along heading_rad and 90° clockwise from it) and runs
/// along forward; leg k (0-based) is the first shifted by k · leg_spacing to starboard and runs
/// along forward for even k, backward for odd k; consecutive legs are joined by a straight
/// crossing of length |leg_spacing| at the end where the first stops. At the next depth the vehicle
/// descends (or rises) vertically where it stopped and flies the same path backwards, and so on
/// alternately. The vehicle moves at `speed_mps`, its yaw along the direction of horizontal travel
/// (yaw = atan2(east, north)); at every change of direction it stops and turns in place by the
/// shorter way at turn_rate_radps (two waypoints at the same place: arrival and departure; none
/// when the heading does not change); during a vertical transit it keeps its yaw. Roll and pitch 0.
/// @throws ValueError naming the field for a non-finite value, no legs, a leg length, speed or
///         turn rate not > 0, a zero spacing or an empty depth list.
std::vector<NavSample> lawnmowerWaypoints(const LawnmowerPattern& pattern);

/// Shape of a closed loop.
enum class LoopShape {
  kRectangle,  ///< length_m along heading_rad × width_m across it
  kCircle,     ///< of radius radius_m, as a regular polygon of circle_vertices vertices
};

/// A closed loop in NED, flown once at each of several depths; see loopWaypoints().
struct LoopPattern {
  LoopShape shape = LoopShape::kRectangle;
  Eigen::Vector2d center_ne_m = Eigen::Vector2d::Zero();  ///< NED north and east, metres
  /// Direction of travel at the start, clockwise from north seen from above, radians (rectangle:
  /// along its first side).
  double heading_rad = 0.0;
  double length_m = 6.0;  ///< rectangle: side along heading_rad, metres, > 0
  double width_m = 4.0;   ///< rectangle: side across it, metres, > 0
  double radius_m = 3.0;  ///< circle: metres, > 0
  std::size_t circle_vertices = 72;  ///< circle: vertices of the polygon, ≥ 3
  bool clockwise = true;  ///< direction of travel seen from above (clockwise: turning to starboard)
  /// Depths of the vehicle origin (NED z, metres, positive down), one loop at each, in order.
  std::vector<double> depths_m{0.0, 1.0};
  double speed_mps = 0.25;       ///< > 0, vertical transits included
  double turn_rate_radps = 0.5;  ///< rectangle: of the turns in place at the corners, rad/s, > 0
};

/// Waypoints (times from 0 s) of a closed loop at each of `pattern.depths_m`, for
/// waypointTrajectory(). Rectangle: it starts at the corner from which its first side runs along
/// heading_rad with the rectangle's centre to starboard (clockwise) or to port (counter-clockwise),
/// i.e. at center − length/2 · forward ∓ width/2 · starboard, and goes round its four sides back to
/// that corner, stopping at each corner to turn in place by 90° at turn_rate_radps (arrival and
/// departure waypoints), yaw along each side. Circle: it starts at center ∓ radius · starboard
/// (the centre lies to starboard when clockwise) heading along heading_rad, and visits the
/// polygon's vertices back to the start at constant speed, yaw at each vertex the circle's tangent
/// (the direction of travel there, so the yaw turns steadily between vertices). After each loop
/// the vehicle moves vertically at the start point to the next depth, keeping its yaw (and turns
/// back to heading_rad in place first if needed). Roll and pitch 0; the vehicle moves at speed_mps.
/// @throws ValueError naming the field for a non-finite value, a size, speed or turn rate not > 0,
///         fewer than 3 circle vertices, or an empty depth list.
std::vector<NavSample> loopWaypoints(const LoopPattern& pattern);

}  // namespace sonarmap
