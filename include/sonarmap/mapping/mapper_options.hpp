#pragma once
/// @file mapper_options.hpp
/// Everything that turns beams into map updates (MapperOptions), and the values the mapper
/// derives from a log when an option is left on "auto": the map's resolution from the log's reach,
/// and the estimate of the work each beam asks for, checked against a budget before mapping.

#include <cstddef>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/detection/extended_returns.hpp"
#include "sonarmap/mapping/sweep_fan.hpp"
#include "sonarmap/mapping/volume_inversion.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/beam_source.hpp"
#include "sonarmap/sonar/log_survey.hpp"
#include "sonarmap/sonar/preprocess.hpp"
#include "sonarmap/sonar/range_scales.hpp"

namespace sonarmap {

/// Which voxel traversal turns a beam into cells (paper §6).
enum class RayAlgorithm {
  kDDA,        ///< Amanatides & Woo (1987): face-connected, every crossed voxel (default)
  kBresenham,  ///< 3D Bresenham on keys: 26-connected, "laser-like" (the paper's choice)
};

/// Parses "dda" or "bresenham". @throws ValueError for any other name.
RayAlgorithm parseRayAlgorithm(std::string_view name);

/// Which volume a beam updates (the inverse sensor model's geometry).
enum class BeamModel {
  /// The sonar's plane (z = 0 of the sonar frame): wedges and arcs, a 2D map (paper §6–§8).
  kPlanar,
  /// The whole beam: the loud core of the cone of horizontal width × vertical aperture is free up to
  /// the obstacle, and the obstacle is a vertical face across both, weighted by the beam pattern
  /// (docs/mapping.md; Moravec & Elfes 1985, Elfes 1987, Fairfield et al. 2007, Ribas et al.
  /// 2008). A 3D map once the vehicle moves, turns or tilts the sonar.
  kVolume,
  /// The whole beam by the forward model inverted jointly over many beams (volume_inversion.hpp):
  /// the level surfaces as kVolume maps them (level_surfaces.hpp), their expected echoes explained
  /// first, and what stands in the water as voxel reflectivities explaining the rest of each range
  /// cell's power. A 3D map; docs/mapping.md.
  kInversion,
};

/// Parses "planar", "volume" or "inversion". @throws ValueError for any other name.
BeamModel parseBeamModel(std::string_view name);

struct MapperOptions;
/// The vertical extent of the cone the volume model clears, radians: half the vertical aperture,
/// where the Gaussian two-way pattern is above −1.5 dB (g(e) = 4^−(2e/a)², 0.25 at the −3 dB
/// edges). A beam proves water only where it is loud: towards the aperture's edges a grazing
/// seabed or surface returns too little to rise above the noise, and clearing the whole aperture
/// erased them (erosion on the simulated missions: docs/accuracy.md). The obstacle's face and the
/// carving of other beams' faces use the whole aperture.
double freeVerticalAperture_rad(const MapperOptions& options);
/// Whether the options' beam model maps the beam's volume (kVolume, kInversion): a 3D map with the
/// volume model's detection (loud echoes and extended returns) and level surfaces.
bool mapsBeamVolume(const MapperOptions& options);
/// Whether a beam without an obstacle clears (up to BeamDetection::echo_onset_m, where a return
/// below the obstacle threshold starts): the planar model yes (and it carves other beams' arcs up
/// to its BeamDetection::water_range_m), the volume model no. In 3D a beam's silence is no proof
/// of water: a seabed or wall met at grazing incidence returns only 1–3 dB above the noise per bin
/// over metres of range, below any obstacle threshold, and clearing there eroded 15 % of the
/// visible surface of the simulated tilted-loop mission and 7 % of the lawnmower's; the volume
/// model's free space comes from the beams that met something, up to it (docs/accuracy.md).
bool clearsWithoutObstacle(const MapperOptions& options);

/// OctoMap's defaults with lazy evaluation on.
inline OctreeOptions lazyOctreeOptions() {
  OctreeOptions options;
  options.lazy = true;
  return options;
}

/// The sonar mapper's octree: lazy, OctoMap's miss (0.4) and clamping (0.12 … 0.97), and a hit of
/// P(occupied | echo) = 0.9 (log-odds +2.2; OctoMap's laser default is 0.7, +0.85). A detection has
/// passed a threshold that noise crosses with probability 10⁻⁶ per bin (calibration.hpp),
/// so one echo outweighs the clamped free evidence of earlier sweeps (−2.0): the map follows a
/// target that moves in (the SeaNet sector log's) within a sweep, while a false echo is cleared
/// again by six sweeps that see water there.
inline OctreeOptions sonarOctreeOptions() {
  OctreeOptions options = lazyOctreeOptions();
  options.occupancy.prob_hit = 0.9;
  return options;
}

/// Everything that turns beams into map updates. Options left unset (nullopt) are derived from
/// each log or sweep: nothing here is tuned to one sonar.
struct MapperOptions {
  /// Voxel edge in metres, > 0. Unset: autoResolution_m() of the log's reach (mapSonarLog), or of
  /// the first sweep's reach (a SonarMapper fed sweeps directly).
  std::optional<double> resolution_m;
  /// Sensor model, aggregation, pruning (sonarOctreeOptions). Lazy: a sweep updates leaves only and
  /// the inner nodes are fixed once at its end (§5.5), so the map is consistent after every sweep.
  /// Every detected obstacle earns occupancy.prob_hit.
  OctreeOptions octree = sonarOctreeOptions();
  /// Bins nearer than this are zeroed before smoothing and detection (paper §8.1: reflections from
  /// the vehicle and the transducer's ringing), metres, ≥ 0. Unset: the near-field clutter extent
  /// estimated on each sweep (estimateNearField, detection/calibration.hpp).
  std::optional<double> self_reflection_range_m;
  /// Longest range a beam is used to, metres (OctoMap's maxrange): a beam reaching farther clears
  /// free space up to max_range_m only, and an obstacle beyond it is dropped. The default is the
  /// longest range of mechanically scanned sonars (Tritech SeaKing: 300 m), so real logs are
  /// untouched while a log declaring kilometre-long bins cannot make the mapper walk billions of
  /// voxels. > 0; +inf: no limit.
  double max_range_m = 300.0;
  SmoothingOptions smoothing{};  ///< polar-image smoothing (paper §8.1), physical units
  DetectorOptions detector{};    ///< first-obstacle detection (paper §8.2, §9), physical units
  RayAlgorithm ray = RayAlgorithm::kDDA;
  /// Horizontal beam width in radians (Tritech Micron and SeaKing: 3°, Ping360: 2°), in [0, π).
  /// Each beam clears its wedge up to the detected range and its obstacle is the arc at that range
  /// across the width, less where other beams saw water beyond it — the MSIS inverse sensor model.
  /// The sweep's wedges are cast together as one fan of rays at most one voxel apart
  /// (sweep_fan.hpp). 0 casts one ray per bearing (paper §6).
  double beam_width_rad = 3.0 * std::numbers::pi / 180.0;
  /// Planar (a 2D map in the sonar's plane) or the whole beam volume (a 3D map).
  BeamModel beam_model = BeamModel::kPlanar;
  /// Vertical −3 dB beam width of the volume model, radians, in (0, π) (Tritech Micron 35°,
  /// SeaKing about 40°, Ping360 25°). Unused by the planar model.
  double vertical_aperture_rad = 35.0 * std::numbers::pi / 180.0;
  /// The water surface's depth in the navigation's NED frame, metres: 0 when the navigation's
  /// depth is a depth sensor's (nedToMap puts it at map z = 0). A level head's cone points both up
  /// and down, so its weak extended return could be the seabed's or the surface's; knowing where
  /// the surface is, a return whose onset is nearer than the surface can enter the cone (its height
  /// above the sonar over the sine of the aperture's upper edge's slope) comes from below: the
  /// seabed, traced from the aperture's lower edge (appendLevelTrace, sweep_fan.hpp). A sonar at or
  /// above that level gets no such trace: a static sonar at the map origin (mapSonarLog without
  /// navigation) keeps none. A cone that points only up meets the surface first on its top ray: an
  /// obstacle whose echo starts there, within the range tolerance, is the surface, traced on it
  /// (isLevelReturn, sweep_fan.hpp). NaN: unknown (navigation without a depth sensor); finite
  /// otherwise.
  double water_surface_depth_m = 0.0;
  /// The volume model seeks weak extended returns in the whole echo of each beam without an
  /// obstacle (a seabed or water surface met at grazing incidence; extended_returns.hpp) and places
  /// them on the level surface their onset implies (appendLevelTrace, sweep_fan.hpp), following the
  /// seabed's slope fitted to every weak seabed onset so far (SeabedSlope, seabed_slope.hpp); such
  /// a beam clears its cone's loud core up to the return's onset. Whole sweeps only: the live
  /// mapper's beams, detected a few at a time, use their first returns. These are the detector's
  /// false-alarm rates and windows (probabilities, looks, degrees).
  ExtendedReturnOptions extended{};
  /// The inversion model's parameters (BeamModel::kInversion).
  VolumeInversionOptions inversion{};
  /// Range tolerance of the inverse sensor model, metres, ≥ 0: a beam's free space ends this much
  /// before its obstacle, so the obstacle's range uncertainty (a bin, the pulse, a voxel) does not
  /// clear what the same surface gave in earlier sweeps; an arc point of the obstacle is dropped
  /// where another beam of the sweep saw water (up to its own leading edge) beyond it by more than
  /// this (planArcs, sweep_fan.hpp). Unset: one bin plus half a voxel for the arcs, and for the free
  /// space that plus each echo's rise (BeamDetection::rise_m: leading edge to peak).
  std::optional<double> range_tolerance_m;
  /// Work budget of one beam, in voxel updates: mapSonarLog refuses a log whose longest beam (at
  /// most max_range_m) would update more voxels than this at the map's resolution
  /// (estimateVoxelUpdatesPerBeam: its wedge, or its cone with the volume model), before mapping,
  /// naming the finest resolution that fits. It bounds the time and the working memory of each beam
  /// (a sweep's cell sets hold at most its beams' updates), not the log's length: a log of hours
  /// maps in time proportional to its beams. > 0; +inf: no limit. The default, 1e7, is over 40×
  /// what any sonar preset (sonar_presets.hpp) needs at its automatic resolution, planar or volume
  /// (at most 2.3e5: the 3° × 40° cone of a SeaKing at 30 m and 0.1 m; any head at about 256 voxels
  /// of reach needs at most 5e5), while 1 mm voxels on a 50 m Ping360 need 4.4e7 planar and 3.2e11
  /// in volume.
  double max_voxel_updates_per_beam = 1e7;
  /// mapSonarLog: clean and detect sweep i+1 on a second thread while sweep i is integrated. The
  /// map is the same either way (detection does not depend on the map).
  bool pipeline_detection = true;
  /// Threads that trace a sweep's free rays (each its share into its own cell set, then merged),
  /// ≥ 1. The map is identical for any count; the tree updates stay on one thread.
  unsigned threads = 1;

