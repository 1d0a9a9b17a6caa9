// sonarmap: sonar logs and point clouds → probabilistic occupancy octrees.
// This executable links only what `sonarmap cloud` needs (sonarmap::octree, algorithms, io and
// CLI11), so a point cloud pays no other component's start-up (OpenCV, HDF5, Boost, Ceres, GDAL...:
// docs/performance.md, "Point-cloud workloads"). It runs a well-formed `sonarmap cloud ...` and a
// bare `sonarmap --version` itself; every other command line, and any `cloud` line that asks for help
// or does not parse, goes unchanged to the full tool (main.cpp, sonarmap-full), which prints the
// same help and errors as always.
// Exit codes: 0 success, 1 bad data or failed output, 2 bad usage. Errors are one line on stderr.
#include <cstdio>
#include <string_view>

#include <CLI/CLI.hpp>

#include "cloud_command.hpp"
#include "full_tool.hpp"
#include "run_command.hpp"
#include "version.hpp"

int main(int argc, char** argv) {
  if (argc == 2 && std::string_view(argv[1]) == "--version") {
    std::printf("%s\n", sonarmap::cli::kVersionLine);  // as CLI11's version flag prints it (stdout, exit 0)
    return 0;
  }
  if (argc < 2 || std::string_view(argv[1]) != "cloud") return sonarmap::cli::execFullTool(argv);
  CLI::App app;
  app.require_subcommand(1);
  sonarmap::cli::CloudArgs cloud_args;
  const sonarmap::cli::Command cloud = sonarmap::cli::addCloudCommand(app, cloud_args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Error&) {  // help, or a usage error: the full tool words it as always
    return sonarmap::cli::execFullTool(argv);
  }
  return sonarmap::cli::runCommand(cloud);
}
