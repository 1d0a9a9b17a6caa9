#pragma once
// `sonarmap eval-trajectory`: an estimated vehicle track scored against the true one
// (eval/trajectory_error.hpp): ATE, RPE and final drift.

#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap eval-trajectory` as typed by the user.
struct EvalTrajectoryArgs {
  std::string estimate;     ///< navigation CSV or TUM trajectory (nav/tum_trajectory.hpp, readTrajectory)
  std::string truth;        ///< the same formats
  bool se3 = false;         ///< --se3: align in SE(3) rather than in the horizontal plane
  double segment_m = 10.0;  ///< --segment: the RPE's segment length, metres, > 0
};

/// Adds the `eval-trajectory` subcommand to `app`; its options fill `args`.
Command addEvalTrajectoryCommand(CLI::App& app, EvalTrajectoryArgs& args);

/// Reads both tracks (readTrajectory: navigation CSV or TUM, told apart by content), scores the
/// estimate and prints one `key value` line per metric on stdout, in this order: poses,
/// distance_m, ate_rmse_m, ate_max_m, ate_start_rmse_m, rpe_segments, rpe_rmse_m, rpe_yaw_rmse_deg, final_drift_m,
/// final_drift_pct (lengths in metres, angles in degrees; "nan" when not defined).
/// @throws FileError for an unreadable or malformed file; ValueError for tracks that share fewer
///         than 3 poses in time.
void runEvalTrajectory(const EvalTrajectoryArgs& args);

}  // namespace sonarmap::cli
