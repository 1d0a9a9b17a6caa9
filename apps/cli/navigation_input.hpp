#pragma once
// Where `map` and `info` take the vehicle's navigation from (--nav: a CSV, a ROS 1 bag, `none`; or
// the input bag's own navigation topic) and which topics of a bag they read (--sonar-topic,
// --nav-topic).

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "sonarmap/formats/navigation_reader.hpp"

namespace sonarmap::cli {

/// Adds --nav (`nav_help` first in its help) into `nav_file`, --nav-topic, and a ROS bag's
/// --sonar-topic, --bearing-unit and --bearing-direction into `log_read`.
void addLogInputOptions(CLI::App& cmd, std::string& nav_file, LogReadOptions& log_read, std::string& nav_topic,
                        const std::string& nav_help);

/// The navigation for the log `input` in `format`: `nav_file`'s ("none": nothing), else the input
/// bag's own navigation topic, else nothing.
/// @throws FileError as readNavigation and readLogNavigation.
std::optional<NavigationSource> navigationFor(const std::string& input, LogFormat format, const std::string& nav_file,
                                              const std::string& nav_topic);

}  // namespace sonarmap::cli
