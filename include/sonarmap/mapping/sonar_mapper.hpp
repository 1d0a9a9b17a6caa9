#pragma once
/// @file sonar_mapper.hpp
/// Builds an occupancy octree from MSIS sweeps (paper §6 and §8): each beam's polar row is
/// cleaned and searched for its first obstacle; the cells from the sonar to that obstacle are
/// updated free (misses) and the obstacle's cell occupied with a confidence from its intensity.
///
/// A sweep is integrated like one scan of OctoMap's `insertPointCloud`: every cell is updated at
/// most once per sweep, and a cell that is an obstacle of any beam of the sweep is not also
/// updated free by another beam. Beams are placed in the map frame by the sonar's pose: one pose for
/// the whole sweep (a static vehicle), or one per beam (a moving vehicle: a Micron turn takes
/// ~8.6 s), e.g. interpolated from navigation fixes at each beam's time (mapSonarLog with a NavTrack).

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/core/progress.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/detection/detection.hpp"
#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/sonar/polar_image.hpp"
#include "sonarmap/sonar/preprocess.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap {


/// Counts gathered while mapping.
struct MappingStats {
  std::size_t sweeps = 0;
  std::size_t beams_used = 0;            ///< beams integrated into the map
  std::size_t beams_skipped = 0;         ///< malformed beams the reader dropped
  std::size_t obstacles = 0;             ///< beams with an obstacle
  std::size_t free_updates = 0;          ///< cells updated free (after per-sweep deduplication)
  std::size_t occupied_updates = 0;      ///< cells updated occupied
  std::size_t out_of_map = 0;            ///< beams whose end lies outside the map (skipped)
  std::size_t beams_clipped = 0;         ///< beams longer than max_range_m (used up to it, obstacle dropped)
  std::size_t beams_without_nav = 0;     ///< beams without a pose: their time lies outside the navigation (skipped)
  /// Times an automatic resolution grew with a longer range scale (SonarMapper::resolveResolution).
  std::size_t resolution_changes = 0;
  /// Beams of a head setting (range scale, gain) used for fewer than the detector's min_beams beams
  /// in a row, before any whole sweep of that setting calibrated it: too few bearings to measure a
  /// background on (skipped; OnlineMapper).
  std::size_t beams_uncalibrated = 0;
  /// Beams without an obstacle that clear nothing (clearsWithoutObstacle: the volume model's):
  /// not in beams_used.
  std::size_t beams_without_evidence = 0;
  /// Beams mapped as an extended return by the volume model, in beams_used: without an
  /// obstacle, a weak return whose whole echo held one (a grazing seabed or water surface) up to the
  /// beam's water range; with one, a return isLevelReturn calls level (then not in obstacles). Each
  /// clears its cone up to the return's onset; one whose aperture points only down or only up maps
  /// it on its level (appendLevelTrace).
  std::size_t extended_returns = 0;
  /// Why beams found no obstacle, summed over the sweeps detected by this mapper (detectors.hpp).
  DetectionDiagnostics detection;
  /// The last detected sweep's calibration (calibration.hpp): what the mapper derived from the log,
  /// and the range of minimum ranges the sweeps used. Metres, dB.
  struct Calibration {
    double band_end_m = 0.0;        ///< end of the self-reflection band
    double near_field_end_m = 0.0;  ///< end of the near-field clutter
    double min_range_m = 0.0;       ///< the detector's minimum range (the option, or the near field's end)
    double threshold_db = 0.0;      ///< the echo threshold above the background
    double span_db = 0.0;           ///< the intensity scale's dB span used
    /// The lowest and highest minimum range over every detected sweep (each sweep calibrates its
    /// own); both 0 before the first sweep.
    double min_range_lowest_m = 0.0;
    double min_range_highest_m = 0.0;
    std::size_t sweeps_detected = 0;  ///< sweeps whose calibration this holds
  } calibration;
  /// The largest |x|, |y| or |z| of a point a beam reached (sonar or wedge end), map frame, metres:
  /// what the map must span (mappingWarnings suggests a resolution from it).
  double farthest_m = 0.0;
};

