#pragma once
// A subcommand of the sonarmap tool: its CLI11 parser, a check of its arguments (usage errors,
// exit 2) and the work itself (data and output errors, exit 1).

#include <functional>

#include <CLI/CLI.hpp>

namespace sonarmap::cli {

struct Command {
  CLI::App* parser = nullptr;
  std::function<void()> check;  ///< throws sonarmap::Error for bad arguments
  std::function<void()> run;    ///< throws for bad data or a failed write
};

}  // namespace sonarmap::cli
