#pragma once
/// @file navigation_reader.hpp
/// The vehicle's navigation wherever a user keeps it: a navigation CSV (nav/navigation.hpp) or the
/// navigation topic of a ROS 1 bag (ros_bag_navigation.hpp), beside the sonar or in the sonar's own
/// bag. What the CLI's --nav and the Python module's `nav` take.

#include <optional>
#include <string>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// A navigation track and where it came from, in words for a summary ("nav.csv", or
/// "/odometry (nav_msgs/Odometry, ENU (REP 103), turned into NED) of run.bag").
struct NavigationSource {
  NavTrack track;
  std::string description;
  std::size_t skipped = 0;  ///< fixes skipped (a bag's messages that gave none)
};

/// Reads the navigation at `path`: a ROS 1 bag's navigation topic when its extension is `.bag`
/// (`nav_topic`, or the one its fields name), else a navigation CSV (readNavCsv).
/// @throws FileError when the file cannot be read, or a bag holds no navigation topic.
NavigationSource readNavigation(const std::string& path, const std::string& nav_topic = {});

/// The navigation recorded in a sonar log's own file: a ROS 1 bag's navigation topic; nullopt for
/// a bag without one (and `nav_topic` empty) and for every other format, which records none.
/// @throws FileError as readRosBagNavigation.
std::optional<NavigationSource> readLogNavigation(const std::string& log_path, LogFormat format,
                                                  const std::string& nav_topic = {});

}  // namespace sonarmap