/// Lines for the user about a finished mapping (the library never prints; `sonarmap map` does):
/// no obstacle, or far fewer obstacles than echoes suggest, with the likely cause (the minimum range
/// beyond the echoes, echoes shorter than the minimum echo length); most beams outside the map,
/// with the resolution that would fit (the map spans ±32768 voxels from its origin); beams beyond
/// the maximum range; beams without navigation. Empty when nothing needs saying.
std::vector<std::string> mappingWarnings(const MappingStats& stats, const MapperOptions& options, double resolution_m);

/// Maps sweeps of one sonar into an occupancy octree (depth 16, OctoMap's layout).
class SonarMapper {
 public:
  /// @throws ValueError when `options` is invalid (MapperOptions::validate).
  explicit SonarMapper(const MapperOptions& options = {});
  SonarMapper(SonarMapper&&) noexcept;
  SonarMapper& operator=(SonarMapper&&) noexcept;
  ~SonarMapper();

  /// Calibrates, cleans and searches the polar image of one sweep: the calibration (calibration.hpp)
  /// on the image as recorded, self-reflection removal (up to the option, or the calibrated band's
  /// end) and smoothing in place, then first-obstacle detection (one per row) with the calibration
  /// (recomputed on the smoothed image when smoothing, the near field kept). Thread-safe: touches no
  /// mapper state.
  SweepDetection detectSweep(PolarImage& polar) const;

  /// detectSweep(polar).detections.
  std::vector<BeamDetection> detect(PolarImage& polar) const;
  /// Cleans and searches a few beams of a sweep in progress (live mapping's provisional beams:
  /// OnlineMapper with OnlineIntegration::kProvisionalBeams) with `calibration`, what an earlier sweep was detected with
  /// (SweepDetection::calibration): self-reflection removal up to the option or its band's end,
  /// smoothing (each call's rows alone), detection by detectRows (detectors.hpp): its background is
  /// not measured again. `rows` must have the calibration's columns. Thread-safe as detectSweep.
  /// @throws ValueError  as detectRows.
  SweepDetection detectRows(PolarImage& rows, const SweepCalibration& calibration) const;

  /// Adds a sweep's diagnostics to stats().detection and keeps its calibration in
  /// stats().calibration (mapSweep and mapSonarLog call it for every sweep they detect).
  void recordDetection(const SweepDetection& detection);

  /// Cleans and searches the polar image of one sweep (self-reflection removal, smoothing,
  /// detection) and integrates it. `polar` is modified in place: afterwards it holds the image
  /// the detector saw. @param sonar_to_map pose of the sonar frame in the map frame.
  std::vector<BeamDetection> mapSweep(PolarImage& polar, const Eigen::Isometry3d& sonar_to_map = Eigen::Isometry3d::Identity());

