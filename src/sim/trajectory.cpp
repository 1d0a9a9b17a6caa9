/// @file trajectory.cpp
/// Simple vehicle trajectories (see trajectory.hpp).

#include "sonarmap/sim/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <utility>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// `angle_rad` wrapped into [−π, π).
double wrapAngle(double angle_rad) { return angle_rad - kTwoPi * std::floor((angle_rad + std::numbers::pi) / kTwoPi); }

/// `value` must be finite and > 0.
void requirePositive(const char* where, const char* field, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw ValueError(std::string(where) + ": " + field + " must be a finite number > 0, got " + std::to_string(value));
  }
}

void requireFinite(const char* where, const char* field, double value) {
  if (!std::isfinite(value)) throw ValueError(std::string(where) + ": " + field + " is not finite");
}

void requireDepths(const char* where, const std::vector<double>& depths_m) {
  if (depths_m.empty()) throw ValueError(std::string(where) + ": depths_m is empty");
  for (const double depth_m : depths_m) requireFinite(where, "a depth in depths_m", depth_m);
}

/// Builds the waypoints of a mission flown at constant speed: straight moves, turns in place.
class PathBuilder {
 public:
  PathBuilder(double speed_mps, double turn_rate_radps) : speed_mps_(speed_mps), turn_rate_radps_(turn_rate_radps) {}

  /// The first waypoint, at time 0.
  void start(const Eigen::Vector3d& position_ned_m, double yaw_rad) {
    NavSample first;
    first.position_ned_m = position_ned_m;
    first.yaw_rad = yaw_rad;
    points_.push_back(first);
  }

  /// Turns in place to `yaw_rad` by the shorter way (nothing when already there).
  void turnTo(double yaw_rad) {
    const double turn_rad = wrapAngle(yaw_rad - points_.back().yaw_rad);
    if (std::abs(turn_rad) < 1e-12) return;
    NavSample next = points_.back();
    next.time_s += std::abs(turn_rad) / turn_rate_radps_;
    next.yaw_rad = yaw_rad;
    points_.push_back(next);
  }

  /// Straight to `position_ned_m`, first turning in place to the direction of horizontal travel
  /// (a vertical move keeps the yaw). Nothing when already there.
  void moveTo(const Eigen::Vector3d& position_ned_m) {
    const Eigen::Vector3d step = position_ned_m - points_.back().position_ned_m;
    if (step.norm() < 1e-12) return;
    if (step.head<2>().norm() > 1e-9) turnTo(std::atan2(step.y(), step.x()));
    arrive(position_ned_m, points_.back().yaw_rad);
  }

  /// Straight to `position_ned_m`, the yaw changing on the way to `yaw_rad` (no turn in place).
  void moveTo(const Eigen::Vector3d& position_ned_m, double yaw_rad) {
    if ((position_ned_m - points_.back().position_ned_m).norm() < 1e-12) return;
    arrive(position_ned_m, yaw_rad);
  }

  const Eigen::Vector3d& position() const { return points_.back().position_ned_m; }
  std::vector<NavSample> take() { return std::move(points_); }

 private:
  void arrive(const Eigen::Vector3d& position_ned_m, double yaw_rad) {
    NavSample next = points_.back();
    next.time_s += (position_ned_m - next.position_ned_m).norm() / speed_mps_;
    next.position_ned_m = position_ned_m;
    next.yaw_rad = yaw_rad;
    points_.push_back(next);
  }

  double speed_mps_;
  double turn_rate_radps_;
  std::vector<NavSample> points_;
};

/// Horizontal unit vectors (north, east) along `heading_rad` and 90° clockwise from it.
std::pair<Eigen::Vector2d, Eigen::Vector2d> forwardAndStarboard(double heading_rad) {
  return {Eigen::Vector2d(std::cos(heading_rad), std::sin(heading_rad)),
          Eigen::Vector2d(-std::sin(heading_rad), std::cos(heading_rad))};
}

Eigen::Vector3d atDepth(const Eigen::Vector2d& north_east_m, double depth_m) {
  return {north_east_m.x(), north_east_m.y(), depth_m};
}

}  // namespace

Trajectory staticTrajectory(const NavSample& pose) {
  return [pose](double time_s) {
    NavSample sample = pose;
    sample.time_s = time_s;
    return sample;
  };
}

