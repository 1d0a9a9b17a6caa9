#pragma once
// `sonarmap eval`: a map (.bt/.ot) scored against a ground-truth scene (eval/ground_truth.hpp) and,
// with --heard-by, against the surface its log's beams heard (eval_heard.hpp).

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "eval_heard.hpp"

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
  /// x,y,z,roll,pitch,yaw sextuples: the sonars' poses as navigation fixes of a sonar mounted with
  /// the identity (NED metres, Z-Y-X degrees as --mounting: pitch −25 is tilted 25° down);
  /// empty: --sensor's positions
  std::vector<double> sensor_pose;
  double vertical_aperture_deg = 0.0;  ///< --vertical-aperture, degrees (set: field-of-view check)
  std::string png;             ///< --png: the occupied voxels coloured by their distance to the truth
  bool quiet = false;          ///< -q: no progress bar
  HeardArgs heard;             ///< --heard-by, --nav, --mounting, --heard-level, --sonar
  std::string scoring;         ///< --scoring: a scoring file (eval_scoring_file.hpp) giving the options above
  std::vector<std::string> file_options;  ///< not an option: the flags the --scoring file gave
};

/// Adds the `eval` subcommand to `app`; its options fill `args`.
Command addEvalCommand(CLI::App& app, EvalArgs& args);

/// Turns the arguments into evaluation options: --sensor positions, or --sensor-pose poses (their
/// orientations enter the options only with --vertical-aperture, for the field-of-view check). An
/// option counts as given when the command line gave it or the --scoring file did
/// (args.file_options).
/// @throws ValueError for a bad value (usage): a count that is not a multiple of 3 (--sensor) or 6
///         (--sensor-pose), both given, a non-finite pose, an aperture outside (0, 180) degrees or
///         without --sensor-pose, or options GroundTruthOptions::validate rejects.
GroundTruthOptions toGroundTruthOptions(const CLI::App& cmd, const EvalArgs& args);

/// Reads the map and the scene (a scene file, or a built-in 2D or 3D scene's name), scores and
/// prints one line per metric on stdout:
///   precision P (occupied on surface / occupied)
///   recall R (found / visible surface voxels)
///   heard_recall, heard_f1, heard_surface: with `heard` (--heard-by), the map scored against the
///     surface the log's beams heard at the map's resolution (printHeardScore, eval_heard.hpp)
///   erosion E (free / visible surface voxels)
///   free_accuracy F (in water / free)
///   wall_error_mean_m M, wall_error_rms_m S (over N matched voxels)
///   surface_error_median_m D, p90_m Q (over every occupied voxel)
///   surface I KIND median_offset_m O (N voxels), one line per primitive with matched voxels
///   region z [A, B] m, range R m, tolerance T m
///   scored N occupied, M surface and K free voxels of MAP in S s [-> PNG]   (the summary line)
/// With args.png, also writes the top view (over the side view for a slab of several layers) of
/// the occupied voxels coloured by their distance to the truth (surfaceErrorFigure,
/// render/map_figures.hpp; the sensors drawn). A progress bar runs
/// on stderr while scoring when it is a terminal, unless args.quiet.
/// @throws sonarmap::Error for an unreadable map, scene, log or navigation file, a map with nothing
///         known in the slab, or a heard surface that cannot be made (scoreHeardSurface).
void runEval(const EvalArgs& args, const GroundTruthOptions& options, const std::optional<HeardRequest>& heard);

}  // namespace sonarmap::cli
