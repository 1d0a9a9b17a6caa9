#pragma once
/// @file simulation_arguments.hpp
/// A simulated MSIS run as a user asks for it (`sonarmap simulate tank --sonar micron --turns 8`,
/// or the Python module's `simulate("tank", sonar="micron", turns=8)`): a head preset, degrees and
/// metres per second, and their checked conversion into MsisSimulationOptions. Shared by the
/// command-line tool and the Python module so both simulate the same run from the same arguments.

#include <cstddef>
#include <cstdint>
#include <string>

#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap {

/// The options of a simulated run in user units; each field's name is the command-line flag's.
struct SimulationArguments {
  std::string sonar = "micron";    ///< a head preset (sonarPresetNames); built-in scenes are built for its range
  double sector_deg = 360.0;       ///< width of the scanned sector, degrees, in (0, 360]; 360: continuous turns
  double sector_center_deg = 0.0;  ///< bearing of the sector's centre, degrees counter-clockwise from the sonar's x
  std::uint64_t seed = 1;          ///< seed of the speckle and noise
  std::size_t turns = 28;          ///< full turns of the head (passes across a sector), ≥ 1
  double speed_mps = 0.0;          ///< vehicle speed over ground along the heading, metres per second
  double heading_deg = 0.0;        ///< vehicle heading, degrees clockwise from north (NED yaw)
  double nav_rate_hz = 10.0;       ///< navigation fixes per second, ≥ 0; 0: no navigation track
};

/// The simulation options of the arguments: the preset's head and echo model, the sector, a
/// constant-velocity trajectory from the NED origin along the heading.
/// @throws ValueError naming the option (as its command-line flag) for a value out of range, or an
///         unknown preset (listing the names).
MsisSimulationOptions toSimulationOptions(const SimulationArguments& args);

/// True when `name` is one of builtinSceneNames() or builtinScene3dNames().
bool isBuiltinSceneName(const std::string& name);

/// The scene called `scene`: a built-in scene built for `head`'s range scale and vertical beam
/// width (a built-in name wins over a file of the same name: write ./tank for the file), else the
/// scene file of that path (scene_file.hpp).
/// @throws ValueError when `scene` is neither a built-in name nor an existing file (listing the
///         names); FileError as readScene for a bad scene file.
Scene sceneOf(const std::string& scene, const MsisHeadOptions& head);

}  // namespace sonarmap