Trajectory constantVelocityTrajectory(const NavSample& start, const Eigen::Vector3d& velocity_ned_mps,
                                      double yaw_rate_radps) {
  const bool finite = std::isfinite(start.time_s) && start.position_ned_m.allFinite() &&
                      std::isfinite(start.roll_rad) && std::isfinite(start.pitch_rad) && std::isfinite(start.yaw_rad) &&
                      velocity_ned_mps.allFinite() && std::isfinite(yaw_rate_radps);
  if (!finite) throw ValueError("constant-velocity trajectory: the start pose, velocity and yaw rate must be finite");
  return [start, velocity_ned_mps, yaw_rate_radps](double time_s) {
    const double elapsed_s = time_s - start.time_s;
    NavSample sample = start;
    sample.time_s = time_s;
    sample.position_ned_m += velocity_ned_mps * elapsed_s;
    sample.yaw_rad += yaw_rate_radps * elapsed_s;
    return sample;
  };
}

Trajectory waypointTrajectory(std::vector<NavSample> waypoints) {
  if (waypoints.empty()) throw ValueError("waypoint trajectory: no waypoint");
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    if (!isFinite(waypoints[i])) {
      throw ValueError("waypoint trajectory: waypoint " + std::to_string(i) + " holds a non-finite value");
    }
    if (i > 0 && !(waypoints[i].time_s > waypoints[i - 1].time_s)) {
      throw ValueError("waypoint trajectory: waypoint " + std::to_string(i) + "'s time " +
                       std::to_string(waypoints[i].time_s) + " s is not after the previous one's " +
                       std::to_string(waypoints[i - 1].time_s) + " s");
    }
  }
  auto shared = std::make_shared<const std::vector<NavSample>>(std::move(waypoints));
  return [shared](double time_s) {
    const std::vector<NavSample>& points = *shared;
    NavSample sample;
    if (!(time_s > points.front().time_s)) {  // before the first waypoint, at it, or NaN
      sample = points.front();
    } else if (time_s >= points.back().time_s) {
      sample = points.back();
    } else {
      const auto after = std::upper_bound(points.begin(), points.end(), time_s,
                                          [](double t, const NavSample& point) { return t < point.time_s; });
      const NavSample& a = *(after - 1);
      const NavSample& b = *after;
      const double f = (time_s - a.time_s) / (b.time_s - a.time_s);
      sample.position_ned_m = a.position_ned_m + f * (b.position_ned_m - a.position_ned_m);
      sample.roll_rad = a.roll_rad + f * (b.roll_rad - a.roll_rad);
      sample.pitch_rad = a.pitch_rad + f * (b.pitch_rad - a.pitch_rad);
      sample.yaw_rad = a.yaw_rad + f * wrapAngle(b.yaw_rad - a.yaw_rad);
    }
    sample.time_s = time_s;
    return sample;
  };
}

std::vector<NavSample> lawnmowerWaypoints(const LawnmowerPattern& pattern) {
  constexpr const char* kWhere = "lawnmowerWaypoints";
  if (!pattern.center_ne_m.allFinite()) throw ValueError(std::string(kWhere) + ": center_ne_m is not finite");
  requireFinite(kWhere, "heading_rad", pattern.heading_rad);
  if (pattern.legs == 0) throw ValueError("lawnmower pattern: legs must be at least 1");
  requirePositive(kWhere, "leg_length_m", pattern.leg_length_m);
  requireFinite(kWhere, "leg_spacing_m", pattern.leg_spacing_m);
  if (pattern.leg_spacing_m == 0.0) throw ValueError("lawnmower pattern: leg_spacing_m must not be 0");
  requirePositive(kWhere, "speed_mps", pattern.speed_mps);
  requirePositive(kWhere, "turn_rate_radps", pattern.turn_rate_radps);
  requireDepths(kWhere, pattern.depths_m);

  // The path at one depth: each leg's start and end, in flying order.
  const auto [forward, starboard] = forwardAndStarboard(pattern.heading_rad);
  const double legs = static_cast<double>(pattern.legs);
  const Eigen::Vector2d first_start = pattern.center_ne_m - 0.5 * pattern.leg_length_m * forward -
                                      0.5 * (legs - 1.0) * pattern.leg_spacing_m * starboard;
  std::vector<Eigen::Vector2d> path;
  for (std::size_t k = 0; k < pattern.legs; ++k) {
    const Eigen::Vector2d near = first_start + static_cast<double>(k) * pattern.leg_spacing_m * starboard;
    const Eigen::Vector2d far = near + pattern.leg_length_m * forward;
    path.push_back(k % 2 == 0 ? near : far);
    path.push_back(k % 2 == 0 ? far : near);
  }

  PathBuilder builder(pattern.speed_mps, pattern.turn_rate_radps);
  builder.start(atDepth(path.front(), pattern.depths_m.front()), pattern.heading_rad);
  for (std::size_t j = 0; j < pattern.depths_m.size(); ++j) {
    const double depth_m = pattern.depths_m[j];
    builder.moveTo(Eigen::Vector3d(builder.position().x(), builder.position().y(), depth_m));  // vertical
    for (const Eigen::Vector2d& point : path) builder.moveTo(atDepth(point, depth_m));  // first: no move
    std::reverse(path.begin(), path.end());  // the next depth flies it backwards
  }
  return builder.take();
}

