#pragma once
/// @file ros_inertial_navigation.hpp
/// Private to formats: a vehicle's navigation dead-reckoned from the raw sensors a ROS 1 bag
/// records when it has no pose topic (see ros_bag_navigation.hpp): the attitude of an IMU's
/// orientation, the depth of a pressure sensor, and the position integrated from a DVL's velocity.

#include <optional>

#include "ros_bag_file.hpp"

namespace sonarmap::detail {

/// The navigation of `bag` from its raw sensors, found by their fields' roles:
///  - attitude (required): a std_msgs/Header and a top-level `orientation` quaternion x, y, z, w
///    (sensor_msgs/Imu; a message whose `orientation_covariance[0]` is −1, "no orientation" in the
///    message's documentation, is skipped);
///  - depth: a header and `fluid_pressure` in pascals (sensor_msgs/FluidPressure), depth =
///    (p − surface pressure) / (ρ g), ρ and the surface pressure from `options`, g = 9.80665 m/s²;
///  - velocity: a header and `twist.linear` (geometry_msgs/TwistStamped), `twist.twist.linear`
///    (TwistWithCovarianceStamped) or `velocity` (vendor DVL messages), x, y, z in m/s in the body.
/// Frames as poses (ros_frames.hpp): ENU world and FLU body unless the frame_id contains "ned"
/// (then NED and FRD). The DVL's velocity is turned into the IMU's frame by the rotation of the
/// /tf_static chain between the two frames (staticTransform) when the log records one, else taken
/// as aligned with it; its lever arm is not used.
/// A fix per attitude message: roll, pitch, yaw from it; north and east integrated from the
/// velocities turned into NED with the attitude nearest in time, each held until the next, from
/// (0, 0) at the first velocity message (zero without a DVL); down the
/// pressure's depth, interpolated, else the integrated velocity's (zero without either).
/// @return nullopt when the bag has no attitude topic.
std::optional<RosBagNavigation> inertialNavigation(RosBagFile& bag, const RosBagNavOptions& options);

}  // namespace sonarmap::detail
