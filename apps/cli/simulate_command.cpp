#include "simulate_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include "output_dir.hpp"
#include "progress.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/scene_file.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sim/trajectory.hpp"
#include "sonarmap/formats/beam_csv.hpp"

namespace sonarmap::cli {
namespace {

namespace fs = std::filesystem;

/// "a, b, c".
std::string joined(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}

/// A built-in name wins over a file of the same name (write ./tank for the file).
/// @throws ValueError (usage) when `scene` is neither a built-in name nor an existing file.
void checkScene(const std::string& scene) {
  if (isBuiltinSceneName(scene) || fs::exists(scene)) return;
  throw ValueError("unknown scene '" + scene + "': neither a built-in scene (" + joined(builtinSceneNames(), ", ") +
                   ") nor a scene file");
}

void check(const SimulateArgs& args, MsisSimulationOptions& options) {
  checkScene(args.scene);
  if (fs::exists(args.output_dir) && !fs::is_directory(args.output_dir)) {
    throw ValueError("-o must name a folder, '" + args.output_dir + "' is a file");
  }
  options = toSimulationOptions(args);
}

void run(const SimulateArgs& args, const MsisSimulationOptions& options) {
  const MsisHeadOptions& head = options.head;
  const Scene scene = sceneOf(args.scene, head);
  const MsisSimulation simulation = [&] {
    ProgressBar bar("simulating");
    return simulateMsis(scene, options, [&](std::size_t done, std::size_t total) {
      if (!args.quiet) bar.update(done, total);
    });
  }();
  OutputDir dir(args.output_dir);
  FileTransaction outputs;
  stageSimulation(outputs, args.output_dir, simulation);
  outputs.commit();
  dir.keep();
  char turns[64] = "turns";
  if (head.isSector()) std::snprintf(turns, sizeof turns, "passes across a %g deg sector", args.sector_deg);
  std::printf("%s: %zu beams in %zu %s, %zu nav fixes, %zu scene primitives -> %s\n", args.sonar.c_str(),
              simulation.log.beams.size(), options.turns, turns, simulation.nav.size(),
              simulation.scene.primitives.size(), args.output_dir.c_str());
}

/// The --sonar option's help: every preset with its one-line description.
std::string sonarHelp() {
  std::string help = "Sonar head preset; built-in scenes are built for its range scale:";
  for (const std::string& name : sonarPresetNames()) help += "\n  " + name + ": " + sonarPreset(name).description;
  return help;
}

}  // namespace

void stageSimulation(FileTransaction& outputs, const std::string& dir, const MsisSimulation& run) {
  const fs::path folder(dir);
  outputs.stage((folder / "scene.txt").string(), [&](std::ostream& out) { writeScene(out, run.scene); });
  outputs.stage((folder / "beams.csv").string(), [&](std::ostream& out) { writeBeamCsv(out, run.log); });
  if (!run.nav.empty()) {
    outputs.stage((folder / "nav.csv").string(), [&](std::ostream& out) { writeNavCsv(out, run.nav); });
  }
}

Command addSimulateCommand(CLI::App& app, SimulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Simulate a mechanically scanned sonar (default: the Tritech Micron) scanning a scene: DIR/beams.csv, "
                  "DIR/nav.csv, DIR/scene.txt");
  cmd->add_option("scene", args.scene,
                  "Built-in scene (" + joined(builtinSceneNames(), " | ") +
                      "), sized for the sonar's range, or a scene file in metres (format: "
                      "include/sonarmap/sim/scene_file.hpp)")
      ->required();
  cmd->add_option("-o,--output", args.output_dir, "Output folder (created when missing)")->required();
  cmd->add_option("--sonar", args.sonar, sonarHelp())->capture_default_str();
  cmd->add_option("--sector", args.sector_deg,
                  "Width of the scanned sector in degrees, (0, 360]; less than 360: the head sweeps back and forth "
                  "across it")
      ->capture_default_str();
  cmd->add_option("--sector-center", args.sector_center_deg,
                  "Bearing of the sector's centre in degrees, counter-clockwise from the sonar's forward axis")
      ->capture_default_str();
  cmd->add_option("--seed", args.seed, "Seed of the speckle and noise: a seed always gives the same files")
      ->capture_default_str();
  cmd->add_option("--turns", args.turns,
                  "Full 360-degree turns of the head (the Micron: 200 beams each), or passes across a sector")
      ->capture_default_str();
  cmd->add_option("--speed", args.speed_mps, "Vehicle speed in m/s along --heading (0: static)")->capture_default_str();
  cmd->add_option("--heading", args.heading_deg, "Vehicle heading in degrees clockwise from north")
      ->capture_default_str();
  cmd->add_option("--nav-rate", args.nav_rate_hz, "Navigation fixes per second in nav.csv; 0: no nav.csv")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", args.quiet, "No progress bar");
  auto options = std::make_shared<MsisSimulationOptions>();
  return {cmd, [&args, options] { check(args, *options); }, [&args, options] { run(args, *options); }};
}

}  // namespace sonarmap::cli
