// --nav, --sonar-topic, --nav-topic, --nav-time-offset and --timezone (see navigation_input.hpp).

#include "navigation_input.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_clock.hpp"
#include "sonarmap/formats/ros_bag_mounting.hpp"

namespace sonarmap::cli {

void addLogInputOptions(CLI::App& cmd, std::string& nav_file, LogReadOptions& log_read, std::string& nav_topic,
                        double& nav_time_offset_s, const std::string& nav_help) {
  cmd.add_option("--nav", nav_file,
                 nav_help + ". A navigation CSV (time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad: NED metres, radians, "
                            "the log's clock), a ROS log (.bag, .mcap, .db3: its nav_msgs/Odometry or pose topic, ENU "
                            "turned into NED), a BlueROV2's MAVLink telemetry (.tlog) or ArduPilot dataflash log (.BIN). "
                            "Default: the input bag's own navigation topic when it has one; `none`: no navigation");
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
  cmd.add_option("--nav-time-offset", nav_time_offset_s,
                 "Seconds added to the navigation's times after both clocks are put on UTC where the files say "
                 "(a Ping Viewer log's name, a .tlog, a bag, a dataflash log's GPS); alone, when either does not. "
                 "`info --nav` prints both spans")
      ->capture_default_str();
  cmd.add_option_function<std::string>(
         "--timezone",
         [&log_read](const std::string& zone) {
           try {
             log_read.utc_offset_s = parseUtcOffset(zone);
           } catch (const ValueError& e) {
             throw CLI::ValidationError("--timezone", e.what());
           }
         },
         "The recording computer's offset from UTC, for a log named in local time (Ping Viewer: "
         "yyyyMMdd-hhmmsszzz.bin): UTC | +03:30 | -05:00. Default: UTC")
      ->type_name("ZONE");
  cmd.add_option("--msg-path", log_read.msg_path,
                 "A folder of .msg files (PKG/msg/NAME.msg) for the message types a ROS 2 log in rosbag2's SQLite "
                 "storage (before Iron) names without definitions. Default: the common types, built in")
      ->type_name("DIR");
}

std::optional<AlignedNavigation> navigationFor(const std::string& input, LogFormat format, const SonarLog& log,
                                               const std::string& nav_file, const std::string& nav_topic,
                                               double nav_time_offset_s, const std::string& msg_path) {
  if (nav_file == "none") return std::nullopt;
  std::optional<NavigationSource> source = nav_file.empty() ? readLogNavigation(input, format, nav_topic, msg_path)
                                                            : readNavigation(nav_file, nav_topic, msg_path);
  if (!source) return std::nullopt;
  AlignedNavigation nav;
  nav.own_clock_utc_s = source->clock_utc_s;
  if (!source->track.empty()) {
    nav.first_own_s = source->track.front().time_s;
    nav.last_own_s = source->track.back().time_s;
  }
  nav.clock = alignNavigationClock(*source, log.clock_utc_s, nav_time_offset_s);
  nav.source = std::move(*source);
  return nav;
}

Eigen::Isometry3d mountingFor(const std::string& input, LogFormat format, const SonarLog& log,
                              const std::optional<AlignedNavigation>& navigation, bool mounting_given,
                              const Eigen::Isometry3d& given) {
  if (mounting_given || !navigation || !isRosLog(format)) return given;
  const std::optional<RosBagMounting> mounting = readRosBagMounting(input, log.frame_id, navigation->source.body_frame);
  if (!mounting) return given;
  const Eigen::Vector3d t = mounting->sonar_to_body.translation();
  std::printf("mounting from /tf_static: %s (sonar at %.3f, %.3f, %.3f m in the body frame, FRD)\n",
              mounting->chain.c_str(), t.x(), t.y(), t.z());
  return mounting->sonar_to_body;
}

std::string spanText(double first_s, double last_s, const std::optional<double>& clock_utc_s) {
  if (clock_utc_s) return utcText(*clock_utc_s + first_s) + " .. " + utcText(*clock_utc_s + last_s);
  char text[96];
  std::snprintf(text, sizeof text, "%.3f .. %.3f s", first_s, last_s);
  return text;
}

std::optional<std::pair<double, double>> spanOf(const std::optional<AlignedNavigation>& nav) {
  if (!nav || nav->source.track.empty()) return std::nullopt;
  return std::pair(nav->source.track.front().time_s, nav->source.track.back().time_s);
}

void requireClockOverlap(const LogSurvey& survey, const std::optional<double>& clock_utc_s, const AlignedNavigation& nav) {
  if (nav.source.track.empty() || survey.beams == 0 || survey.beams_in_span > 0) return;
  throw FileError("no beam within the navigation's time span: sonar " + spanText(survey.earliest_s, survey.latest_s, clock_utc_s) +
                  ", navigation " + spanText(nav.first_own_s, nav.last_own_s, nav.own_clock_utc_s) + " (" +
                  nav.clock.how + "); give --nav-time-offset SECONDS or --timezone");
}

/// One line on where the navigation came from, unless it is the navigation CSV the user named;
/// how its clock was joined to the log's when either clock is known or an offset was given; the
/// reader's notes.
void printNavigationSource(const AlignedNavigation& navigation, const std::string& nav_file) {
  const NavigationSource& source = navigation.source;
  const bool csv = !nav_file.empty() && source.description == std::filesystem::path(nav_file).filename().string();
  if (!csv) {
    std::printf("navigation %s: %zu fixes%s\n", source.description.c_str(), source.track.size(),
                source.skipped > 0 ? (", " + std::to_string(source.skipped) + " messages skipped").c_str() : "");
  }
  if (navigation.clock.shift_s != 0.0 || (navigation.clock.both_utc && !nav_file.empty())) {
    std::printf("navigation clock: %s (times moved by %+.3f s)\n", navigation.clock.how.c_str(), navigation.clock.shift_s);
  }
  for (const std::string& note : source.notes) std::fprintf(stderr, "warning: %s\n", note.c_str());
}

}  // namespace sonarmap::cli
