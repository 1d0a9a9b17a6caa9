#pragma once
/// @file navigation_source.hpp
/// A navigation track as a reader found it: the fixes, where they came from, and what its clock is.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "sonarmap/nav/geodetic.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// A navigation track and where it came from, in words for a summary ("nav.csv", or
/// "/odometry (nav_msgs/Odometry, ENU (REP 103), turned into NED) of run.bag").
struct NavigationSource {
  NavTrack track;
  std::string description;
  std::size_t skipped = 0;  ///< messages or records skipped (that gave no fix, or could not be read)
  /// UTC, in seconds since 1970, at the track's time_s = 0 when the file says (log_clock.hpp): 0 for
  /// a ROS log or a MAVLink telemetry log, a dataflash log's boot time from its GPS fixes; unset for
  /// a navigation CSV or a dataflash log without a GPS fix.
  std::optional<double> clock_utc_s;
  /// The vehicle's body frame the fixes are of, where the file names it (a ROS log's
  /// child_frame_id: where its /tf_static mounts the sonar, ros_bag_mounting.hpp); empty otherwise.
  std::string body_frame;
  /// Lines for the user about the reading: where a file was cut and what was kept before it.
  std::vector<std::string> notes;
  /// Latitudes and longitudes the file records (a bag's sensor_msgs/NavSatFix, a dataflash log's
  /// GPS records with a 3D fix, a telemetry log's GLOBAL_POSITION_INT), on the track's clock, each
  /// checked by requireGeodetic; empty when it records none.
  std::vector<GeodeticFix> geodetic_fixes;
  /// Where they came from, in words ("/gps/fix (sensor_msgs/NavSatFix)"); empty without them.
  std::string geodetic_description;
  /// The geodetic position of the track's NED zero (geodeticOriginOf(geodetic_fixes, track)),
  /// set by readNavigation and readLogNavigation; nullopt when no fix lies within the track's span.
  std::optional<GeodeticPoint> geodetic_origin;
};

}  // namespace sonarmap
