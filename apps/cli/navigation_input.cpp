// --nav, --sonar-topic, --nav-topic, --nav-time-offset and --timezone (see navigation_input.hpp).

#include "navigation_input.hpp"

#include "help_groups.hpp"

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
  cmd.add_option("--nav", nav_file, nav_help)->group(help_group::kNavigation);
  cmd.add_option("--sonar-topic", log_read.sonar_topic, "Sonar topic of a ROS log (default: found by its fields)")
      ->group(help_group::kInput);
  cmd.add_option("--bearing-unit", log_read.bearing_unit, "A ROS log's bearing unit: auto | deg | rad | grad")
      ->check(CLI::IsMember({"auto", "deg", "rad", "grad"}))
      ->capture_default_str()
      ->option_text("UNIT=auto")
      ->group(help_group::kInput);
  cmd.add_option("--bearing-direction", log_read.bearing_direction, "Way a ROS log's bearings grow from above: cw | ccw")
      ->check(CLI::IsMember({"cw", "ccw"}))
      ->capture_default_str()
      ->group(help_group::kInput);
  cmd.add_option("--nav-topic", nav_topic, "Navigation topic of a ROS log (default: found by its fields)")
      ->group(help_group::kNavigation);
  cmd.add_option("--nav-time-offset", nav_time_offset_s, "Time added to the navigation's clock (s)")
      ->capture_default_str()
      ->group(help_group::kNavigation);
  cmd.add_option_function<std::string>(
         "--timezone",
         [&log_read](const std::string& zone) {
           try {
             log_read.utc_offset_s = parseUtcOffset(zone);
           } catch (const ValueError& e) {
             throw CLI::ValidationError("--timezone", e.what());
           }
         },
         "UTC offset of a log named in local time: UTC | +03:30 | -05:00")
      ->type_name("ZONE")
      ->group(help_group::kInput);
  cmd.add_option("--msg-path", log_read.msg_path, "Folder of .msg files for a rosbag2 SQLite log's types")
      ->type_name("DIR")
      ->group(help_group::kInput);
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
