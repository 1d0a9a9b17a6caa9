#pragma once
// `sonarmap convert`: a sonar log (.mat, .V4LOG, beam .csv) → beam CSV (docs/formats.md).

#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap convert` as typed by the user.
struct ConvertArgs {
  std::string input;
  std::string output;
  std::string format = "auto";    ///< input format, or auto (by extension)
  double sound_speed_m_s = 1500;  ///< for wire captures written or read
};

/// Adds the `convert` subcommand to `app`; its options fill `args`.
Command addConvertCommand(CLI::App& app, ConvertArgs& args);

}  // namespace sonarmap::cli
