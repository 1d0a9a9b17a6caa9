#pragma once
// `sonarmap simulate`: a simulated MSIS run (sim/msis_simulator.hpp) of a head preset
// (sim/sonar_presets.hpp) written as a beam CSV, its navigation CSV and its ground-truth scene file.

#include <cstddef>
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"

#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap simulate` as typed by the user.
struct SimulateArgs {
  std::string scene;  ///< a built-in scene name (builtinSceneNames) or a scene file (scene_file.hpp)
  std::string output_dir;
  std::string sonar = "micron";  ///< a head preset (sonarPresetNames); built-in scenes are built for its range
  double sector_deg = 360.0;     ///< width of the scanned sector, degrees, in (0, 360]; 360: continuous turns
  double sector_center_deg = 0.0;  ///< bearing of the sector's centre, degrees counter-clockwise from the sonar's x
  std::uint64_t seed = 1;
  std::size_t turns = 28;   ///< full turns of the head (passes across a sector), ≥ 1 (28: as many as the CRAS log)
  double speed_mps = 0.0;   ///< vehicle speed over ground, metres per second
  double heading_deg = 0.0; ///< vehicle heading, degrees clockwise from north (NED yaw)
  double nav_rate_hz = 10.0;///< navigation fixes per second, ≥ 0; 0 writes no nav.csv
  bool quiet = false;       ///< -q: no progress bar
};

/// Adds the `simulate` subcommand to `app`; its options fill `args`.
Command addSimulateCommand(CLI::App& app, SimulateArgs& args);

/// Stages the files of a simulated run in `outputs`: `dir`/beams.csv (beam CSV, docs/formats.md),
/// `dir`/nav.csv (navigation CSV, only when `run.nav` is not empty) and `dir`/scene.txt
/// (scene_file.hpp). @throws FileError when a file cannot be staged.
void stageSimulation(FileTransaction& outputs, const std::string& dir, const MsisSimulation& run);

}  // namespace sonarmap::cli
