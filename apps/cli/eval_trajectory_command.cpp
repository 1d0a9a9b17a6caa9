#include "eval_trajectory_command.hpp"

#include "help_groups.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/trajectory_error.hpp"
#include "sonarmap/nav/tum_trajectory.hpp"

namespace sonarmap::cli {

Command addEvalTrajectoryCommand(CLI::App& app, EvalTrajectoryArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "eval-trajectory",
      "Score a vehicle track against the true one: ATE, RPE, final drift");
  cmd->add_option("estimate", args.estimate, "Estimated track: navigation CSV or TUM (NED)")->required();
  cmd->add_option("--truth", args.truth, "True track: navigation CSV or TUM (e.g. truth_nav.csv)")
      ->required()
      ->group(help_group::kInput);
  cmd->add_flag("--se3", args.se3, "Align in SE(3) for the ATE (default SE(2), depth unaligned)")
      ->group(help_group::kScoring);
  cmd->add_option("--segment", args.segment_m, "RPE segment: distance the truth travels (m, > 0)")
      ->capture_default_str()
      ->group(help_group::kScoring);
  auto check = [&args] {
    if (!(std::isfinite(args.segment_m) && args.segment_m > 0.0)) {
      throw ValueError("--segment must be a number > 0 (metres)");
    }
  };
  return {cmd, check, [&args] { runEvalTrajectory(args); }};
}

void runEvalTrajectory(const EvalTrajectoryArgs& args) {
  const NavTrack estimate = readTrajectory(args.estimate);
  const NavTrack truth = readTrajectory(args.truth);
  TrajectoryErrorOptions options;
  options.se3 = args.se3;
  options.segment_m = args.segment_m;
  const TrajectoryError e = evaluateTrajectory(estimate, truth, options);
  std::printf("poses %zu\n", e.poses);
  std::printf("distance_m %.4f\n", e.distance_m);
  std::printf("ate_rmse_m %.4f\n", e.ate_rmse_m);
  std::printf("ate_max_m %.4f\n", e.ate_max_m);
  std::printf("ate_start_rmse_m %.4f\n", e.ate_start_rmse_m);
  std::printf("rpe_segments %zu\n", e.rpe_segments);
  std::printf("rpe_rmse_m %.4f\n", e.rpe_rmse_m);
  std::printf("rpe_yaw_rmse_deg %.4f\n", e.rpe_yaw_rmse_deg);
  std::printf("final_drift_m %.4f\n", e.final_drift_m);
  std::printf("final_drift_pct %.4f\n", e.final_drift_pct);
}

}  // namespace sonarmap::cli
