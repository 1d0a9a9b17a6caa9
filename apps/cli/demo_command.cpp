#include "demo_command.hpp"

#include <filesystem>

#include "map_command.hpp"
#include "map_outputs.hpp"
#include "output_dir.hpp"
#include "simulate_command.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"

namespace sonarmap::cli {
namespace {

void check(const DemoArgs& args) {
  if (std::filesystem::exists(args.output_dir) && !std::filesystem::is_directory(args.output_dir)) {
    throw ValueError("-o must name a folder, '" + args.output_dir + "' is a file");
  }
}

/// `map` with its defaults and every image, writing into `dir` under the name "tank".
MapArgs demoMapArgs(const OutputDir& dir, bool quiet) {
  MapArgs args;
  args.output_bt = dir.file("tank.bt");
  args.map_png = dir.file("tank.png");
  args.polar_png = dir.file("tank_polar.png");
  args.cartesian_png = dir.file("tank_cartesian.png");
  args.quiet = quiet;
  args.tank_report = true;
  return args;
}

void run(const DemoArgs& args) {
  MsisSimulationOptions simulation_options;  // static head, 28 turns, seed 1
  simulation_options.nav_rate_hz = 0.0;      // static: the map needs no navigation
  const MsisSimulation simulation = simulateMsis(builtinScene("tank"), simulation_options);
  OutputDir dir(args.output_dir);
  const MapArgs map_args = demoMapArgs(dir, args.quiet);
  const MapperOptions mapper_options = toMapperOptions(map_args);
  const MappedLog mapped = mapWithProgress(
      [&](const ProgressCallback& progress) { return mapSonarLog(simulation.log, mapper_options, progress); },
      args.quiet);
  FileTransaction outputs;
  stageMapOutputs(outputs, map_args, simulation.log, mapped.mapper.map(), mapped.mapper.map().resolution_m());
  stageSimulation(outputs, args.output_dir, simulation);
  outputs.commit();
  dir.keep();
  const std::vector<std::string> warnings =
      mappingWarnings(mapped.mapper.stats(), mapped.mapper.options(), mapped.mapper.map().resolution_m());
  printWarnings(warnings);
  printMapSummary(mapped, map_args.output_bt, false, warnings.size());
  printTankReport(mapped.mapper.map());
}

}  // namespace

Command addDemoCommand(CLI::App& app, DemoArgs& args) {
  CLI::App* cmd = app.add_subcommand("demo", "Simulate the built-in tank and map it (needs no data)");
  cmd->add_option("-o,--output", args.output_dir,
                  "Output folder (created when missing): tank.bt, tank.png, tank_polar.png, tank_cartesian.png, "
                  "beams.csv, scene.txt")
      ->required();
  cmd->add_flag("-q,--quiet", args.quiet, "No progress bar");
  return {cmd, [&args] { check(args); }, [&args] { run(args); }};
}

}  // namespace sonarmap::cli
