#pragma once
/// @file navigation_reader.hpp
/// The vehicle's navigation wherever a user keeps it: a navigation CSV (nav/navigation.hpp) or the
/// navigation topic of a ROS 1 bag (ros_bag_navigation.hpp), beside the sonar or in the sonar's own
/// bag. What the CLI's --nav and the Python module's `nav` take.

#include <optional>
#include <string>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/navigation_source.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// Reads the navigation at `path`: a ROS log's navigation topic when its extension names one
/// (`.bag`, `.mcap`, `.db3`, a rosbag2 folder; `nav_topic`, or the one its fields name); a MAVLink
/// telemetry log when it ends in `.tlog` (readMavlinkTlogNavigation); an ArduPilot dataflash log
/// when it ends in `.bin` (any case) or its bytes start as one (readDataflashNavigation); else a
/// navigation CSV
/// (readNavCsv).
/// @throws FileError when the file cannot be read, or holds no navigation.
/// `msg_path`: as RosBagOptions::msg_path.
NavigationSource readNavigation(const std::string& path, const std::string& nav_topic = {},
                                const std::string& msg_path = {});

/// The navigation recorded in a sonar log's own file: a ROS 1 bag's navigation topic; nullopt for
/// a bag without one (and `nav_topic` empty) and for every other format, which records none.
/// @throws FileError as readRosBagNavigation.
std::optional<NavigationSource> readLogNavigation(const std::string& log_path, LogFormat format,
                                                  const std::string& nav_topic = {}, const std::string& msg_path = {});

/// How a navigation track's times were put on a sonar log's clock.
struct NavClockAlignment {
  double shift_s = 0.0;  ///< added to every fix's time
  bool both_utc = false;  ///< both files said what their clock is in UTC
  std::string how;        ///< in words, for a summary
};

/// Puts `nav`'s fix times on the sonar log's clock: each time + shift, with shift =
/// nav_time_offset_s + (nav.clock_utc_s − log_clock_utc_s) when both clocks are known in UTC
/// (log_clock.hpp), else nav_time_offset_s alone (the two files are taken to share a clock, as a
/// navigation CSV written for its log does). `nav.clock_utc_s` becomes `log_clock_utc_s`.
/// @throws ValueError when nav_time_offset_s is not finite.
NavClockAlignment alignNavigationClock(NavigationSource& nav, const std::optional<double>& log_clock_utc_s,
                                       double nav_time_offset_s);

}  // namespace sonarmap