  /// @throws ValueError naming the option for a resolution that is set but not finite and > 0, a
  ///         self-reflection range or range tolerance that is set but not finite and ≥ 0, a max
  ///         range that is NaN or ≤ 0, a beam width outside [0, π), a per-beam budget that is NaN or ≤ 0,
  ///         invalid smoothing, detector or extended-return options, invalid occupancy parameters, or 0 threads.
  void validate() const;
};

/// The default map resolution for a sonar reaching `reach_m`: about 256 voxels from the sonar to
/// the end of its beams (reach / 256), rounded to the nearest of 1, 2, 5 × 10^k metres, and never
/// below 1 mm. Tritech Micron at 5 m: 0.02 m (the paper's); SeaKing at 30 m: 0.1 m; Ping360 at
/// 50 m: 0.2 m. Cost and detail then do not depend on the range scale: a 360° sweep touches about
/// π · 256² ≈ 2 × 10⁵ cells of its plane whatever the sonar.
/// @throws ValueError when reach_m is not finite and > 0.
double autoResolution_m(double reach_m);

/// The reach of a log: its longest beam (bins × bin length), at most max_range_m, metres;
/// 0 for a log without beams.
double logReach_m(const SonarLog& log, double max_range_m);
/// The same of a surveyed log.
double logReach_m(const LogSurvey& survey, double max_range_m);

/// The automatic resolution of a log and what it follows.
struct AutoResolution {
  double resolution_m = 0.0;  ///< voxel edge, metres
  RangeScale scale;           ///< the range scale it follows (its reach at most max_range_m)
  std::size_t scales = 0;     ///< range scales (bin lengths) in the log
  std::size_t beams = 0;      ///< beams in the log
  bool coarsened = false;     ///< coarser than the scale's own, to fit MapperOptions::max_voxel_updates_per_beam
};

/// The resolution mapSonarLog uses when MapperOptions::resolution_m is unset: autoResolution_m of
/// the reach of the range scale most beams use (mostUsedRangeScale, range_scales.hpp; at most
/// max_range_m), so a log mostly recorded at 10 m maps at 5 cm although it opens with a Ping360's
/// power-on pings at 2 m and the user looked out to 20 m for a while. When the log's longest beam
/// at it would exceed max_voxel_updates_per_beam (estimateVoxelUpdatesPerBeam), the next coarser of
/// 1, 2, 5 × 10^k m that fits, but never coarser than autoResolution_m of the log's longest reach
/// (checkWorkBudget then says what fits). A log of one range scale: autoResolution_m(logReach_m).
/// @throws ValueError when options are invalid or no beam of the log has bins.
AutoResolution autoResolutionForLog(const SonarLog& log, const MapperOptions& options);
/// The same for a surveyed log (log_survey.hpp).
AutoResolution autoResolutionForLog(const LogSurvey& survey, const MapperOptions& options);

/// `options` with every "auto" the mapper needs before the first sweep resolved for `log`:
/// resolution_m (autoResolutionForLog). Other options are unchanged.
/// @throws ValueError when options are invalid, or the resolution is auto and the log has no beam.
MapperOptions resolveForLog(const MapperOptions& options, const SonarLog& log);
/// The same for a surveyed log.
MapperOptions resolveForLog(const MapperOptions& options, const LogSurvey& survey);

/// Upper estimate of the voxel updates of one beam reaching `range_m` (metres, > 0; at most
/// options.max_range_m is used) mapped with `options` (resolution_m set, metres): the planar model
/// clears its wedge, beam width × range² / 2 over the voxel's area, plus its line of range / voxel
/// voxels; the volume model its free cone, beam width × free vertical aperture × range³ / 3 over
/// the voxel's volume, plus the shell of its whole vertical aperture, aperture × range² over the
/// voxel's area. A beam narrower than a voxel at its end counts as a voxel wide. A Ping360 at 50 m:
/// 1.3e3 (planar) and 6.7e4 (volume) at its automatic 0.2 m.
/// @throws ValueError when options.resolution_m is unset or options are invalid, or range_m is
///         not finite and > 0.
double estimateVoxelUpdatesPerBeam(const MapperOptions& options, double range_m);

/// Lines for the user about options that cannot work with `log` (a minimum range, self-reflection
/// range or echo length beyond the log's reach, a maximum range that cuts its beams, a resolution
/// coarser than a quarter of the reach, smoothing longer than half of it); each names the option
/// (MapperOptions field and command-line flag). Empty when nothing needs saying.
std::vector<std::string> optionWarnings(const MapperOptions& options, const SonarLog& log);
/// The same for a surveyed log.
std::vector<std::string> optionWarnings(const MapperOptions& options, const LogSurvey& survey);

/// Throws when the log's longest beam (logReach_m, at most options.max_range_m) needs more voxel
/// updates (estimateVoxelUpdatesPerBeam at options.resolution_m, else the automatic resolution) than
/// options.max_voxel_updates_per_beam. Nothing to check for a log without bins.
/// @throws ValueError naming the estimate, the budget, the option that raises it
///         (max_voxel_updates_per_beam, `--max-voxel-updates-per-beam` on the command line), the
///         finest resolution that fits the budget and the automatic one.
void checkWorkBudget(const SonarLog& log, const MapperOptions& options);
/// The same for a surveyed log.
void checkWorkBudget(const LogSurvey& survey, const MapperOptions& options);

/// The options a log is mapped with: `options` resolved for it (resolveForLog) and its work budget
/// checked (checkWorkBudget). mapSonarLog maps with them; an OnlineMapper built with them and fed
/// the log's beams in order, every field of each Beam, gives mapSonarLog's map byte for byte. An
/// OnlineMapper given `options` with the resolution on "auto" knows only the beams so far: its
/// resolution follows its first sweep and coarsens as a longer range scale comes (SonarMapper),
/// whereas a log's follows the range scale most of its beams use, known only once it has ended.
/// @throws ValueError as resolveForLog and checkWorkBudget.
MapperOptions mappingOptionsForLog(const MapperOptions& options, const LogSurvey& survey);
/// The same for a log held whole.
MapperOptions mappingOptionsForLog(const MapperOptions& options, const SonarLog& log);

}  // namespace sonarmap