std::vector<NavSample> loopWaypoints(const LoopPattern& pattern) {
  constexpr const char* kWhere = "loopWaypoints";
  if (!pattern.center_ne_m.allFinite()) throw ValueError(std::string(kWhere) + ": center_ne_m is not finite");
  requireFinite(kWhere, "heading_rad", pattern.heading_rad);
  if (pattern.shape == LoopShape::kRectangle) {
    requirePositive(kWhere, "length_m", pattern.length_m);
    requirePositive(kWhere, "width_m", pattern.width_m);
  } else {
    requirePositive(kWhere, "radius_m", pattern.radius_m);
    if (pattern.circle_vertices < 3) {
      throw ValueError("loop pattern: circle_vertices must be at least 3, got " +
                       std::to_string(pattern.circle_vertices));
    }
  }
  requirePositive(kWhere, "speed_mps", pattern.speed_mps);
  requirePositive(kWhere, "turn_rate_radps", pattern.turn_rate_radps);
  requireDepths(kWhere, pattern.depths_m);

  const auto [forward, starboard] = forwardAndStarboard(pattern.heading_rad);
  const double side = pattern.clockwise ? 1.0 : -1.0;  // the centre lies to starboard when clockwise
  PathBuilder builder(pattern.speed_mps, pattern.turn_rate_radps);
  if (pattern.shape == LoopShape::kRectangle) {
    const Eigen::Vector2d corner =
        pattern.center_ne_m - 0.5 * pattern.length_m * forward - side * 0.5 * pattern.width_m * starboard;
    const Eigen::Vector2d along = pattern.length_m * forward, across = side * pattern.width_m * starboard;
    const std::vector<Eigen::Vector2d> corners{corner, corner + along, corner + along + across, corner + across, corner};
    builder.start(atDepth(corner, pattern.depths_m.front()), pattern.heading_rad);
    for (const double depth_m : pattern.depths_m) {
      builder.moveTo(atDepth(corner, depth_m));  // vertical
      for (const Eigen::Vector2d& point : corners) builder.moveTo(atDepth(point, depth_m));
    }
    return builder.take();
  }
  // Circle: the vertex at angle φ (clockwise from north about the centre) is centre + r·(cos φ, sin φ);
  // clockwise travel increases φ, and the direction of travel there is φ + 90° (φ − 90° otherwise).
  const double start_angle_rad = pattern.heading_rad - side * 0.5 * std::numbers::pi;
  const double step_rad = side * kTwoPi / static_cast<double>(pattern.circle_vertices);
  const Eigen::Vector2d start = pattern.center_ne_m - side * pattern.radius_m * starboard;
  builder.start(atDepth(start, pattern.depths_m.front()), pattern.heading_rad);
  for (const double depth_m : pattern.depths_m) {
    builder.moveTo(atDepth(start, depth_m));  // vertical, keeping the yaw
    for (std::size_t k = 1; k <= pattern.circle_vertices; ++k) {
      const bool last = k == pattern.circle_vertices;
      const double angle_rad = start_angle_rad + static_cast<double>(k) * step_rad;
      const Eigen::Vector2d on_circle =
          pattern.center_ne_m + pattern.radius_m * Eigen::Vector2d(std::cos(angle_rad), std::sin(angle_rad));
      const Eigen::Vector2d vertex = last ? start : on_circle;  // closes exactly
      const double yaw_rad = last ? pattern.heading_rad : wrapAngle(angle_rad + side * 0.5 * std::numbers::pi);
      builder.moveTo(atDepth(vertex, depth_m), yaw_rad);
    }
  }
  return builder.take();
}

}  // namespace sonarmap
