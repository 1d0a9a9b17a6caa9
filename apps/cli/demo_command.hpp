#pragma once
// `sonarmap demo`: the whole pipeline on data it makes itself, so it runs on any machine: the
// built-in tank is simulated (static head, sim/msis_simulator.hpp) and mapped as `sonarmap map`
// maps a log with its default options.

#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap demo` as typed by the user.
struct DemoArgs {
  std::string output_dir;
  bool quiet = false;
};

/// Adds the `demo` subcommand to `app`; its options fill `args`.
Command addDemoCommand(CLI::App& app, DemoArgs& args);

}  // namespace sonarmap::cli
