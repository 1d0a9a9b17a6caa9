#pragma once
/// @file heard_surface.hpp
/// The surface a log's beams could hear, as a map, and a map scored against it.
///
/// The heard surface is an oracle for the 3D accuracy missions (simulated_mission.hpp) and for any
/// log a simulated head recorded in a known scene: scored like a mapped log (evaluateAgainstScene
/// with missionTruthOptions), its recall bounds what any map of that log can reach with a detector
/// that needs a surface's mean echo that far above the receiver's floor (sim/echo_levels.hpp), and
/// its precision is 1 up to the voxel grid: every occupied voxel holds a surface point. F1 ≤ 2R /
/// (1 + R) follows for any map whose recall is bounded by R: how far the 3D targets can be
/// reached. scoreAgainstHeardSurface() turns it round: a map's recall measured over the heard
/// surface only, not over every surface the sonar could geometrically see.
///
/// Method: for every beam of the log, from the head's true pose at the beam's time, a grid of rays
/// spans the echo model's whole ray extent (EchoModelOptions::horizontal and vertical: extent × the
/// beam widths), at most one voxel apart at the head's range. A ray's first surface within the
/// range is kept when that primitive's echo in the bin of the ray's range is at least
/// `min_level_db` over the floor (EchoLevels::levels); its voxel is marked occupied once. The grid
/// is finer than the echo model's own rays, so a surface the model lights between its rays is
/// found too; the levels are the model's.

#include <cstddef>
#include <limits>

#include <Eigen/Geometry>

#include "sonarmap/core/progress.hpp"
#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/scene.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Options of heardSurfaceMap().
struct HeardSurfaceOptions {
  double resolution_m = 0.05;  ///< the map's voxel edge, metres, > 0
  /// A surface point is kept where its primitive's echo in the point's bin is at least this many
  /// dB over the floor; −infinity keeps every surface point a ray meets (the geometry alone).
  double min_level_db = 0.0;

  /// @throws ValueError when resolution_m is not a finite number > 0 or min_level_db is NaN or +∞.
  void validate() const;
};

/// What heardSurfaceMap() found besides the map.
struct HeardSurfaceStats {
  std::size_t beams = 0;        ///< beams of the log traced
  std::size_t beams_without_nav = 0;  ///< beams skipped: their time lies outside the navigation's span
  std::size_t rays = 0;         ///< rays cast in all
  std::size_t surface_hits = 0; ///< rays that met a surface within the range
  std::size_t heard_hits = 0;   ///< of those, at least min_level_db over the floor
  std::size_t voxels = 0;       ///< occupied voxels of the map: the heard points' voxels
};

/// The heard surface of a log on disk (see the file's comment) as an octree at
/// options.resolution_m whose occupied voxels are the heard points' voxels (one hit each) and which
/// holds nothing else. Frames: map (NWU, z up; navigation.hpp), as mapSonarLog places the beams.
/// @param log            the beams (times on the navigation's clock, bearings in the sonar frame,
///                       beam.hpp), e.g. readSonarLog of the log `sonarmap map` reads.
/// @param true_nav       the vehicle's TRUE navigation (NED metres, radians; navigation.hpp), e.g.
///                       readNavCsv of a simulation's truth_nav.csv; each beam is traced from
///                       nedToMap() · interpolateBodyToNed(true_nav, beam time) · sonar_to_body, and a
///                       beam outside [first fix, last fix] is skipped and counted
///                       (HeardSurfaceStats::beams_without_nav). Empty: the sonar is static at the
///                       map origin with the identity pose, as mapSonarLog without navigation and
///                       `sonarmap map` without --nav place it (sonar_to_body is then unused).
/// @param sonar_to_body  the sonar's mounting: sonar frame → body frame (FRD), e.g.
///                       sonarToBodyOfMounting of `map --mounting`'s six numbers
///                       (mapping_arguments.hpp).
/// @param scene          the scene the log was recorded in (map frame, metres).
/// @param head, echo     the simulator's head and echo model that recorded the log (a SonarPreset's,
///                       sim/sonar_presets.hpp): range, bins, beam widths, pattern, levels.
/// `stats`, when given, receives the counts; `progress`, when set, is called after each beam
/// (beams done, beams of the log).
/// @throws ValueError for invalid options, head or echo options or scene (EchoLevels), an invalid
///         navigation track (interpolateBodyToNed's rules), a beam whose bin length differs from the
///         head's (range_m / bins, relative 1e-6: the log was not recorded by that head), or when no
///         point is heard (an empty map cannot be scored).
OcTree16 heardSurfaceMap(const SonarLog& log, const NavTrack& true_nav, const Eigen::Isometry3d& sonar_to_body,
                         const Scene& scene, const MsisHeadOptions& head, const EchoModelOptions& echo,
                         const HeardSurfaceOptions& options, HeardSurfaceStats* stats = nullptr,
                         const ProgressCallback& progress = {});

/// The heard surface of a simulated mission: the general form above with the run's log, its true
/// navigation (run.simulation.nav, the fixes a truth_nav.csv holds; a run simulated without
/// navigation, nav_rate_hz 0, is heard as a static log), mounting (run.options.sonar_to_body),
/// scene, head and echo model.
/// @throws ValueError as the general form.
OcTree16 heardSurfaceMap(const MissionRun& run, const HeardSurfaceOptions& options,
                         HeardSurfaceStats* stats = nullptr);

/// A map scored against the heard surface of its log (scoreAgainstHeardSurface).
struct HeardSurfaceScore {
  std::size_t heard_voxels = 0;        ///< occupied voxels of the heard-surface map
  std::size_t heard_voxels_found = 0;  ///< of those, with an occupied voxel of the map within T
  double recall = 0.0;                 ///< heard recall: heard_voxels_found / heard_voxels
  double precision = 0.0;              ///< the map's precision against the scene (GroundTruthReport)
  double f1 = 0.0;                     ///< heard F1: 2 · precision · recall / (precision + recall), 0 when both are 0
};

/// Scores `map` against `heard`, the heard surface of the log it was made from (heardSurfaceMap at
/// the map's resolution). `truth` is evaluateAgainstScene's report of the same map; its precision
/// and its definitions stay as they are (ground_truth.hpp). Definitions (map frame, metres; a voxel
/// is a finest voxel, pruned leaves expanded, at its centre):
///  - T = truth.tolerance_m: the tolerance evaluateAgainstScene used, max(tolerance, √3 · res).
///  - Map voxels: the occupied voxels of `map` whose centre z lies in [truth.z_min_m,
///    truth.z_max_m] (the evaluated slab: the voxels precision counts).
///  - Heard voxels: every occupied voxel of `heard`.
///  - Heard recall = heard voxels with a map voxel whose centre is within T of theirs / heard voxels.
///  - Heard F1 = 2 P R / (P + R) with P = truth.precision and R the heard recall; 0 when both are 0.
/// A map with no occupied voxel scores recall 0. Cost: heard voxels × (2 T / res)³ hash look-ups.
/// @throws ValueError when the two maps' resolutions differ, `heard` has no occupied voxel, or
///         truth.tolerance_m is not a finite number > 0.
HeardSurfaceScore scoreAgainstHeardSurface(const OcTree16& map, const GroundTruthReport& truth, const OcTree16& heard);

}  // namespace sonarmap
