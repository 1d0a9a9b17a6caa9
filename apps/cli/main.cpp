// sonarmap: sonar logs → probabilistic occupancy octrees.
// Exit codes: 0 success, 1 bad data or failed output, 2 bad usage. Errors are one line on stderr.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "map_command.hpp"
#include "sonarmap/core/errors.hpp"

namespace {

int fail(int code, const char* message) {
  std::fprintf(stderr, "sonarmap: error: %s\n", message);
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sonarmap: probabilistic 3D occupancy maps from mechanically scanned imaging sonar"};
  app.require_subcommand(1);
  sonarmap::cli::MapArgs map_args;
  CLI::App* map_cmd = sonarmap::cli::addMapCommand(app, map_args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    return fail(2, error.what());
  }
  sonarmap::MapperOptions options;
  try {
    if (map_cmd->parsed()) options = sonarmap::cli::toMapperOptions(map_args);
  } catch (const sonarmap::Error& error) {
    return fail(2, error.what());
  }
  try {
    if (map_cmd->parsed()) sonarmap::cli::runMap(map_args, options);
  } catch (const std::exception& error) {
    return fail(1, error.what());
  }
  return 0;
}