  /// Integrates one sweep whose detections are already known (one per polar row).
  /// @throws ValueError when `detections` and the polar image differ in length.
  void integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                      const Eigen::Isometry3d& sonar_to_map = Eigen::Isometry3d::Identity());

  /// Integrates one sweep of a moving sonar: row r is placed with `sonar_to_map_per_row[r]` (the
  /// sonar's pose in the map frame at the beam's time). Consecutive beams whose poses move any
  /// point of their reach by at most a quarter voxel share one fan of rays (sweep_fan.hpp), so a
  /// static sweep is planned once and maps exactly as the single-pose overload; a moving one is
  /// planned group by group (moving at 0.1 m/s with 2 cm voxels: about one beam per group), which
  /// casts the overlap of neighbouring wedges twice (the cells are still updated once per sweep).
  /// @throws ValueError when `detections` or the poses differ in length from the polar image.
  void integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                      const std::vector<Eigen::Isometry3d>& sonar_to_map_per_row);

  /// As above; a row whose pose is nullopt (no navigation at its time) is skipped and counted in
  /// stats().beams_without_nav.
  /// @throws ValueError when `detections` or the poses differ in length from the polar image.
  void integrateSweep(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                      const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map_per_row);

  /// As the overload above for a few beams of a sweep in progress (live mapping's provisional
  /// beams: ProvisionalBeams): the same updates for these rows, but a cell is updated at most once per call,
  /// not once per sweep (neighbouring calls' wedges overlap), and no sweep is counted.
  /// @throws ValueError when `detections` or the poses differ in length from the polar image.
  void integrateBeams(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                      const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map_per_row);
  /// Integrates what the mapper still holds: the inversion model's last window of beams
  /// (volume_inversion.hpp); nothing for the other models. mapSonarLog and OnlineMapper::finish
  /// call it; the map is final afterwards.
  void finish();
  const OcTree16& map() const { return map_; }
  OcTree16& map() { return map_; }
  const MappingStats& stats() const { return stats_; }
  MappingStats& stats() { return stats_; }
  const MapperOptions& options() const { return options_; }

 private:
  /// With an automatic resolution (MapperOptions::resolution_m unset at construction), fixes it
  /// from the first sweep's reach (autoResolution_m) and starts the (still empty) map at that
  /// resolution; a later sweep of a longer range scale, whose autoResolution_m is coarser, coarsens
  /// the map so far to it (resampledMap, algorithms/resample.hpp; counted in
  /// MappingStats::resolution_changes). Never finer. mapSonarLog resolves the resolution for the
  /// whole log first (autoResolutionForLog), so this applies to mappers fed beam by beam (live).
  void resolveResolution(const PolarImage& polar);
  /// MapperOptions::range_tolerance_m, or the sweep's part of its automatic value: a bin plus half a
  /// voxel (each echo's rise is added per beam).
  double rangeTolerance_m(const PolarImage& polar) const;
  /// integrateSweep's body: `pose_of(row)` is the row's pose, or null to skip it without navigation;
  /// `whole_sweep`: count a sweep (false for integrateBeams).
  template <class PoseOfRow>
  void integrateRows(const PolarImage& polar, const std::vector<BeamDetection>& detections, PoseOfRow&& pose_of,
                     bool whole_sweep);
  /// integrateSweep and integrateBeams with optional poses; `whole_sweep` counts a sweep.
  void integratePosedRows(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                          const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map_per_row, bool whole_sweep);
  /// The volume model: adds the seabed onsets of work_->beams to the mission's (SeabedSlope) and
  /// sets each seabed trace's normal from them (PlannedBeam::trace_normal); then checkLoudTraces.
  void placeSeabedTraces();
  /// Turns back into obstacles the sweep's loud traces whose onset lies above the seabed measured
  /// so far (sweep_plan.cpp).
  void checkLoudTraces();
  /// The volume model: every posed beam's looks at the level surfaces (level_surfaces.hpp: the
  /// seabed fitted so far, the water surface at its depth), and the columns they have now heard
  /// as occupied cells.
  /// The inversion model: also adds every posed beam, with the level planes its looks went to, to
  /// the inversion's window.
  template <class PoseOfRow>
  void addLevelSurfaceLooks(const PolarImage& polar, const std::vector<BeamDetection>& detections, PoseOfRow&& pose_of);
  /// Plans work_->beams into work_->rays and hit_points, one fan per group of nearby poses.
  void planBeams();
  /// The beams' shape: the width, and the vertical aperture with the volume model (0: planar).
  BeamShape beamShape() const;
  /// True when the sonar and the beam's wedge lie inside the map; records how far it reached.
  bool beamInsideMap(const PlannedBeam& beam);
  /// Turns the sweep's plan into keys: the key box, and the hit cells in tree order (Morton code),
  /// one per cell with the largest weight among its arc points.
  void keySweep();
  /// Updates every cell the planned rays cross once, free, unless it is a hit cell of the sweep.
  void integrateFreeCells();
  /// Updates every hit cell of the sweep once, in tree order; the volume model also records them.
  void integrateHits();

  struct SweepWork;  // the sweep's plan and cells, reused from sweep to sweep

  MapperOptions options_;
  bool auto_resolution_ = false;  ///< resolution_m was unset at construction
  OcTree16 map_;
  MappingStats stats_;
  std::unique_ptr<SweepWork> work_;
  std::unique_ptr<VolumeInversion> inversion_;  ///< the inversion model's window of beams
};

