#include "eval_trajectory_command.hpp"

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
      "Score an estimated vehicle track against the true one: ATE (after a rigid alignment, and with the start positions "
      "matched), RPE over segments and final drift; one 'key value' line each");
  cmd->add_option("estimate", args.estimate,
                  "Estimated track: navigation CSV (time_s,x_m,...) or TUM trajectory (time x y z qx qy qz qw), "
                  "NED, told apart by content")
      ->required();
  cmd->add_option("--truth", args.truth, "True track, navigation CSV or TUM (e.g. sonarmap simulate's truth_nav.csv)")
      ->required();
  cmd->add_flag("--se3", args.se3,
                "Align in SE(3) (3D rotation and translation) for the ATE; default SE(2): in the horizontal plane, "
                "depth unaligned");
  cmd->add_option("--segment", args.segment_m, "RPE segment: distance the truth travels, m, > 0")
      ->capture_default_str();
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
