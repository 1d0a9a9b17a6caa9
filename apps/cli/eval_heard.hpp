#pragma once
// `sonarmap eval --heard-by`: a map's recall measured over the surface the log's beams heard
// (eval/heard_surface.hpp), beside eval's scores against the whole scene.

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <Eigen/Geometry>

#include "sonarmap/eval/heard_surface.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap::cli {

/// The heard-surface options of `sonarmap eval` as typed by the user.
struct HeardArgs {
  std::string beams;             ///< --heard-by: the log (any log `sonarmap map` reads); empty: not asked
  std::string nav_csv;           ///< --nav: the TRUE navigation CSV; empty: the sonar static at the map origin
  std::vector<double> mounting;  ///< --mounting X,Y,Z (m), ROLL,PITCH,YAW (degrees); empty: the default
  std::string level_db = "0";    ///< --heard-level: dB over the receiver's floor, or -inf / any
  std::string sonar = "micron";  ///< --sonar: the simulator preset that recorded the log
};

/// The heard-surface options, checked.
struct HeardRequest {
  std::string beams;                ///< the log's path
  std::string nav_csv;              ///< the true navigation's path; empty: static
  Eigen::Isometry3d sonar_to_body;  ///< sonar frame → body frame (FRD), sonarToBodyOfMounting
  double min_level_db = 0.0;        ///< dB over the floor; −infinity: the geometry alone
  SonarPreset preset;               ///< the head and echo model that recorded the log
};

/// Adds --heard-by, --nav, --mounting, --heard-level and --sonar to `cmd`; they fill `args`.
void addHeardOptions(CLI::App& cmd, HeardArgs& args);

/// `text` as --heard-level's dB over the floor: a finite number, or -inf or any (−infinity: every
/// surface point a ray meets counts, the geometry alone).
/// @throws ValueError (usage) for anything else (+inf, nan, not a number).
double parseHeardLevel(const std::string& text);

/// The checked request, or nullopt without --heard-by.
/// @throws ValueError (usage) when --nav, --mounting, --heard-level or --sonar is given without
///         --heard-by, --mounting without --nav, a bad level (parseHeardLevel), an unknown preset,
///         or a mounting sonarToBodyOfMounting rejects.
std::optional<HeardRequest> toHeardRequest(const CLI::App& cmd, const HeardArgs& args);

/// Reads the request's log (its format by its extension, as `sonarmap map`) and navigation,
/// computes their heard surface in `scene` at `resolution_m` (the map's) and scores `map` against it
/// (scoreAgainstHeardSurface), drawing a progress bar on stderr unless `quiet`.
/// @return the score and, through `stats`, the heard surface's counts.
/// @throws sonarmap::Error for an unreadable log or navigation file, a log the preset's head did
///         not record, or when nothing is heard.
HeardSurfaceScore scoreHeardSurface(const HeardRequest& request, const Scene& scene, const OcTree16& map,
                                    const GroundTruthReport& truth, bool quiet, HeardSurfaceStats& stats);

/// Prints eval's heard-surface lines on stdout:
///   heard_recall R (F of N heard surface voxels mapped)
///   heard_f1 F (precision P, heard recall R)
///   heard_surface N voxels: echoes >= L dB over the floor (or: every surface a ray meets) by the
///     PRESET head, B beams traced (K without navigation)
void printHeardScore(const HeardRequest& request, const HeardSurfaceScore& score, const HeardSurfaceStats& stats);

}  // namespace sonarmap::cli