// Progress callbacks (core/progress.hpp) count sweeps here: (sweeps done, sweeps in total).


/// Maps every sweep of `log` (split where the head completes a turn or reverses, short fragments
/// joined to their neighbour) with the sonar static at the map origin, options left on "auto"
/// resolved for the log (resolveForLog). `stats().beams_skipped` includes the reader's skipped
/// beams; mappingWarnings() says what went wrong when few or no obstacles were found.
/// @throws ValueError for invalid options, a sweep that mixes bin lengths, a log whose longest beam
///         needs more voxel updates than options.max_voxel_updates_per_beam (checkWorkBudget, before
///         mapping), or when no beam could be mapped because every one reaches outside the map (naming the resolution that fits).
SonarMapper mapSonarLog(const SonarLog& log, const MapperOptions& options = {}, const ProgressCallback& progress = {});

/// Maps every sweep of `log` (split and detected as above) from a moving vehicle: each beam is
/// placed with the sonar's pose at its time, nedToMap() · bodyToNed(t) · sonar_to_body, where
/// bodyToNed(t) is interpolated from `nav` (interpolateBodyToNed, navigation.hpp; O(log fixes) per
/// beam). Beams whose time lies outside [first fix, last fix] are skipped and counted in
/// `stats().beams_without_nav`. A constant track at the NED origin with the default mounting
/// (upright, aligned: sonar_to_body = diag(1, −1, −1)) gives the same map as the overload above.
/// @param nav            navigation fixes on the beams' clock (NED, body FRD; navigation.hpp).
/// @param sonar_to_body  the sonar's mounting: sonar frame (beam.hpp) → body frame (FRD).
/// @throws ValueError for invalid options, a sweep that mixes bin lengths, or a navigation track
///         that is empty, non-finite or not strictly increasing in time.
SonarMapper mapSonarLog(const SonarLog& log, const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body,
                        const MapperOptions& options = {}, const ProgressCallback& progress = {});

/// The detector's smallest sweep for `options` (BackgroundOptions::min_beams, at least 1): the
/// `min_beams` a log is surveyed with for mapSonarLog's progress (surveyLog).
std::size_t surveyMinBeams(const MapperOptions& options);

/// mapSonarLog for a log read beam by beam: `source`'s beams from its first (rewind()), surveyed as
/// `survey` (surveyLog over it with surveyMinBeams(options)), give the map of mapSonarLog on the
/// log held whole, byte for byte, holding one beam at a time besides the map and the sweeps being
/// detected. The resolution and the work budget need no pass of their own (autoResolutionForLog and
/// checkWorkBudget use the survey). `stats().beams_skipped` is the source's count after the pass.
/// @throws as mapSonarLog(log, ...), and what the source throws.
SonarMapper mapSonarLog(BeamSource& source, const LogSurvey& survey, const MapperOptions& options = {},
                        const ProgressCallback& progress = {});
/// The same from a moving vehicle (as mapSonarLog(log, nav, sonar_to_body, ...)).
SonarMapper mapSonarLog(BeamSource& source, const LogSurvey& survey, const NavTrack& nav,
                        const Eigen::Isometry3d& sonar_to_body, const MapperOptions& options = {},
                        const ProgressCallback& progress = {});

}  // namespace sonarmap
