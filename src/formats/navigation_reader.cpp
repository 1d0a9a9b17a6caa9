/// @file navigation_reader.cpp
/// Navigation from a CSV or a ROS 1 bag (see navigation_reader.hpp).

#include "sonarmap/formats/navigation_reader.hpp"

#include <filesystem>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"

namespace sonarmap {
namespace {

NavigationSource fromBag(const std::string& path, RosBagNavigation nav) {
  NavigationSource source;
  source.track = std::move(nav.track);
  source.skipped = nav.skipped;
  source.description = nav.topic + " (" + nav.type + ", " + nav.frame + ") of " + std::filesystem::path(path).filename().string();
  return source;
}

}  // namespace

NavigationSource readNavigation(const std::string& path, const std::string& nav_topic) {
  if (const auto format = logFormatOfPath(path); format && isRosLog(*format)) {
    std::optional<RosBagNavigation> nav = readRosBagNavigation(path, RosBagNavOptions{nav_topic});
    if (!nav) {
      throw FileError("'" + path + "': ROS bag: no topic holds a pose (nav_msgs/Odometry, geometry_msgs/PoseStamped or "
                      "PoseWithCovarianceStamped, or a message laid out as one)");
    }
    return fromBag(path, std::move(*nav));
  }
  NavigationSource source;
  source.track = readNavCsv(path);
  source.description = std::filesystem::path(path).filename().string();
  return source;
}

std::optional<NavigationSource> readLogNavigation(const std::string& log_path, LogFormat format, const std::string& nav_topic) {
  if (!isRosLog(format)) return std::nullopt;
  std::optional<RosBagNavigation> nav = readRosBagNavigation(log_path, RosBagNavOptions{nav_topic});
  if (!nav) return std::nullopt;
  return fromBag(log_path, std::move(*nav));
}

}  // namespace sonarmap
