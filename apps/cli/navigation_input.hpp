#pragma once
// Where `map` and `info` take the vehicle's navigation from (--nav: a CSV, a ROS 1 bag, `none`; or
// the input bag's own navigation topic) and which topics of a bag they read (--sonar-topic,
// --nav-topic).

#include <optional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "sonarmap/formats/navigation_reader.hpp"
#include "sonarmap/sonar/log_survey.hpp"

namespace sonarmap::cli {

/// Adds --nav (`nav_help` its one-line help) into `nav_file`, --nav-topic, --nav-time-offset into
/// `nav_time_offset_s`, --timezone, --msg-path and a ROS bag's --sonar-topic, --bearing-unit and
/// --bearing-direction into `log_read`.
void addLogInputOptions(CLI::App& cmd, std::string& nav_file, LogReadOptions& log_read, std::string& nav_topic,
                        double& nav_time_offset_s, const std::string& nav_help);

/// A navigation put on the sonar log's clock, and how.
struct AlignedNavigation {
  NavigationSource source;
  NavClockAlignment clock;
  std::optional<double> own_clock_utc_s;  ///< the navigation file's clock before alignment
  double first_own_s = 0.0, last_own_s = 0.0;  ///< its span on its own clock
};

/// The navigation for `log` (read from `input` in `format`): `nav_file`'s ("none": nothing), else
/// the input bag's own navigation topic, else nothing; its times put on the log's clock
/// (alignNavigationClock).
/// @throws FileError as readNavigation and readLogNavigation.
std::optional<AlignedNavigation> navigationFor(const std::string& input, LogFormat format, const SonarLog& log,
                                               const std::string& nav_file, const std::string& nav_topic,
                                               double nav_time_offset_s, const std::string& msg_path = {});

/// "2024-08-14 10:15:02.123 UTC .. 10:19:14.456 UTC" for a span on a clock known in UTC, else
/// "12.300 .. 15.800 s".
std::string spanText(double first_s, double last_s, const std::optional<double>& clock_utc_s);

/// The sonar's mounting (sonar frame → body FRD): `given` (--mounting's) when `mounting_given`;
/// else, for a ROS log input with navigation, the chain of its /tf_static transforms from the
/// navigation's body frame to the frame its sonar messages name (ros_bag_mounting.hpp), said in
/// one line; else `given` (the default mounting).
/// @throws FileError as readRosBagMounting.
Eigen::Isometry3d mountingFor(const std::string& input, LogFormat format, const SonarLog& log,
                              const std::optional<AlignedNavigation>& navigation, bool mounting_given,
                              const Eigen::Isometry3d& given);

/// One line on where the navigation came from, unless it is the navigation CSV named `nav_file`;
/// how its clock was joined to the log's when either clock is known or an offset was given; the
/// reader's notes as warnings on standard error.
void printNavigationSource(const AlignedNavigation& navigation, const std::string& nav_file);

/// [first, last] fix time of `nav`'s track on the log's clock: what a log is surveyed with
/// (surveyLog's span) for requireClockOverlap; nullopt without fixes.
std::optional<std::pair<double, double>> spanOf(const std::optional<AlignedNavigation>& nav);

/// @throws FileError naming both spans (spanText) when no beam of the log surveyed as `survey`
/// (with spanOf(nav)) lies within the track's span: the navigation is on another clock
/// (--nav-time-offset, --timezone). `clock_utc_s`: the log's (SonarLog::clock_utc_s).
void requireClockOverlap(const LogSurvey& survey, const std::optional<double>& clock_utc_s, const AlignedNavigation& nav);

}  // namespace sonarmap::cli
