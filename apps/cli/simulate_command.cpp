#include "simulate_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include "output_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/scene_file.hpp"
#include "sonarmap/sim/trajectory.hpp"
#include "sonarmap/formats/beam_csv.hpp"

namespace sonarmap::cli {
namespace {

namespace fs = std::filesystem;

bool isBuiltinScene(const std::string& name) {
  const std::vector<std::string> names = builtinSceneNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

/// A built-in name wins over a file of the same name (write ./tank for the file).
/// @throws ValueError (usage) when `scene` is neither a built-in name nor an existing file.
void checkScene(const std::string& scene) {
  if (isBuiltinScene(scene) || fs::exists(scene)) return;
  std::string known;
  for (const std::string& name : builtinSceneNames()) known += (known.empty() ? "" : ", ") + name;
  throw ValueError("unknown scene '" + scene + "': neither a built-in scene (" + known + ") nor a scene file");
}

/// The simulation options of the arguments. @throws ValueError for a value out of range (usage).
MsisSimulationOptions toSimulationOptions(const SimulateArgs& args) {
  if (args.turns < 1) throw ValueError("--turns must be at least 1");
  if (!std::isfinite(args.speed_mps)) throw ValueError("--speed must be finite");
  if (!std::isfinite(args.heading_deg)) throw ValueError("--heading must be finite");
  MsisSimulationOptions options;
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
  const Scene scene = isBuiltinScene(args.scene) ? builtinScene(args.scene) : readScene(args.scene);
  const MsisSimulation simulation = simulateMsis(scene, options);
  OutputDir dir(args.output_dir);
  FileTransaction outputs;
  stageSimulation(outputs, args.output_dir, simulation);
  outputs.commit();
  dir.keep();
  std::printf("%zu beams in %zu turns, %zu nav fixes, %zu scene primitives -> %s\n", simulation.log.beams.size(),
              options.turns, simulation.nav.size(), simulation.scene.primitives.size(), args.output_dir.c_str());
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
      "simulate", "Simulate a Tritech Micron scanning a scene: DIR/beams.csv, DIR/nav.csv, DIR/scene.txt");
  cmd->add_option("scene", args.scene, "Built-in scene (tank | harbour) or a scene file (format: include/sonarmap/sim/scene_file.hpp)")->required();
  cmd->add_option("-o,--output", args.output_dir, "Output folder (created when missing)")->required();
  cmd->add_option("--seed", args.seed, "Seed of the speckle and noise: a seed always gives the same files")
      ->capture_default_str();
  cmd->add_option("--turns", args.turns, "Full 360-degree turns of the head (200 beams each)")->capture_default_str();
  cmd->add_option("--speed", args.speed_mps, "Vehicle speed in m/s along --heading (0: static)")->capture_default_str();
  cmd->add_option("--heading", args.heading_deg, "Vehicle heading in degrees clockwise from north")
      ->capture_default_str();
  cmd->add_option("--nav-rate", args.nav_rate_hz, "Navigation fixes per second in nav.csv; 0: no nav.csv")
      ->capture_default_str();
  auto options = std::make_shared<MsisSimulationOptions>();
  return {cmd, [&args, options] { check(args, *options); }, [&args, options] { run(args, *options); }};
}

}  // namespace sonarmap::cli
