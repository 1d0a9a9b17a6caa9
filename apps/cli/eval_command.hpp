#pragma once
// `sonarmap eval`: a map (.bt/.ot) scored against a ground-truth scene (eval/ground_truth.hpp).

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"

#include "sonarmap/eval/ground_truth.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap eval` as typed by the user.
struct EvalArgs {
  std::string map;
  std::string truth;           ///< scene file, or a built-in scene's name when no such file exists
  std::vector<double> z_m;     ///< --z-min, --z-max as given (empty: unset)
  double z_min_m = 0.0, z_max_m = 0.0;
  double tolerance_m = 0.1;
  double max_range_m = 0.0;    ///< 0: the map's reach
  std::vector<double> sensor;  ///< x,y,z triples, map frame; empty: the origin
};

/// Adds the `eval` subcommand to `app`; its options fill `args`.
Command addEvalCommand(CLI::App& app, EvalArgs& args);

/// Turns the arguments into evaluation options. @throws ValueError for a bad value (usage).
GroundTruthOptions toGroundTruthOptions(const CLI::App& cmd, const EvalArgs& args);

/// Reads the map and the scene, scores and prints one line per metric on stdout:
///   precision P (occupied on surface / occupied)
///   recall R (found / visible surface voxels)
///   free_accuracy F (in water / free)
///   wall_error_mean_m M, wall_error_rms_m S (over N matched voxels)
///   surface I KIND median_offset_m O (N voxels), one line per primitive with matched voxels
///   region z [A, B] m, range R m, tolerance T m
/// @throws sonarmap::Error for an unreadable map or scene, or a map with nothing known in the slab.
void runEval(const EvalArgs& args, const GroundTruthOptions& options);

}  // namespace sonarmap::cli
