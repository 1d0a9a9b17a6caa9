// The full sonarmap tool (sonarmap-full): every command. Users run `sonarmap` (lean_main.cpp), which
// runs `cloud` itself and hands everything else to this executable with the same arguments.
// Exit codes: 0 success, 1 bad data or failed output, 2 bad usage. Errors are one line on stderr.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cloud_command.hpp"
#include "convert_command.hpp"
#include "demo_command.hpp"
#include "emulate_command.hpp"
#include "eval_command.hpp"
#include "eval_trajectory_command.hpp"
#include "help_groups.hpp"
#include "info_command.hpp"
#include "live_command.hpp"
#include "localize_command.hpp"
#include "map_command.hpp"
#include "run_command.hpp"
#include "simulate_command.hpp"
#include "suggest.hpp"
#include "version.hpp"
#include "view_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"sonarmap: probabilistic 3D occupancy maps from mechanically scanned imaging sonar and point clouds"};
  app.set_version_flag("--version", sonarmap::cli::kVersionLine);
  app.require_subcommand(1);
  // Every option's help is one line (details: docs/commands.md); the widest option name fits the
  // column, so each option stays on one line. The subcommands share this formatter.
  auto formatter = std::make_shared<sonarmap::cli::GroupedHelpFormatter>();
  formatter->column_width(44);
  app.formatter(formatter);
  app.footer("Options of a command: sonarmap COMMAND --help; all of them in detail: docs/commands.md");
  sonarmap::cli::MapArgs map_args;
  sonarmap::cli::CloudArgs cloud_args;
  sonarmap::cli::ConvertArgs convert_args;
  sonarmap::cli::SimulateArgs simulate_args;
  sonarmap::cli::DemoArgs demo_args;
  sonarmap::cli::EvalArgs eval_args;
  sonarmap::cli::EvalTrajectoryArgs eval_trajectory_args;
  sonarmap::cli::LiveArgs live_args;
  sonarmap::cli::EmulateArgs emulate_args;
  sonarmap::cli::LocalizeArgs localize_args;
  sonarmap::cli::ViewArgs view_args;
  sonarmap::cli::InfoArgs info_args;
  const std::vector<sonarmap::cli::Command> commands{sonarmap::cli::addMapCommand(app, map_args),
                                                     sonarmap::cli::addInfoCommand(app, info_args),
                                                     sonarmap::cli::addLiveCommand(app, live_args),
                                                     sonarmap::cli::addEmulateCommand(app, emulate_args),
                                                     sonarmap::cli::addCloudCommand(app, cloud_args),
                                                     sonarmap::cli::addConvertCommand(app, convert_args),
                                                     sonarmap::cli::addSimulateCommand(app, simulate_args),
                                                     sonarmap::cli::addDemoCommand(app, demo_args),
                                                     sonarmap::cli::addEvalCommand(app, eval_args),
                                                     sonarmap::cli::addEvalTrajectoryCommand(app, eval_trajectory_args),
                                                     sonarmap::cli::addLocalizeCommand(app, localize_args),
                                                     sonarmap::cli::addViewCommand(app, view_args)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForVersion& version) {
    return app.exit(version);
  } catch (const CLI::ParseError& error) {
    return sonarmap::cli::fail(2, sonarmap::cli::parseErrorMessage(app, std::vector<std::string>(argv + 1, argv + argc), error).c_str());
  }
  for (const sonarmap::cli::Command& command : commands) {
    if (command.parser->parsed()) return sonarmap::cli::runCommand(command);
  }
  return 0;
}
