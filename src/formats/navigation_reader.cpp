/// @file navigation_reader.cpp
/// Navigation from a CSV or a ROS 1 bag (see navigation_reader.hpp).

#include "sonarmap/formats/navigation_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_clock.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"

namespace sonarmap {
namespace {

NavigationSource fromBag(const std::string& path, RosBagNavigation nav) {
  NavigationSource source;
  source.track = std::move(nav.track);
  source.skipped = nav.skipped;
  source.clock_utc_s = 0.0;  // header stamps: seconds since 1970
  source.body_frame = nav.body_frame;
  source.description = nav.topic + " (" + nav.type + ", " + nav.frame + ") of " + std::filesystem::path(path).filename().string();
  source.geodetic_fixes = std::move(nav.geodetic_fixes);
  if (!nav.geodetic_topic.empty()) source.geodetic_description = nav.geodetic_topic + " (sensor_msgs/NavSatFix)";
  return source;
}

/// `source` with its geodetic origin found from its fixes (geodeticOriginOf).
NavigationSource withGeodeticOrigin(NavigationSource source) {
  source.geodetic_origin = geodeticOriginOf(source.geodetic_fixes, source.track);
  return source;
}

bool startsAsDataflash(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::array<std::uint8_t, 3> head{};
  file.read(reinterpret_cast<char*>(head.data()), head.size());
  return file.gcount() == static_cast<std::streamsize>(head.size()) && isDataflashLog(head);
}

std::string secondsText(double s) {
  char text[48];
  std::snprintf(text, sizeof text, "%+.3f s", s);
  return text;
}

}  // namespace

NavigationSource readNavigation(const std::string& path, const std::string& nav_topic, const std::string& msg_path) {
  if (const auto format = logFormatOfPath(path); format && isRosLog(*format)) {
    std::optional<RosBagNavigation> nav = readRosBagNavigation(path, RosBagNavOptions{.nav_topic = nav_topic, .msg_path = msg_path});
    if (!nav) {
      throw FileError("'" + path + "': ROS bag: no topic holds a pose (nav_msgs/Odometry, geometry_msgs/PoseStamped or "
                      "PoseWithCovarianceStamped, or a message laid out as one)");
    }
    return withGeodeticOrigin(fromBag(path, std::move(*nav)));
  }
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".tlog") return withGeodeticOrigin(readMavlinkTlogNavigation(path));
  // .BIN is ArduPilot's name for a dataflash log (a Ping Viewer .bin holds no navigation)
  if (extension == ".bin" || startsAsDataflash(path)) return withGeodeticOrigin(readDataflashNavigation(path));
  NavigationSource source;
  source.track = readNavCsv(path);
  source.description = std::filesystem::path(path).filename().string();
  return source;
}

std::optional<NavigationSource> readLogNavigation(const std::string& log_path, LogFormat format, const std::string& nav_topic,
                                                  const std::string& msg_path) {
  if (!isRosLog(format)) return std::nullopt;
  std::optional<RosBagNavigation> nav = readRosBagNavigation(log_path, RosBagNavOptions{.nav_topic = nav_topic, .msg_path = msg_path});
  if (!nav) return std::nullopt;
  return withGeodeticOrigin(fromBag(log_path, std::move(*nav)));
}

NavClockAlignment alignNavigationClock(NavigationSource& nav, const std::optional<double>& log_clock_utc_s,
                                       double nav_time_offset_s) {
  if (!std::isfinite(nav_time_offset_s)) {
    throw ValueError("navigation time offset " + std::to_string(nav_time_offset_s) + " s: expected a finite number");
  }
  NavClockAlignment alignment;
  alignment.both_utc = nav.clock_utc_s && log_clock_utc_s;
  alignment.shift_s = nav_time_offset_s + (alignment.both_utc ? *nav.clock_utc_s - *log_clock_utc_s : 0.0);
  if (alignment.both_utc) {
    alignment.how = "both clocks in UTC";
  } else {
    alignment.how = std::string("taken as on the sonar log's clock (") +
                    (log_clock_utc_s ? "" : "the sonar log does not say when it started") +
                    (!log_clock_utc_s && !nav.clock_utc_s ? ", " : "") +
                    (nav.clock_utc_s ? "" : "the navigation's clock is not UTC") + ")";
  }
  if (nav_time_offset_s != 0.0) alignment.how += ", moved by --nav-time-offset " + secondsText(nav_time_offset_s);
  for (NavSample& fix : nav.track) fix.time_s += alignment.shift_s;
  for (GeodeticFix& fix : nav.geodetic_fixes) fix.time_s += alignment.shift_s;
  nav.clock_utc_s = log_clock_utc_s;
  return alignment;
}

}  // namespace sonarmap
