#pragma once
// `sonarmap simulate`: a simulated MSIS run (sim/msis_simulator.hpp) of a head preset
// (sim/sonar_presets.hpp) written as a beam CSV, its navigation CSVs (believed and true) and its
// ground-truth scene file.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"

#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/nav/map_frame_axes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap simulate` as typed by the user: the run's options (SimulationArguments,
/// shared with the Python module's simulate) plus the scene and the output folder.
struct SimulateArgs : SimulationArguments {
  std::string scene;  ///< a built-in scene name or a scene file (sceneOf)
  std::string output_dir;
  bool no_position = false;  ///< --no-position: nav.csv and the logs hold no north and east (a vehicle without a DVL)
  bool quiet = false;  ///< -q: no progress bar
  std::string bag;     ///< --bag: also the log and its believed navigation as a ROS 1 bag (empty: none)
  std::string mcap;    ///< --mcap: also as a ROS 2 log in MCAP (empty: none)
  MapFrame map_frame = kDefaultMapFrame;  ///< --map-frame: the frame scene.txt is written in
  std::string geo_origin;  ///< --geo-origin LAT,LON[,H]: with --bag, the NED zero on the Earth (NavSatFix written)
};

/// Adds the `simulate` subcommand to `app`; its options fill `args`.
Command addSimulateCommand(CLI::App& app, SimulateArgs& args);

/// Stages the files of a simulated run in `outputs`, in this order: `dir`/scene.txt
/// (scene_file.hpp, its coordinates in `scene_frame`: the frame the run's map is written in),
/// `dir`/beams.csv (beam CSV, docs/formats.md), and when `run.nav` is not empty
/// `dir`/nav.csv (navigation CSV: the dead-reckoning track the vehicle believes,
/// run.dead_reckoning, when the run has one, else the true track) and `dir`/truth_nav.csv
/// (navigation CSV of the true track, run.nav). @throws FileError when a file cannot be staged.
void stageSimulation(FileTransaction& outputs, const std::string& dir, const MsisSimulation& run,
                     MapFrame scene_frame);

/// A --sonar option's one-line help: `lead`, then every head preset's name (sonarPresetNames)
/// joined by " | " (what each head is: docs/commands.md).
std::string sonarPresetHelp(const std::string& lead);

/// `names` joined with `separator` between them, for help texts and messages.
std::string joined(const std::vector<std::string>& names, const char* separator);

/// Adds the vehicle's path options shared by `simulate` and `emulate` (help group Navigation):
/// --speed (m/s), --heading (degrees cw from north), --depth (m, NED), --mission, --laps and
/// --mounting, filling the fields of `args` of those names (simulation_arguments.hpp).
void addVehiclePathOptions(CLI::App& cmd, SimulationArguments& args);

}  // namespace sonarmap::cli
