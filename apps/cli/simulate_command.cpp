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

constexpr double kDegree = std::numbers::pi / 180.0;

bool isBuiltinScene(const std::string& name) {
  const std::vector<std::string> names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

/// "a, b, c".
std::string joined(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}

/// A built-in name wins over a file of the same name (write ./tank for the file).
/// @throws ValueError (usage) when `scene` is neither a built-in name nor an existing file.
void checkScene(const std::string& scene) {
  if (isBuiltinScene(scene) || fs::exists(scene)) return;
  throw ValueError("unknown scene '" + scene + "': neither a built-in scene (" + joined(builtinSceneNames(), ", ") +
                   ") nor a scene file");
}

/// The simulation options of the arguments. @throws ValueError for a value out of range (usage).
MsisSimulationOptions toSimulationOptions(const SimulateArgs& args) {
  if (args.turns < 1) throw ValueError("--turns must be at least 1");
  if (!std::isfinite(args.speed_mps)) throw ValueError("--speed must be finite");
  if (!std::isfinite(args.heading_deg)) throw ValueError("--heading must be finite");
  if (!(std::isfinite(args.sector_deg) && args.sector_deg > 0.0 && args.sector_deg <= 360.0)) {
    throw ValueError("--sector must be in (0, 360] degrees");
  }
  if (!std::isfinite(args.sector_center_deg)) throw ValueError("--sector-center must be finite");
  const SonarPreset preset = sonarPreset(args.sonar);
  MsisSimulationOptions options;
  options.head = preset.head;
  options.echo = preset.echo;
  options.head.sector_width_rad = args.sector_deg == 360.0 ? 2.0 * std::numbers::pi : args.sector_deg * kDegree;
  options.head.sector_center_rad = args.sector_center_deg * kDegree;
  options.turns = args.turns;
  options.seed = args.seed;
  options.nav_rate_hz = args.nav_rate_hz;
  NavSample start;
  start.yaw_rad = args.heading_deg * std::numbers::pi / 180.0;
  const Eigen::Vector3d velocity_ned_mps(args.speed_mps * std::cos(start.yaw_rad),
                                         args.speed_mps * std::sin(start.yaw_rad), 0.0);
  options.trajectory = constantVelocityTrajectory(start, velocity_ned_mps);
  options.validate();
  return options;
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
  const Scene scene = isBuiltinScene(args.scene)
                          ? builtinScene(args.scene, head.range_m, head.vertical_beam_width_rad)
                          : readScene(args.scene);
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
