#pragma once
// The scoring file: what `sonarmap eval` needs to score a simulated mission's map as
// docs/accuracy.md does (the truth, the sonar's poses, its aperture and reach, the log and the true
// navigation for the heard surface), written by `sonarmap demo` beside the map so that
// `sonarmap eval MAP --scoring FILE` needs no pasted poses.
//
// The file is one JSON object whose keys are eval's options without their dashes, each value as the
// option takes it; file names are relative to the scoring file's folder:
//   {"truth": "scene.txt", "max-range": 5, "vertical-aperture": 35,
//    "sensor-pose": [[x, y, z, roll, pitch, yaw], ...],   (NED m, degrees: eval --sensor-pose)
//    "heard-by": "beams.csv", "nav": "truth_nav.csv", "mounting": [0, 0, 0, 0, -25, 0], "sonar": "micron"}

#include <array>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "eval_command.hpp"

namespace sonarmap::cli {

/// What a scoring file holds; file names as written (relative to the file's folder).
struct ScoringFile {
  std::string truth;                              ///< scene file
  double max_range_m = 0.0;                       ///< eval --max-range
  double vertical_aperture_deg = 0.0;             ///< eval --vertical-aperture
  std::vector<std::array<double, 6>> sensor_poses;  ///< eval --sensor-pose, one per pose
  std::string heard_by;                           ///< the log (eval --heard-by)
  std::string nav;                                ///< its TRUE navigation CSV (eval --nav)
  std::array<double, 6> mounting{};               ///< eval --mounting: X,Y,Z m, ROLL,PITCH,YAW degrees
  std::string sonar;                              ///< the head preset that recorded the log (eval --sonar)
};

/// Writes `file` as the JSON object above (numbers written so that they read back exactly).
void writeScoringFile(std::ostream& out, const ScoringFile& file);

/// Reads the scoring file at `path` into `args`, for each of its options the command line `cmd`
/// did not give (the command line wins), and records them in args.file_options; file names are
/// taken relative to `path`'s folder (a truth that names no file there stays a built-in scene's name).
/// @throws ValueError for an unreadable file, a file that is not such an object, an unknown key
///         (naming the keys accepted) or a value of the wrong kind.
void applyScoringFile(const std::string& path, const CLI::App& cmd, EvalArgs& args);

}  // namespace sonarmap::cli
