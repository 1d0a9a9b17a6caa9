#pragma once
// `sonarmap info`: what a sonar log holds, before mapping it: the format and sonar, the
// beams and their clock, the sweeps, the bearings, each head setting (range scale and gain) with
// its beams, what the reader skipped and why, and the navigation's coverage when given. One screen
// of text, or one JSON object with --json.

#include <string>

#include "sonarmap/formats/log_reader.hpp"

#include <CLI/CLI.hpp>

#include "command.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap info` as typed by the user.
struct InfoArgs {
  std::string input;
  std::string format = "auto";  ///< input format, or auto (by extension): inputFormat
  std::string nav_file;         ///< --nav: navigation CSV or bag whose coverage is reported ("none"; empty: the input bag's own)
  LogReadOptions log_read;      ///< --sonar-topic, --bearing-unit, --bearing-direction of a ROS bag input
  std::string nav_topic;        ///< --nav-topic of a ROS bag
  double nav_time_offset_s = 0.0;  ///< --nav-time-offset: seconds added to the navigation's clock
  bool json = false;            ///< --json: one JSON object on stdout instead of the text
};

/// Adds the `info` subcommand to `app`; its options fill `args`. Its check rejects an unknown
/// --format name (ValueError: usage, exit 2).
Command addInfoCommand(CLI::App& app, InfoArgs& args);

/// Reads the log (and the navigation CSV when given), summarizes it (summarizeLog,
/// sonar/log_summary.hpp) and prints the summary on stdout: about 10 to 30 lines of text with a
/// unit on every number, or with args.json one JSON object (keys with their units: `duration_s`,
/// `bin_length_m`, `span_deg`, ...; a value the log does not give is null).
/// @throws FileError for an unknown extension, an unreadable or malformed log or navigation CSV.
void runInfo(const InfoArgs& args);

}  // namespace sonarmap::cli
