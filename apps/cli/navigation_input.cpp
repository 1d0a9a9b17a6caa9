// --nav, --sonar-topic and --nav-topic (see navigation_input.hpp).

#include "navigation_input.hpp"

namespace sonarmap::cli {

void addLogInputOptions(CLI::App& cmd, std::string& nav_file, LogReadOptions& log_read, std::string& nav_topic,
                        const std::string& nav_help) {
  cmd.add_option("--nav", nav_file,
                 nav_help + ". A navigation CSV (time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad: NED metres, radians, "
                            "the log's clock) or a ROS 1 bag (.bag: its nav_msgs/Odometry or pose topic, ENU turned into "
                            "NED). Default: the input bag's own navigation topic when it has one; `none`: no navigation");
  cmd.add_option("--sonar-topic", log_read.sonar_topic,
                 "The sonar topic of a ROS bag input. Default: the first topic whose message has a bearing, a bin "
                 "length or range, and intensities");
  cmd.add_option("--bearing-unit", log_read.bearing_unit,
                 "A ROS bag's bearing unit where it cannot tell: auto (degrees unless the field's name ends in _rad or "
                 "every bearing fits in 2 pi) | deg | rad | grad")
      ->check(CLI::IsMember({"auto", "deg", "rad", "grad"}))
      ->capture_default_str();
  cmd.add_option("--bearing-direction", log_read.bearing_direction,
                 "Which way a ROS bag's bearings grow seen from above: cw (as Tritech heads count) | ccw (as REP 103 "
                 "angles do)")
      ->check(CLI::IsMember({"cw", "ccw"}))
      ->capture_default_str();
  cmd.add_option("--nav-topic", nav_topic,
                 "The navigation topic of a ROS bag (the input's, or --nav's). Default: nav_msgs/Odometry, else the "
                 "topic with a header and a pose that has most messages");
}

std::optional<NavigationSource> navigationFor(const std::string& input, LogFormat format, const std::string& nav_file,
                                              const std::string& nav_topic) {
  if (nav_file == "none") return std::nullopt;
  if (!nav_file.empty()) return readNavigation(nav_file, nav_topic);
  return readLogNavigation(input, format, nav_topic);
}

}  // namespace sonarmap::cli
